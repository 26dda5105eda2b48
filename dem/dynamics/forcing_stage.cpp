// Stage: drift forces on every dynamic body (skin drag on the bottom, air drag on the top).
#include "dynamics/world.h"

namespace polyfloe::dynamics {

void World::drift_forces() {
  const forcing::DriftSettings& s = settings_.drift;
  if (!s.skin_drag && !s.air_drag) return;
  const std::size_t n = size();
  for (std::size_t i = 0; i < n; ++i)
    if (is_dynamic_[i]) force_[i] += forcing::drift_force(s, plan_area_[i], vel_eval_[i]);
}

}  // namespace polyfloe::dynamics
