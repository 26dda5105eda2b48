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

// The final half kick with drag and Coriolis implicit: their load is linear in v = (u, omega) once each sample's
// speed factor is frozen at the predicted velocity v*, F_d(v) = F_d(v*) - D (v - v*), so
//   (M + h D) v_new = M v + h (F + D v*),   F the total force evaluated at v*.
// With the explicit first half kick this is the trapezoidal rule on the linearised drag: A-stable, and an exact
// rotation (Cayley) for Coriolis. The stored force is brought to v_new so the next first kick starts from it.
void World::kick_semi_implicit(double h) {
  const std::size_t n = size();
  for (std::size_t i = 0; i < n; ++i) {
    const forcing::DriftLoad& d = drift_load_[i];  // sized by drift_forces() in compute_forces()
    if (!is_dynamic_[i] || !d.has_damping()) {
      vel_[i] += (h * inv_mass_[i]) * force_[i];
      omega_[i] += h * inv_inertia_[i] * torque_[i];
      continue;
    }
    // A = M + h D = [[a, -b, p], [b, a, q], [p, q, r]]: eliminate the (u_x, u_y) block B = [[a, -b], [b, a]]
    // (B^-1 = [[a, b], [-b, a]] / (a^2 + b^2)); the Schur complement r - a (p^2 + q^2) / (a^2 + b^2) > 0 since
    // M + h D is positive definite.
    const double m = mass_[i], a = m + h * d.c, b = h * d.mf, p = h * d.cx, q = h * d.cy,
                 r = inertia_[i] + h * d.crr;
    const Vec2& vs = vel_eval_[i];
    const double ws = omega_eval_[i];
    // rhs = M v + h (F + D v*)
    const double dvx = d.c * vs.x() - d.mf * vs.y() + d.cx * ws;
    const double dvy = d.mf * vs.x() + d.c * vs.y() + d.cy * ws;
    const double dvw = d.cx * vs.x() + d.cy * vs.y() + d.crr * ws;
    const double f1x = m * vel_[i].x() + h * (force_[i].x() + dvx);
    const double f1y = m * vel_[i].y() + h * (force_[i].y() + dvy);
    const double f2 = inertia_[i] * omega_[i] + h * (torque_[i] + dvw);
    const double inv_det = 1.0 / (a * a + b * b);
    // B^-1 f1 and B^-1 P
    const double gx = (a * f1x + b * f1y) * inv_det, gy = (-b * f1x + a * f1y) * inv_det;
    const double hx = (a * p + b * q) * inv_det, hy = (-b * p + a * q) * inv_det;
    const double w_new = (f2 - p * gx - q * gy) / (r - p * hx - q * hy);
    const Vec2 u_new{gx - hx * w_new, gy - hy * w_new};
    // The force at the new velocity: F - D (v_new - v*).
    const Vec2 du = u_new - vs;
    const double dw = w_new - ws;
    force_[i] -= Vec2{d.c * du.x() - d.mf * du.y() + d.cx * dw, d.mf * du.x() + d.c * du.y() + d.cy * dw};
    torque_[i] -= d.cx * du.x() + d.cy * du.y() + d.crr * dw;
    vel_[i] = u_new;
    omega_[i] = w_new;
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
  rotation_[i] = {c, s};
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
