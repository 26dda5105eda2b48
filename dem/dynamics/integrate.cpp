// Stage: velocity-Verlet kicks and drift, and the world-frame shapes that follow the bodies.
#include <cmath>

#include "dynamics/world.h"

namespace polyfloe::dynamics {

void World::kick(double half_dt) {
  const std::size_t n = size();
  for (std::size_t i = 0; i < n; ++i) {
    vel_[i] += (half_dt * inv_mass_[i]) * force_[i];
    omega_[i] += half_dt * inv_inertia_[i] * torque_[i];
  }
}

void World::drift(double dt) {
  const std::size_t n = size();
  for (std::size_t i = 0; i < n; ++i) {
    if (motion_[i] == Motion::fixed) continue;
    pos_[i] += dt * vel_[i];
    yaw_[i] += dt * omega_[i];
  }
}

void World::update_shape(int i) {
  const double c = std::cos(yaw_[i]), s = std::sin(yaw_[i]);
  const auto& local = shape_[i]->vertices();
  Vec2* out = world_xy_.data() + vert_off_[i];
  geometry::Aabb box{pos_[i], pos_[i]};
  for (std::size_t k = 0; k < local.size(); ++k) {
    out[k] = pos_[i] + geometry::rotate(local[k], c, s);
    box.lo = box.lo.cwiseMin(out[k]);
    box.hi = box.hi.cwiseMax(out[k]);
  }
  boxes_[i] = box;
}

void World::update_shapes() {
  const int n = static_cast<int>(size());
  for (int i = 0; i < n; ++i)
    if (motion_[i] != Motion::fixed) update_shape(i);
}

}  // namespace polyfloe::dynamics
