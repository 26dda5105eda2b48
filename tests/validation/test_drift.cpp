// Drift forcing (paper Eq. 9-14) against closed forms and hand-computed values. Each case is a row of
// docs/validation.md; the printed numbers are the ones quoted there.
//   1. free drift, skin + air drag only, current and wind along x: u - u_c = k (u_a - u), k = sqrt(rho_a c_a /
//      (rho_w c_w)), within 0.5 % (three floes: from rest, from ahead, thick);
//   2. free drift with Coriolis: steady speed and turning angle equal the root of the force balance
//      1/2 rho_a c_a |u_a - u| (u_a - u) - 1/2 rho_w c_w |u - u_c| (u - u_c) - rho_i h f k x u = 0 (Newton's method
//      here), within 0.5 %;
//   3. inertial oscillation (Coriolis only): period 2 pi / f and radius u0 / f within 0.1 % over 10 periods;
//   4. a square at rest in a uniform current, form drag only: force 1/2 C_d^F rho_w d L (|cos| + |sin|) U^2 along
//      the current and no torque, to 1e-10;
//   5. a square at rest in a linear shear current u = (G y, 0), skin drag only: torque -1/2 c_w rho_w G^2 a^5
//      (hand-integrated); every triangle rule has its sign and the error falls with the degree; with a current
//      that keeps w of one sign the integrand is a polynomial and the rules are exact to their degree; the floe
//      spins up at the quadrature's torque / inertia;
//   6. scaling: every length x2 at fixed velocities (rates, shear and f halved): every force x4, every moment x8
//      (to 1e-12) - the printed Eq. 12 (r_e^2) would scale like a force;
//   7. large steps: the semi-implicit treatment converges to case 2's balance at dt = 50 drag relaxation times
//      (to 1e-9), where the explicit one blows up;
//   7b. the fields are sampled where each term acts (side-face centres at half draft, bottom, top: hand values in a
//      field that varies across the floe and with depth), and a constant external push ends at the drag's terminal
//      velocity at every step size;
//   8. a symmetric floe at the centre of a solid-body vortex spins up towards the water's rotation without
//      overshoot and without drifting off (|u| < 1e-9 m/s).
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <random>
#include <stdexcept>
#include <string>

#include "dynamics/world.h"
#include "forcing/analytic_fields.h"
#include "test_support.h"

using namespace polyfloe;
using forcing::FieldKind;
using forcing::FieldSpec;
using geometry::Vec2;

namespace {

constexpr double kRhoIce = 920.0;

std::shared_ptr<const geometry::ConvexPolygon> rect(double w, double h) {
  return tsupport::shape_of({{-w / 2, -h / 2}, {w / 2, -h / 2}, {w / 2, h / 2}, {-w / 2, h / 2}});
}

std::shared_ptr<const forcing::VelocityField> uniform(const Vec2& v) {
  return forcing::make_field(FieldSpec::uniform(v));
}

forcing::DriftSettings skin_and_air(const Vec2& current, const Vec2& wind) {
  forcing::DriftSettings s = forcing::DriftSettings::none();
  s.skin_drag = s.air_drag = true;
  s.ocean = uniform(current);
  s.wind = uniform(wind);
  return s;
}

// Steady free drift with Coriolis, per unit area: Newton's method with a finite-difference Jacobian.
Vec2 coriolis_free_drift(const forcing::DriftSettings& s, const Vec2& uc, const Vec2& ua, double h) {
  const double f = s.coriolis_parameter(0.0);
  auto residual = [&](const Vec2& u) -> Vec2 {
    const Vec2 wa = ua - u, ww = u - uc;
    return 0.5 * s.air_density * s.air_drag_coefficient * wa.norm() * wa -
           0.5 * s.water_density * s.skin_drag_coefficient * ww.norm() * ww - kRhoIce * h * f * Vec2(-u.y(), u.x());
  };
  Vec2 u = forcing::free_drift_velocity(s, uc, ua);
  for (int it = 0; it < 100; ++it) {
    const Vec2 r = residual(u);
    Eigen::Matrix2d j;
    for (int k = 0; k < 2; ++k) {
      Vec2 e{0.0, 0.0};
      e(k) = 1e-7;
      j.col(k) = (residual(u + e) - residual(u - e)) / 2e-7;
    }
    const Vec2 du = j.lu().solve(-r);
    u += du;
    if (du.norm() < 1e-15) break;
  }
  return u;
}

TEST(Drift, SkinAndAirDragBringEveryFloeToTheClosedFormFreeDriftWithinHalfAPercent) {
  const Vec2 uc{0.2, 0.0}, ua{10.0, 0.0};
  dynamics::WorldSettings ws;
  ws.drift = skin_and_air(uc, ua);
  const forcing::DriftSettings& d = ws.drift;
  const double k = std::sqrt(d.air_density * d.air_drag_coefficient / (d.water_density * d.skin_drag_coefficient));
  const Vec2 closed = (uc + k * ua) / (1.0 + k);
  EXPECT_NEAR((forcing::free_drift_velocity(d, uc, ua) - closed).norm(), 0.0, 1e-15);
  dynamics::World w(ws);
  w.add_body({.id = 1, .shape = rect(10, 10), .position = {0.0, 0.0}});
  w.add_body(
      {.id = 2, .shape = rect(30, 12), .position = {0.0, 5000.0}, .velocity = {1.0, 0.5}, .angular_velocity = 0.05});
  w.add_body({.id = 3, .shape = rect(10, 10), .position = {0.0, -5000.0}, .velocity = {-0.3, 0.2}, .thickness = 3.0});
  for (int s = 0; s < 20000; ++s) w.step(10.0);  // 2e5 s; relaxation time ~1e3 s (3e3 s for the thick floe)
  for (int i = 0; i < 3; ++i) {
    const Vec2 u = w.velocities()[i];
    const double balance = ((u - uc) - k * (ua - u)).norm() / (u - uc).norm();
    const double err = (u - closed).norm() / closed.norm();
    std::printf(
        "free drift (skin + air), floe %d: u = (%.8f, %.2e) m/s, closed form %.8f m/s, |u - closed| / |u| = "
        "%.1e, balance residual %.1e\n",
        i + 1, u.x(), u.y(), closed.x(), err, balance);
    EXPECT_LT(err, 5e-3);
    EXPECT_LT(balance, 5e-3);
    EXPECT_NEAR(w.angular_velocities()[i], 0.0, 1e-9);
  }
}

TEST(Drift, FreeDriftWithCoriolisIsTheBalanceRootRightOfTheWindInTheNorthAndLeftInTheSouth) {
  for (const auto& [uc, ua, lat] :
       {std::tuple{Vec2(0.0, 0.0), Vec2(10.0, 0.0), 75.0}, std::tuple{Vec2(0.1, -0.05), Vec2(8.0, 6.0), 60.0},
        std::tuple{Vec2(0.0, 0.0), Vec2(10.0, 0.0), -70.0}}) {
    dynamics::WorldSettings ws;
    ws.drift = skin_and_air(uc, ua);
    ws.drift.coriolis = true;
    ws.drift.latitude = lat;
    dynamics::World w(ws);
    w.add_body({.id = 1, .shape = rect(20, 20)});
    for (int s = 0; s < 40000; ++s) w.step(10.0);  // 4e5 s: ~9 inertial periods, ~400 relaxation times
    const Vec2 u = w.velocities()[0];
    const Vec2 ref = coriolis_free_drift(ws.drift, uc, ua, 1.0);
    auto angle = [&](const Vec2& v) { return std::atan2(geometry::cross(ua, v), ua.dot(v)) * 180 / std::numbers::pi; };
    const double speed_err = std::abs(u.norm() - ref.norm()) / ref.norm();
    const double angle_err = std::abs(angle(u) - angle(ref)) / std::abs(angle(ref));
    std::printf(
        "free drift with Coriolis at %.0f deg: speed %.6f m/s (root %.6f), angle to the wind %.4f deg "
        "(root %.4f): errors %.1e, %.1e\n",
        lat, u.norm(), ref.norm(), angle(u), angle(ref), speed_err, angle_err);
    EXPECT_LT(speed_err, 5e-3);
    EXPECT_LT(angle_err, 5e-3);
    if (lat > 0) {
      EXPECT_LT(angle(u), -5.0) << "northern hemisphere: to the right of the wind";
    } else {
      EXPECT_GT(angle(u), 5.0) << "southern hemisphere: to the left of the wind";
    }
  }
}

TEST(Drift, InertialCircleHasPeriodTwoPiOverFRadiusUOverFAndKeepsTheSpeed) {
  dynamics::WorldSettings ws;
  ws.drift = forcing::DriftSettings::none();
  ws.drift.coriolis = true;
  ws.drift.latitude = 75.0;
  const double f = ws.drift.coriolis_parameter(0.0);
  const double u0 = 0.5, period = 2 * std::numbers::pi / f, radius = u0 / f;
  dynamics::World w(ws);
  w.add_body({.id = 1, .shape = rect(30, 20), .velocity = {u0, 0.0}});
  const double dt = 60.0;
  const int steps = static_cast<int>(std::ceil(10 * period / dt));
  std::vector<double> crossings;  // upward zero crossings of u_y ... u_y = -u0 sin(f t): downward at t = 0
  std::vector<Vec2> pos;
  double uy_prev = w.velocities()[0].y();
  for (int s = 0; s < steps; ++s) {
    w.step(dt);
    const double uy = w.velocities()[0].y();
    if (uy_prev > 0.0 && uy <= 0.0) crossings.push_back(w.time() - dt * uy / (uy - uy_prev));
    uy_prev = uy;
    pos.push_back(w.positions()[0]);
  }
  ASSERT_GE(crossings.size(), 9u);
  const double measured_period = (crossings.back() - crossings.front()) / static_cast<double>(crossings.size() - 1);
  // Centre of the circle: x0 + (0, -u0 / f) for clockwise motion (f > 0) starting along +x.
  const Vec2 centre{0.0, -radius};
  double r_min = 1e300, r_max = 0.0;
  for (const Vec2& p : pos) {
    r_min = std::min(r_min, (p - centre).norm());
    r_max = std::max(r_max, (p - centre).norm());
  }
  std::printf(
      "inertial oscillation at 75 deg, dt = %.0f s: period %.2f s (2 pi / f = %.2f s, error %.1e), radius "
      "%.3f..%.3f m (u0 / f = %.3f m, error %.1e) over %zu periods; speed %.12f (u0 = %.1f)\n",
      dt, measured_period, period, std::abs(measured_period - period) / period, r_min, r_max, radius,
      std::max(r_max - radius, radius - r_min) / radius, crossings.size(), w.velocities()[0].norm(), u0);
  EXPECT_LT(std::abs(measured_period - period) / period, 1e-3);
  EXPECT_LT(std::max(r_max - radius, radius - r_min) / radius, 1e-3);
  EXPECT_NEAR(w.velocities()[0].norm(), u0, 1e-12);  // the Cayley rotation keeps |u| exactly
}

TEST(Drift, FormDragOnASquareAtRestIsTheHandValueAlongTheCurrentWithNoTorqueAtAnyYaw) {
  for (double yaw_deg : {0.0, 30.0, 45.0, 110.0}) {
    const double l = 12.0, h = 1.0, u = 0.7;
    dynamics::WorldSettings ws;
    ws.drift = forcing::DriftSettings::none();
    ws.drift.form_drag = true;
    ws.drift.ocean = uniform({u, 0.0});
    dynamics::World w(ws);
    const double yaw = yaw_deg * std::numbers::pi / 180.0;
    w.add_body({.id = 1, .shape = rect(l, l), .position = {50.0, -20.0}, .yaw = yaw, .thickness = h});
    w.compute_forces(0.0);
    const double d = h * kRhoIce / 1025.0;
    const double width = l * (std::abs(std::cos(yaw)) + std::abs(std::sin(yaw)));  // across the flow
    const double hand = 0.5 * 0.20 * 1025.0 * d * width * u * u;
    const Vec2 f = w.forces()[0];
    std::printf(
        "form drag, square %.0f m at yaw %.0f deg in %.1f m/s: F = (%.10f, %.1e) N, hand %.10f N, "
        "torque %.1e N m\n",
        l, yaw_deg, u, f.x(), f.y(), hand, w.torques()[0]);
    EXPECT_NEAR(f.x(), hand, 1e-10 * hand);
    EXPECT_NEAR(f.y(), 0.0, 1e-10 * hand);
    EXPECT_NEAR(w.torques()[0], 0.0, 1e-10 * hand * l);
  }
}

TEST(Drift, FieldsAreSampledWhereEachTermActs) {
  // Square 10 m x 10 m, h = 2 m (draft d = 1.7951 m, freeboard 0.2049 m), at rest, centroid rule.
  const double l = 10.0, h = 2.0, d = h * kRhoIce / 1025.0;
  auto load = [&](forcing::DriftSettings s) {
    dynamics::WorldSettings ws;
    ws.drift = s;
    dynamics::World w(ws);
    w.add_body({.id = 1, .shape = rect(l, l), .thickness = h});
    w.compute_forces(0.0);
    return w.forces()[0];
  };
  FieldSpec depth;  // u = (1 + 0.1 y + 0.2 z, 0): varies across the floe and with depth
  depth.kind = FieldKind::linear;
  depth.velocity = {1.0, 0.0};
  depth.gradient << 0.0, 0.1, 0.0, 0.0;
  depth.depth_gradient = {0.2, 0.0};
  // Form drag: only the upstream -x face (centre (-5, 0), half draft) pushes, against water 1 - 0.2 d / 2.
  forcing::DriftSettings form = forcing::DriftSettings::none();
  form.form_drag = true;
  form.ocean = forcing::make_field(depth);
  const double uf = 1.0 - 0.1 * d;
  EXPECT_NEAR(load(form).x(), 0.5 * 0.20 * 1025.0 * l * d * uf * uf, 1e-9);
  // Skin drag at the bottom (z = -d) and air drag at the top (z = h - d), the centroid rule.
  forcing::DriftSettings skin = forcing::DriftSettings::none();
  skin.skin_drag = true;
  skin.quadrature = forcing::Quadrature::centroid;
  skin.ocean = forcing::make_field(depth);
  const double ub = 1.0 - 0.2 * d;
  EXPECT_NEAR(load(skin).x(), 0.5 * 0.0055 * 1025.0 * l * l * ub * ub, 1e-9);
  forcing::DriftSettings air = forcing::DriftSettings::none();
  air.air_drag = true;
  air.quadrature = forcing::Quadrature::centroid;
  FieldSpec wind = depth;
  wind.velocity = {10.0, 0.0};
  wind.depth_gradient = {5.0, 0.0};  // strong shear near the surface
  air.wind = forcing::make_field(wind);
  const double ua = 10.0 + 5.0 * (h - d);
  EXPECT_NEAR(load(air).x(), 0.5 * 0.0012 * 1.2 * l * l * ua * ua, 1e-9);
}

TEST(Drift, TerminalVelocityUnderAConstantLoad) {
  // The semi-implicit kick with another force present: a constant push F against skin drag in still water ends at
  // F = 1/2 c_w rho_w A u^2, at steps from small to far beyond the relaxation time.
  for (double dt : {1.0, 100.0, 1e5}) {
    dynamics::WorldSettings ws;
    ws.drift = forcing::DriftSettings::none();
    ws.drift.skin_drag = true;
    dynamics::World w(ws);
    const double f = 500.0;  // [N]
    w.add_body({.id = 1, .shape = rect(10, 10), .external_force = {f, 0.0}});
    for (int s = 0; s < 3000; ++s) w.step(dt);
    const double u = std::sqrt(f / (0.5 * 0.0055 * 1025.0 * 100.0));
    std::printf("terminal velocity under %.0f N, dt = %g s: %.12f m/s (closed form %.12f)\n", f, dt,
                w.velocities()[0].x(), u);
    EXPECT_NEAR(w.velocities()[0].x(), u, 1e-9 * u) << "dt " << dt;
  }
}

TEST(Drift, ShearSpinUpAndQuadratureConvergence) {
  const double a = 10.0, g = 0.01, h = 1.0;  // square half-width [m], shear du/dy [1/s]
  const double k = 0.5 * 0.0055 * 1025.0;
  auto world_with = [&](forcing::Quadrature q, const Vec2& u0) {
    dynamics::WorldSettings ws;
    ws.drift = forcing::DriftSettings::none();
    ws.drift.skin_drag = true;
    ws.drift.quadrature = q;
    FieldSpec s;
    s.kind = FieldKind::linear;
    s.velocity = u0;
    s.gradient << 0.0, g, 0.0, 0.0;
    ws.drift.ocean = forcing::make_field(s);
    auto w = std::make_unique<dynamics::World>(ws);
    w->add_body({.id = 1, .shape = rect(2 * a, 2 * a), .thickness = h});
    w->compute_forces(0.0);
    return w;
  };
  using forcing::Quadrature;
  const Quadrature rules[] = {Quadrature::centroid, Quadrature::degree1, Quadrature::degree2, Quadrature::degree4,
                              Quadrature::degree5};
  // Pure shear: w changes sign across y = 0 (a kink in |w| w): T = -k G^2 int |y|^3 dA = -k G^2 a^5.
  const double exact = -k * g * g * std::pow(a, 5);
  double prev_err = 1.0;
  for (Quadrature q : rules) {
    const auto w = world_with(q, {0.0, 0.0});
    const double t = w->torques()[0];
    const double err = std::abs(t - exact) / std::abs(exact);
    std::printf(
        "shear u = (G y, 0), G = %.2f 1/s, square 2a = %.0f m, %-8s: torque %.6f N m (hand %.6f), error "
        "%.2e, force (%.1e, %.1e) N\n",
        g, 2 * a, std::string(to_string(q)).c_str(), t, exact, err, w->forces()[0].x(), w->forces()[0].y());
    EXPECT_NEAR(w->forces()[0].norm(), 0.0, 1e-12);
    if (q == Quadrature::centroid) {
      EXPECT_NEAR(t, 0.0, 1e-12) << "the paper's centre-velocity form cannot see shear";
      continue;
    }
    EXPECT_LT(t, 0.0) << "clockwise, like the water's vorticity -G";
    // The kink of |w| w along y = 0 runs through two of the fan triangles: it caps the order of accuracy, so the
    // degree-5 rule is no better than the degree-4 one here; both are within 1 %.
    if (q == Quadrature::degree4 || q == Quadrature::degree5) {
      EXPECT_LT(err, 0.01) << to_string(q);
    } else {
      EXPECT_LT(err, prev_err) << to_string(q);
    }
    prev_err = std::min(prev_err, err);
    // Spin-up: after one short step omega = T / I dt (to the step's second-order error).
    dynamics::World& ww = *w;
    const double dt = 1e-3;
    ww.step(dt);
    EXPECT_NEAR(ww.angular_velocities()[0], t / ww.inertia(0) * dt, 1e-6 * std::abs(t / ww.inertia(0) * dt));
  }
  // Shear plus a current that keeps w_x < 0 everywhere: |w| w = -(U0 + G y)^2 x, a polynomial: force (degree 2)
  // exact from degree 2 on, torque (degree 3) from degree 4 on.
  const double u0 = 0.5;
  const double fx = k * (u0 * u0 * 4 * a * a + g * g * 4 * std::pow(a, 4) / 3);
  const double tz = -k * 2 * u0 * g * 4 * std::pow(a, 4) / 3;
  for (Quadrature q : rules) {
    const auto w = world_with(q, {u0, 0.0});
    const double ef = std::abs(w->forces()[0].x() - fx) / fx, et = std::abs(w->torques()[0] - tz) / std::abs(tz);
    std::printf("shear + current U0 = %.1f m/s, %-8s: force error %.1e, torque error %.1e\n", u0,
                std::string(to_string(q)).c_str(), ef, et);
    const bool force_exact = q == Quadrature::degree2 || q == Quadrature::degree4 || q == Quadrature::degree5;
    const bool torque_exact = q == Quadrature::degree4 || q == Quadrature::degree5;
    EXPECT_TRUE(!force_exact || ef < 1e-12) << to_string(q) << ": " << ef;
    EXPECT_TRUE(!torque_exact || et < 1e-12) << to_string(q) << ": " << et;
  }
}

// Force and torque of each drift term on one floe, all lengths times `s`, rates divided by `s`.
struct Load {
  Vec2 force;
  double torque;
};
Load term_load(int term, double s) {
  std::mt19937_64 rng(5);
  auto poly = tsupport::random_convex(rng, 8, 20.0, 13.0);
  for (Vec2& p : poly) p *= s;
  const double phi0 = 70.0 * std::numbers::pi / 180;
  dynamics::WorldSettings ws;
  ws.drift = forcing::DriftSettings::none();
  ws.drift.quadrature = forcing::Quadrature::degree2;
  switch (term) {
    case 0: ws.drift.form_drag = true; break;
    case 1: ws.drift.moment_drag = true; break;
    case 2: ws.drift.skin_drag = true; break;
    case 3: ws.drift.air_drag = true; break;
    case 4:
      ws.drift.coriolis = true;
      ws.drift.latitude = std::asin(std::sin(phi0) / s) * 180 / std::numbers::pi;  // f / s
      break;
  }
  FieldSpec ocean;
  ocean.kind = FieldKind::linear;
  ocean.velocity = {0.3, -0.1};
  ocean.origin = Vec2(100.0, 40.0) * s;
  ocean.gradient << 2e-3 / s, -4e-3 / s, 3e-3 / s, 1e-3 / s;
  ocean.depth_gradient = Vec2(0.02, 0.01) / s;
  ws.drift.ocean = forcing::make_field(ocean);
  FieldSpec wind;
  wind.kind = FieldKind::solid_body;
  wind.origin = Vec2(-300.0, 200.0) * s;
  wind.angular_velocity = 0.01 / s;
  wind.velocity = {6.0, 2.0};
  ws.drift.wind = forcing::make_field(wind);
  dynamics::World w(ws);
  w.add_body({.id = 1,
              .shape = tsupport::shape_of(poly),
              .position = Vec2(130.0, 70.0) * s,
              .yaw = 0.3,
              .velocity = {0.5, 0.2},
              .angular_velocity = 0.004 / s,
              .thickness = 1.5 * s});
  w.compute_forces(0.0);
  return {w.forces()[0], w.torques()[0]};
}

TEST(Drift, DoublingTheFloeScalesEveryDriftForceByFourAndEveryTorqueByEight) {
  const char* names[] = {"form drag", "moment drag", "skin drag", "air drag", "Coriolis"};
  for (int term = 0; term < 5; ++term) {
    const Load a = term_load(term, 1.0), b = term_load(term, 2.0);
    const double rf = b.force.norm() / a.force.norm(), rt = b.torque / a.torque;
    std::printf("scaling, %-11s: |F| x %s, M x %s (dimensional analysis: 4, 8)\n", names[term],
                term == 1 ? "- (none)" : std::to_string(rf).c_str(),
                term == 4 ? "- (none)" : std::to_string(rt).c_str());
    if (term != 1) {
      EXPECT_NEAR(rf, 4.0, 4e-12) << names[term];
      EXPECT_NEAR((b.force - 4.0 * a.force).norm(), 0.0, 1e-12 * b.force.norm()) << names[term];
    }
    if (term != 4) {
      EXPECT_NEAR(rt, 8.0, 8e-12) << names[term];
    }
  }
  // (The printed Eq. 12, 1/2 C rho A_sub r_e^2 w|w|, would scale by A_sub x4, r_e^2 x4, w^2 / 4 -> x4: like a
  // force, which is why the kernel uses r_e^3 and the x8 above holds.)
}

TEST(Drift, LargeStepsSemiImplicitConvergesExplicitBlowsUp) {
  // Skin + air drag + Coriolis on a 5 m floe: the steady state is the root of case 2's balance. (Form drag makes
  // the steady velocity depend on the floe's yaw, which a step far beyond the rotational time scale scrambles.)
  const Vec2 uc{0.3, 0.0}, ua{15.0, 5.0};
  const double rel_time = kRhoIce * 1.0 / (1025.0 * 0.0055 * 0.3);  // m / (dF/du) per area at |w| ~ 0.3 m/s [s]
  const double dt = 50.0 * rel_time;
  for (auto treatment : {forcing::DriftTreatment::semi_implicit, forcing::DriftTreatment::explicit_step}) {
    dynamics::WorldSettings ws;
    ws.drift = skin_and_air(uc, ua);
    ws.drift.coriolis = true;
    ws.drift.latitude = 75.0;
    ws.drift.treatment = treatment;
    dynamics::World w(ws);
    w.add_body({.id = 1, .shape = rect(5, 5), .velocity = {2.0, -1.0}, .angular_velocity = 0.1});
    bool finite = true;
    for (int s = 0; s < 200 && finite; ++s) {
      w.step(dt);
      finite = std::isfinite(w.velocities()[0].x()) && w.velocities()[0].norm() < 1e3;
    }
    if (treatment == forcing::DriftTreatment::semi_implicit) {
      const Vec2 ref = coriolis_free_drift(ws.drift, uc, ua, 1.0);
      const double err = (w.velocities()[0] - ref).norm() / ref.norm();
      std::printf(
          "large steps, semi-implicit: dt = %.0f s (50 relaxation times, f dt = %.2f): u = (%.8f, %.8f) m/s, "
          "balance root (%.8f, %.8f), error %.1e\n",
          dt, ws.drift.coriolis_parameter(0.0) * dt, w.velocities()[0].x(), w.velocities()[0].y(), ref.x(), ref.y(),
          err);
      EXPECT_TRUE(finite);
      EXPECT_LT(err, 1e-9);
    } else {
      std::printf("large steps, explicit: dt = %.0f s: %s\n", dt, finite ? "stayed finite" : "blew up");
      EXPECT_FALSE(finite) << "the explicit treatment should fail at 50 relaxation times (or the test is moot)";
    }
  }
}

TEST(Drift, FloeSpinsUpWithASolidBodyVortex) {
  // A regular 12-gon centred on the vortex: no net force by symmetry; the relative rotation decays (algebraically:
  // quadratic drag) without overshoot, for the paper's centroid rule (through the drag moment on omega - Omega_w)
  // and for a triangle rule (bottom drag too).
  for (auto q : {forcing::Quadrature::centroid, forcing::Quadrature::degree2}) {
    dynamics::WorldSettings ws;  // every ocean term on, no wind
    ws.drift.air_drag = false;
    ws.drift.quadrature = q;
    FieldSpec s;
    s.kind = FieldKind::solid_body;
    s.angular_velocity = 2e-3;
    ws.drift.ocean = forcing::make_field(s);
    dynamics::World w(ws);
    std::vector<Vec2> poly;
    for (int k = 0; k < 12; ++k)
      poly.emplace_back(15 * std::cos(k * std::numbers::pi / 6), 15 * std::sin(k * std::numbers::pi / 6));
    w.add_body({.id = 1, .shape = tsupport::shape_of(poly)});
    double prev = 0.0;
    bool monotone = true;
    for (int k = 0; k < 4000; ++k) {
      w.step(5.0);
      monotone = monotone && w.angular_velocities()[0] >= prev && w.angular_velocities()[0] <= 2e-3;
      prev = w.angular_velocities()[0];
    }
    std::printf("solid-body vortex Omega = 2e-3 rad/s, %s: floe omega after %.0f s = %.6e rad/s, |u| = %.1e m/s\n",
                std::string(to_string(q)).c_str(), w.time(), w.angular_velocities()[0], w.velocities()[0].norm());
    EXPECT_TRUE(monotone);
    EXPECT_GT(w.angular_velocities()[0], 0.8 * 2e-3);
    EXPECT_LT(w.velocities()[0].norm(), 1e-9);
  }
}

}  // namespace

TEST(Drift, UpdateEveryKeepsTheSteadyStateAndConvergesInTheTransient) {
  // DriftSettings::update_every = K: the loads are evaluated in full every K steps and taken from that
  // evaluation's linear model F_d(v) = b - D v in between. (1) Steady states are fixed points of both, so the
  // large-step free drift with Coriolis ends at the same balance root (to 1e-9) for K = 8. (2) In a transient
  // (a 10 x 6 m floe at rest in a 1 m/s current with a 15 m/s wind across it and a spin, every term, 20 s at
  // dt = 0.01 s) the velocities after K = 2, 4, 8, 16 differ from every-step's by an error that grows about
  // linearly with the time between evaluations (the floe's yaw is frozen there); at the channel's step and K = 8
  // it is below half the error of every-step evaluation at dt = 0.01 s against dt / 4.
  const Vec2 uc{0.3, 0.0}, ua{15.0, 5.0};
  {
    dynamics::WorldSettings ws;
    ws.drift = skin_and_air(uc, ua);
    ws.drift.coriolis = true;
    ws.drift.update_every = 8;
    dynamics::World w(ws);
    w.add_body({.id = 1, .shape = rect(5, 5), .velocity = {2.0, -1.0}, .angular_velocity = 0.1});
    const double rel_time = kRhoIce * 1.0 / (1025.0 * 0.0055 * 0.3);
    for (int s = 0; s < 400; ++s) w.step(0.5 * rel_time);
    const Vec2 ref = coriolis_free_drift(ws.drift, uc, ua, 1.0);
    const double err = (w.velocities()[0] - ref).norm() / ref.norm();
    std::printf("update_every = 8, free drift with Coriolis: error against the balance root %.1e\n", err);
    EXPECT_LT(err, 1e-9);
  }
  auto transient = [&](int every, double dt) {
    dynamics::WorldSettings ws;
    ws.drift.ocean = uniform({1.0, 0.0});
    ws.drift.wind = uniform({0.0, 15.0});
    ws.drift.coriolis = true;
    ws.drift.quadrature = forcing::Quadrature::degree2;
    ws.drift.update_every = every;
    dynamics::World w(ws);
    w.add_body({.id = 1, .shape = rect(10, 6), .angular_velocity = 0.2});
    for (int s = 0, n = static_cast<int>(std::lround(20.0 / dt)); s < n; ++s) w.step(dt);
    return Eigen::Vector3d(w.velocities()[0].x(), w.velocities()[0].y(), 5.0 * w.angular_velocities()[0]);
  };
  const double dt = 0.01;
  const Eigen::Vector3d ref = transient(1, dt);
  // The step's own error, for scale: every step at dt against every step at dt / 4.
  const double step_err = (ref - transient(1, dt / 4)).norm() / ref.norm();
  std::printf("every step: the velocity after 20 s at dt = %.3g s differs from dt / 4's by %.2e\n", dt, step_err);
  double last = 0.0;
  for (const int k : {2, 4, 8, 16}) {
    const double err = (transient(k, dt) - ref).norm() / ref.norm();
    std::printf("update_every = %d: velocity after 20 s (u, v, 5 m x omega) differs from every step's by %.2e\n", k,
                err);
    EXPECT_GT(err, last) << "the error should grow with the interval";
    last = err;
  }
  // At the channel scene's step (0.627 ms: 5 ms between full evaluations at K = 8) the error is far smaller, and
  // below what a drift-only run at dt = 10 ms (evaluated every step) carries.
  const double dt_channel = 6.27e-4;
  const double err_channel = (transient(8, dt_channel) - transient(1, dt_channel)).norm() / ref.norm();
  std::printf("update_every = 8 at dt = %.3g s: differs from every step's by %.2e\n", dt_channel, err_channel);
  EXPECT_LT(err_channel, 0.5 * step_err);
}

TEST(Drift, AWorldRefusesAnUpdateIntervalItCannotKeep) {
  // The World's own check (the scene reader names the scene's key): an interval outside [1, 1000], or above 1 with
  // the explicit treatment, which has no linear model to step with.
  dynamics::WorldSettings ws;
  ws.drift = skin_and_air({0.3, 0.0}, {15.0, 5.0});
  auto message = [&] {
    try {
      dynamics::World w(ws);
    } catch (const std::invalid_argument& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  ws.drift.update_every = 8;
  EXPECT_EQ(message(), "");
  ws.drift.update_every = 0;
  EXPECT_NE(message().find("update_every is 0; it must be in [1, 1000]"), std::string::npos) << message();
  ws.drift.update_every = 1001;
  EXPECT_NE(message().find("[1, 1000]"), std::string::npos) << message();
  ws.drift.update_every = 8;
  ws.drift.treatment = forcing::DriftTreatment::explicit_step;
  EXPECT_NE(message().find("needs the semi-implicit treatment"), std::string::npos) << message();
  ws.drift.update_every = 1;
  EXPECT_EQ(message(), "");
}
