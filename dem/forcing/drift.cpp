#include "forcing/drift.h"

#include <cmath>

namespace polyfloe::forcing {

Vec2 free_drift_velocity(const DriftSettings& s) {
  if (s.skin_drag && s.air_drag) {
    // Equal and opposite drags: u - u_c and u_a - u are parallel with |u - u_c| = k |u_a - u|.
    const double k = std::sqrt(s.air_density * s.air_drag_coefficient / (s.water_density * s.skin_drag_coefficient));
    return (s.current + k * s.wind) / (1.0 + k);
  }
  if (s.skin_drag) return s.current;
  if (s.air_drag) return s.wind;
  return {0.0, 0.0};
}

}  // namespace polyfloe::forcing
