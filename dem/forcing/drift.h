// Drift forcing, minimal set: uniform current and wind; skin drag on the bottom (paper Eq. 13) and air drag on
// the top (Eq. 14), both quadratic in the velocity of the floe centre relative to the fluid.
// The full set (form drag, moment drag, quadrature, Coriolis, fields) is the [drift] work.
#pragma once

#include "geometry/vec2.h"

namespace polyfloe::forcing {

using geometry::Vec2;

struct DriftSettings {
  double water_density = 1025.0;         // rho_w [kg/m^3]
  Vec2 current{0.0, 0.0};                // u_c [m/s]
  bool skin_drag = true;                 // Eq. 13 on/off
  double skin_drag_coefficient = 0.0055; // c_w [-]
  double air_density = 1.2;              // rho_a [kg/m^3]
  Vec2 wind{0.0, 0.0};                   // u_a [m/s]
  bool air_drag = true;                  // Eq. 14 on/off
  double air_drag_coefficient = 0.0012;  // c_a [-]
};

// -1/2 c rho A (u - u_f) |u - u_f|: quadratic drag of a face of area A [m^2] moving at u relative to a fluid at u_f.
inline Vec2 quadratic_drag(double coefficient, double density, double area, const Vec2& u, const Vec2& u_fluid) {
  const Vec2 rel = u - u_fluid;
  return (-0.5 * coefficient * density * area * rel.norm()) * rel;
}

// Skin drag + air drag on a floe with plan area A [m^2] moving at u [m/s].
inline Vec2 drift_force(const DriftSettings& s, double area, const Vec2& u) {
  Vec2 f{0.0, 0.0};
  if (s.skin_drag) f += quadratic_drag(s.skin_drag_coefficient, s.water_density, area, u, s.current);
  if (s.air_drag) f += quadratic_drag(s.air_drag_coefficient, s.air_density, area, u, s.wind);
  return f;
}

// Steady free-drift velocity under skin and air drag alone (both along one axis or not): solves
// rho_a c_a |u_a - u| (u_a - u) = rho_w c_w |u - u_c| (u - u_c): u = (u_c + k u_a) / (1 + k),
// k = sqrt(rho_a c_a / (rho_w c_w)) [m/s].
Vec2 free_drift_velocity(const DriftSettings& s);

}  // namespace polyfloe::forcing
