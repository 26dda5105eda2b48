// The World's drift model (dynamics/drift_model.h).
#include "dynamics/drift_model.h"

#include <utility>

namespace polyfloe::dynamics {

void DriftModel::resize(std::size_t n, bool clear) {
  if (clear)
    load_.assign(n, forcing::DriftLoad{});
  else
    load_.resize(n);
  inverse_dt_ = 0.0;
}

void DriftModel::restore(std::vector<forcing::DriftLoad> loads, std::vector<Vec2> linear_force,
                         std::vector<double> linear_torque) {
  load_ = std::move(loads);
  lin_force_ = std::move(linear_force);
  lin_torque_ = std::move(linear_torque);
  inverse_dt_ = 0.0;  // the drag matrices changed
}

}  // namespace polyfloe::dynamics
