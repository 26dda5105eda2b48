// Spatial (6-DOF) mode against closed forms: free fall, a floating box's equilibrium, heave and roll periods
// (hydrostatics), and Coulomb friction stopping a sliding box.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <numbers>

#include "dynamics/spatial_world.h"

namespace {

using namespace polyfloe;
using geometry::Vec3;

constexpr double kG = 9.81, kRhoIce = 920.0, kRhoWater = 1025.0;

dynamics::SpatialBodyDesc box_body(dynamics::BodyId id, const Vec3& size, const Vec3& position) {
  dynamics::SpatialBodyDesc d;
  d.id = id;
  d.shape = std::make_shared<geometry::ConvexPolyhedron>(geometry::ConvexPolyhedron::box(size));
  d.density = kRhoIce;
  d.position = position;
  return d;
}

// Verlet integrates a constant force exactly: z(t) = z0 + v0 t - g t^2 / 2 to round-off.
TEST(SpatialForces, FreeFallIsExact) {
  dynamics::SpatialSettings s;
  s.gravity = {0.0, 0.0, -kG};
  dynamics::SpatialWorld w(s);
  auto d = box_body(1, {1.0, 2.0, 3.0}, {0.0, 0.0, 100.0});
  d.velocity = {1.0, 0.0, 2.0};
  d.angular_velocity = {0.3, -0.2, 0.5};
  w.add_body(d);
  const double dt = 1e-3;
  for (int k = 0; k < 2000; ++k) w.step(dt);
  const double t = 2.0;
  EXPECT_NEAR(w.position(0).z(), 100.0 + 2.0 * t - 0.5 * kG * t * t, 1e-9);
  EXPECT_NEAR(w.position(0).x(), 1.0 * t, 1e-12);
  EXPECT_NEAR(w.velocity(0).z(), 2.0 - kG * t, 1e-9);
}

struct Floating {
  dynamics::SpatialWorld world;
  double draft = 0.0;  // [m]
};

Floating floating_box(const Vec3& size, double dz, double roll) {
  dynamics::SpatialSettings s;
  s.gravity = {0.0, 0.0, -kG};
  s.buoyancy = true;
  s.water_density = kRhoWater;
  dynamics::SpatialWorld w(s);
  const double draft = size.z() * kRhoIce / kRhoWater;
  auto d = box_body(1, size, {0.0, 0.0, 0.5 * size.z() - draft + dz});
  d.orientation = dynamics::Quat(Eigen::AngleAxisd(roll, Vec3::UnitX()));
  w.add_body(d);
  return {std::move(w), draft};
}

// Times of the upward zero crossings of x(t) - mean, linearly interpolated.
std::vector<double> crossings(const std::vector<double>& t, const std::vector<double>& x) {
  double mean = 0.0;
  for (double v : x) mean += v / static_cast<double>(x.size());
  std::vector<double> c;
  for (std::size_t i = 1; i < x.size(); ++i) {
    if (x[i - 1] < mean && x[i] >= mean)
      c.push_back(t[i - 1] + (mean - x[i - 1]) / (x[i] - x[i - 1]) * (t[i] - t[i - 1]));
  }
  return c;
}

// At the draft h rho_ice / rho_water the weight and the buoyancy balance: no force, no torque.
TEST(SpatialForces, BoxFloatsAtItsDraft) {
  auto [w, draft] = floating_box({4.0, 3.0, 1.0}, 0.0, 0.0);
  w.compute_forces(1e-3);
  EXPECT_LT(w.force(0).norm(), 1e-9 * w.mass(0) * kG);
  EXPECT_LT(w.torque(0).norm(), 1e-9 * w.mass(0) * kG);
}

// Heave of a wall-sided body: T = 2 pi sqrt(m / (rho_w g A)) = 2 pi sqrt(rho_ice h / (rho_w g)) (no added mass in
// the model), within 0.5 %.
TEST(SpatialForces, HeavePeriodOfAFloatingBox) {
  auto [w, draft] = floating_box({4.0, 4.0, 1.0}, -0.05, 0.0);
  const double period = 2.0 * std::numbers::pi * std::sqrt(kRhoIce * 1.0 / (kRhoWater * kG));
  const double dt = period / 2000.0;
  std::vector<double> t, z;
  for (int k = 0; k < 10000; ++k) {
    w.step(dt);
    t.push_back(w.time());
    z.push_back(w.position(0).z());
  }
  const auto c = crossings(t, z);
  ASSERT_GE(c.size(), 4u);
  const double measured = (c.back() - c.front()) / static_cast<double>(c.size() - 1);
  std::cout << "heave period " << measured << " s, closed form " << period << " s\n";
  EXPECT_NEAR(measured, period, 0.005 * period);
  // undamped: the amplitude stays (energy exchanged with the buoyancy potential only)
  const auto [lo, hi] = std::minmax_element(z.begin() + 8000, z.end());
  EXPECT_NEAR(*hi - *lo, 0.10, 0.002);
}

// Roll of a wide floe: small-angle period 2 pi sqrt(I_xx / (m g GM)), GM = d/2 + b^2 / (12 d) - h/2 (metacentric
// height of a box of beam b, draft d, height h), within 2 % (the heave it excites couples weakly).
TEST(SpatialForces, RollPeriodFromTheMetacentricHeight) {
  const double b = 10.0, h = 1.0;
  auto [w, draft] = floating_box({b, b, h}, 0.0, 1.0 * std::numbers::pi / 180.0);
  const double gm = 0.5 * draft + b * b / (12.0 * draft) - 0.5 * h;
  ASSERT_GT(gm, 0.0);  // stable
  const double period = 2.0 * std::numbers::pi * std::sqrt((b * b + h * h) / 12.0 / (kG * gm));
  const double dt = period / 2000.0;
  std::vector<double> t, roll;
  for (int k = 0; k < 10000; ++k) {
    w.step(dt);
    t.push_back(w.time());
    const Vec3 up = w.orientation(0) * Vec3::UnitZ();
    roll.push_back(std::atan2(-up.y(), up.z()));
  }
  const auto c = crossings(t, roll);
  ASSERT_GE(c.size(), 4u);
  const double measured = (c.back() - c.front()) / static_cast<double>(c.size() - 1);
  std::cout << "roll period " << measured << " s, closed form " << period << " s\n";
  EXPECT_NEAR(measured, period, 0.02 * period);
  EXPECT_LT(*std::max_element(roll.begin(), roll.end()), 1.1 * std::numbers::pi / 180.0);  // bounded: stable
}

// A box sliding on a fixed plate under gravity stops after v0^2 / (2 mu g) (within 2 %: the tangential spring's
// elastic stretch and the start of the contact), without tipping or drifting sideways.
TEST(SpatialForces, CoulombFrictionStopsASlidingBox) {
  dynamics::SpatialSettings s;
  s.gravity = {0.0, 0.0, -kG};
  s.contact.friction = 0.3;
  s.contact.restitution = 0.2;
  s.contact.youngs_modulus = 1e8;
  dynamics::SpatialWorld w(s);
  auto plate = box_body(1, {40.0, 10.0, 1.0}, {0.0, 0.0, -0.5});
  plate.motion = dynamics::Motion::fixed;
  w.add_body(plate);
  // resting depth of a 1 m cube face-on: m g = k_n d^1.5 (one witness point at the face centre)
  auto cube = box_body(2, {1.0, 1.0, 1.0}, {-10.0, 0.0, 0.5});
  w.add_body(cube);
  const double dt = w.shortest_contact_duration(1.0) / 40.0;
  for (int k = 0; k < 20000; ++k) w.step(dt);  // settle onto the plate
  ASSERT_LT(w.velocity(1).norm(), 1e-3);
  const double v0 = 2.0;
  const double x0 = w.position(1).x();
  // restart the cube sliding at v0 along x
  dynamics::SpatialWorld w2(s);
  w2.add_body(plate);
  cube.position = w.position(1);
  cube.orientation = w.orientation(1);
  cube.velocity = {v0, 0.0, 0.0};
  w2.add_body(cube);
  for (int k = 0; k < 400000 && (k < 10 || w2.velocity(1).norm() > 1e-4); ++k) w2.step(dt);
  const double distance = w2.position(1).x() - x0;
  const double expected = v0 * v0 / (2.0 * 0.3 * kG);
  std::cout << "sliding distance " << distance << " m, closed form " << expected << " m\n";
  EXPECT_NEAR(distance, expected, 0.02 * expected);
  EXPECT_NEAR(w2.position(1).y(), 0.0, 1e-6);
  const Vec3 up = w2.orientation(1) * Vec3::UnitZ();
  EXPECT_GT(up.z(), std::cos(1.0 * std::numbers::pi / 180.0));  // not tipped
}

}  // namespace
