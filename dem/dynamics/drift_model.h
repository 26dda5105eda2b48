// The World's drift model: what the step keeps of the drift forcing (wind, currents, Coriolis) between its
// stages, where drag and Coriolis are treated semi-implicitly (forcing::DriftTreatment::semi_implicit):
//
// - each body's drift load of the last evaluation with its damping matrix D (drag with the speed factors frozen
//   at the velocity it was evaluated at) and its Coriolis part m f;
// - that evaluation's linear model F_d(v) = b - D v, b = F_d(v*) + D v*: between full evaluations of the drift
//   forcing (forcing::DriftSettings::update_every) the loads come from it at each step's velocity;
// - the damped inverse of A = M + dt D_drag + dt/2 C (C = m f [[0, -1], [1, 0]]) per body, which the final kick
//   solves with (backward Euler for drag, the trapezoidal rule for Coriolis; dynamics/integrate.cpp), kept while
//   D and dt stay the same.
//
// Bodies are the World's indices. The model knows no geometry and no field: the forcing stage
// (dynamics/forcing_stage.cpp) writes the loads, the integrator reads them.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "dynamics/body.h"
#include "dynamics/rows.h"
#include "forcing/drift.h"
#include "geometry/vec2.h"

namespace polyfloe::dynamics {

using geometry::Vec2;

class DriftModel {
 public:
  // A body's velocity: translation and yaw rate.
  struct Velocity {
    Vec2 u;    // [m/s]
    double w;  // [rad/s]
  };
  // The inverse of A = M + dt D_drag + dt/2 C for one body as its adjugate (row-major) and 1/det(A); A is positive
  // definite (M > 0, D_drag >= 0, C antisymmetric), so the cofactor inverse is safe.
  struct DampedInverse {
    double adj[9];
    double inv_det;
  };
  static DampedInverse damped_inverse(const forcing::DriftLoad& d, double dt, double mass, double inertia);
  // A^-1 (p, p_w): the velocity v = (u, w) that solves A v = (p, p_w).
  static Velocity apply(const DampedInverse& a, const Vec2& p, double p_w);

  // --- the loads (one per body once the forcing stage has run; none before) ---
  std::size_t size() const { return load_.size(); }
  const forcing::DriftLoad& load(std::size_t i) const { return load_[i]; }
  forcing::DriftLoad& load(std::size_t i) { return load_[i]; }
  // Whether body i has a load with a damping matrix (and so is treated semi-implicitly).
  bool damped(std::size_t i) const { return i < load_.size() && load_[i].has_damping(); }
  // n loads, each to be written by the forcing stage; `clear`: all of them none (no drift forcing). The drag
  // matrices change: no inverse is kept.
  void resize(std::size_t n, bool clear);

  // --- the linear model ---
  // Whether this evaluation's loads come from the linear model: a function of the step count alone (restarts keep
  // it), and never on the first evaluation or after a change from outside (dt = 0: compute_forces anew).
  bool linear_step(const forcing::DriftSettings& s, std::uint64_t steps, double dt, std::size_t n) const {
    return s.update_every > 1 && s.treatment == forcing::DriftTreatment::semi_implicit && dt > 0.0 &&
           steps % static_cast<std::uint64_t>(s.update_every) != 0 && load_.size() == n && lin_force_.size() == n &&
           lin_torque_.size() == n;
  }
  bool has_linear_model(std::size_t i) const { return i < lin_force_.size(); }
  // Sizes the linear model for n bodies (bodies without drift damping keep b = 0, never read).
  void resize_linear_model(std::size_t n) {
    lin_force_.resize(n, Vec2{0.0, 0.0});
    lin_torque_.resize(n, 0.0);
  }
  // Body i's linear model from its load evaluated at velocity (u, w): b = F_d + D (u, w).
  void fit_linear_model(std::size_t i, const Vec2& u, double w) {
    const forcing::DriftLoad& d = load_[i];
    const Eigen::Vector3d dv = d.damping_times(u, w);
    lin_force_[i] = d.force + dv.head<2>();
    lin_torque_[i] = d.torque + dv.z();
  }
  // Body i's load from the linear model at velocity (u, w): force, torque = b - D (u, w).
  void set_linear_load(std::size_t i, const Vec2& u, double w) {
    forcing::DriftLoad& d = load_[i];
    const Eigen::Vector3d dv = d.damping_times(u, w);
    d.force = lin_force_[i] - dv.head<2>();
    d.torque = lin_torque_[i] - dv.z();
  }

  // --- the final kick ---
  // Body i's velocity after the final kick of a step of dt, from its half-kicked velocity (v, w), its total force
  // and torque at the end of the step (its load included) and `a`, its damped inverse for dt:
  //   M v_new = M v + dt/2 F_o + dt (b - D v_new) - dt/2 C v_new,  F_o = force - load.
  Velocity implicit_velocity(std::size_t i, double dt, const DampedInverse& a, double mass, double inertia,
                             const Vec2& v, double w, const Vec2& force, double torque) const {
    const forcing::DriftLoad& d = load_[i];
    const double half_dt = 0.5 * dt;
    return apply(a, mass * v + half_dt * (force - d.force) + dt * lin_force_[i],
                 inertia * w + half_dt * (torque - d.torque) + dt * lin_torque_[i]);
  }
  // Makes room for n kept inverses; whether they must be computed anew for dt (dt > 0 and none kept for it).
  bool begin_inverses(std::size_t n, double dt) {
    inverse_.resize(n);
    return dt > 0.0 && inverse_dt_ != dt;
  }
  // Keeps body i's inverse for dt.
  void keep_inverse(std::size_t i, double dt, double mass, double inertia) {
    inverse_[i] = damped_inverse(load_[i], dt, mass, inertia);
  }
  const DampedInverse& kept_inverse(std::size_t i) const { return inverse_[i]; }
  // The kept inverses hold for dt from now (0: none held).
  void set_inverses_dt(double dt) { inverse_dt_ = dt; }
  // Body i's damped inverse for dt: the kept one where it holds, else computed.
  DampedInverse inverse_of(std::size_t i, double dt, double mass, double inertia) const {
    return dt == inverse_dt_ ? inverse_[i] : damped_inverse(load_[i], dt, mass, inertia);
  }
  // A body was added or the bodies' loads were replaced from outside: no inverse is kept.
  void forget_inverses() { inverse_dt_ = 0.0; }

  // The World stored its n bodies anew: body k is body from[k] of before. (Arrays not yet sized for every body are
  // first sized with no load and no linear model, which is what the ones missing mean.)
  void permute(std::span<const int> from) {
    const std::size_t n = from.size();
    if (!load_.empty() && load_.size() < n) load_.resize(n);
    if (!lin_force_.empty() && lin_force_.size() < n) {
      lin_force_.resize(n, Vec2{0.0, 0.0});
      lin_torque_.resize(n, 0.0);
    }
    gather_rows(load_, from);
    gather_rows(lin_force_, from);
    gather_rows(lin_torque_, from);
    if (inverse_.size() == n)
      gather_rows(inverse_, from);
    else
      forget_inverses();
  }

  // --- state (WorldState's drift_load, lin_force, lin_torque) ---
  const std::vector<forcing::DriftLoad>& loads() const { return load_; }
  const std::vector<Vec2>& linear_force() const { return lin_force_; }
  const std::vector<double>& linear_torque() const { return lin_torque_; }
  void restore(std::vector<forcing::DriftLoad> loads, std::vector<Vec2> linear_force,
               std::vector<double> linear_torque);

 private:
  std::vector<forcing::DriftLoad> load_;
  std::vector<Vec2> lin_force_;     // b of the linear model, force [N]
  std::vector<double> lin_torque_;  // and torque [N m]
  // Each damped body's inverse for the drag matrix it has now and the step inverse_dt_ [s] (0: none kept).
  std::vector<DampedInverse> inverse_;
  double inverse_dt_ = 0.0;
};

inline DriftModel::DampedInverse DriftModel::damped_inverse(const forcing::DriftLoad& d, double dt, double mass,
                                                            double inertia) {
  const double half_dt = 0.5 * dt;
  const double a00 = mass + dt * d.dxx, a01 = dt * d.dxy - half_dt * d.mf, a02 = dt * d.dxw;
  const double a10 = dt * d.dxy + half_dt * d.mf, a11 = mass + dt * d.dyy, a12 = dt * d.dyw;
  const double a20 = dt * d.dxw, a21 = dt * d.dyw, a22 = inertia + dt * d.dww;
  const double c00 = a11 * a22 - a12 * a21, c01 = a12 * a20 - a10 * a22, c02 = a10 * a21 - a11 * a20;
  // x = A^-1 f via the adjugate (transposed cofactors).
  return {{c00, a02 * a21 - a01 * a22, a01 * a12 - a02 * a11,  //
           c01, a00 * a22 - a02 * a20, a02 * a10 - a00 * a12,  //
           c02, a01 * a20 - a00 * a21, a00 * a11 - a01 * a10},
          1.0 / (a00 * c00 + a01 * c01 + a02 * c02)};
}

inline DriftModel::Velocity DriftModel::apply(const DampedInverse& a, const Vec2& f1, double f2) {
  const double* m = a.adj;
  return {{(m[0] * f1.x() + m[1] * f1.y() + m[2] * f2) * a.inv_det,
           (m[3] * f1.x() + m[4] * f1.y() + m[5] * f2) * a.inv_det},
          (m[6] * f1.x() + m[7] * f1.y() + m[8] * f2) * a.inv_det};
}

}  // namespace polyfloe::dynamics
