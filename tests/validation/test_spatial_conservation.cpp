// Spatial (6-DOF) mode: momentum, angular momentum and energy over a tumbling run of 50 polyhedra that collide many
// times, frictionless with e = 1 (energy within 0.5 %), and with friction and damping (momenta only).
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "dynamics/spatial_world.h"

namespace {

using namespace polyfloe;
using geometry::Vec3;

struct Tumble {
  dynamics::SpatialWorld world;
  double dt = 0.0;
};

// 50 boxes and prisms (0.8-2 m) on a 5 x 5 x 2 lattice 3 m apart, turned at random, thrown towards the centre at
// about 1 m/s and spinning at up to 1 rad/s. No gravity, no walls.
Tumble make_tumble(double restitution, double friction, dynamics::SpatialNarrowPhase method) {
  dynamics::SpatialSettings s;
  s.contact.youngs_modulus = 1.0e8;
  s.contact.restitution = restitution;
  s.contact.friction = friction;
  s.narrow_phase = method;
  dynamics::SpatialWorld w(s);
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  int id = 0;
  for (int k = 0; k < 2; ++k) {
    for (int j = 0; j < 5; ++j) {
      for (int i = 0; i < 5; ++i) {
        dynamics::SpatialBodyDesc d;
        d.id = static_cast<dynamics::BodyId>(id++);
        if (id % 2) {
          d.shape = std::make_shared<geometry::ConvexPolyhedron>(
              geometry::ConvexPolyhedron::box({0.8 + 1.2 * u(rng), 0.8 + 1.2 * u(rng), 0.8 + 1.2 * u(rng)}));
        } else {
          d.shape = std::make_shared<geometry::ConvexPolyhedron>(geometry::ConvexPolyhedron::prism(
              geometry::ConvexPolygon::regular(5 + static_cast<int>(4 * u(rng)), 0.5 + 0.5 * u(rng)),
              0.8 + 1.0 * u(rng)));
        }
        d.position = {3.0 * (i - 2), 3.0 * (j - 2), 3.0 * (k - 0.5)};
        const Vec3 axis = Vec3(u(rng) - 0.5, u(rng) - 0.5, u(rng) - 0.5).normalized();
        d.orientation = dynamics::Quat(Eigen::AngleAxisd(6.28 * u(rng), axis));
        d.velocity = -0.35 * d.position + Vec3(u(rng) - 0.5, u(rng) - 0.5, u(rng) - 0.5);
        d.angular_velocity = Vec3(u(rng) - 0.5, u(rng) - 0.5, u(rng) - 0.5) * 2.0;
        w.add_body(d);
      }
    }
  }
  const double dt = w.shortest_contact_duration(2.0) / 100.0;
  return {std::move(w), dt};
}

struct Totals {
  double energy = 0.0, momentum_scale = 0.0;
  Vec3 p, l;
};

Totals totals(const dynamics::SpatialWorld& w) {
  Totals t;
  t.energy = w.kinetic_energy() + w.contact_energy();
  t.p = w.linear_momentum();
  t.l = w.angular_momentum();
  for (int i = 0; i < static_cast<int>(w.size()); ++i) t.momentum_scale += w.mass(i) * w.velocity(i).norm();
  return t;
}

// Frictionless, e = 1: momentum and angular momentum to round-off, energy within 0.5 % of the start, at every frame.
TEST(SpatialConservation, FiftyTumblingBodiesElasticFrictionless) {
  auto [w, dt] = make_tumble(1.0, 0.0, dynamics::SpatialNarrowPhase::sat);
  w.compute_forces(dt);
  const Totals t0 = totals(w);
  const int steps = static_cast<int>(std::ceil(8.0 / dt));
  std::size_t contact_steps = 0, manifold = 0;
  double worst_energy = 0.0;
  for (int k = 0; k < steps; ++k) {
    w.step(dt);
    contact_steps += w.contacts().size();
    for (const auto& c : w.contacts()) manifold += c.manifold_points > 0;
    if (k % 50 == 0 || k == steps - 1) {
      const Totals t = totals(w);
      worst_energy = std::max(worst_energy, std::abs(t.energy - t0.energy) / t0.energy);
      ASSERT_LT((t.p - t0.p).norm(), 1e-10 * t0.momentum_scale) << "step " << k;
      // angular momentum about the origin: lever ~ 10 m
      ASSERT_LT((t.l - t0.l).norm(), 1e-9 * 10.0 * t0.momentum_scale) << "step " << k;
    }
  }
  RecordProperty("contact_steps", static_cast<int>(contact_steps));
  std::cout << "steps " << steps << ", contact-steps " << contact_steps << " (" << manifold
            << " with a manifold), worst energy error " << worst_energy * 100 << " %, narrow-phase failures "
            << w.narrow_phase_stats().primary_failures << " of " << w.narrow_phase_stats().queries << "\n";
  EXPECT_GT(contact_steps, 20000u);  // many collisions, not a fly-by
  EXPECT_LT(worst_energy, 0.005);
}

// Friction and damping take energy but no momentum.
TEST(SpatialConservation, FrictionAndDampingKeepMomenta) {
  auto [w, dt] = make_tumble(0.3, 0.5, dynamics::SpatialNarrowPhase::sat);
  w.compute_forces(dt);
  const Totals t0 = totals(w);
  const int steps = static_cast<int>(std::ceil(8.0 / dt));
  for (int k = 0; k < steps; ++k) w.step(dt);
  const Totals t = totals(w);
  EXPECT_LT((t.p - t0.p).norm(), 1e-10 * t0.momentum_scale);
  EXPECT_LT((t.l - t0.l).norm(), 1e-9 * 10.0 * t0.momentum_scale);
  EXPECT_LT(t.energy, 0.9 * t0.energy);  // the collisions did dissipate
}

}  // namespace
