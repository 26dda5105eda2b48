// World basics, each against an exact or closed-form reference:
//   add_body rejects bad bodies (duplicate id, no shape, too many vertices, non-positive or non-finite thickness or
//   density) and leaves the world unchanged; ids map to indices and back;
//   mass and inertia of a rectangular prism (rho h w l, m (w^2 + l^2) / 12) and the diagnostics built on them;
//   world_vertices = position + R(yaw) x body-frame vertices (1e-12 m);
//   a free floe with no force keeps its velocity and angular velocity bit for bit, and moves by v t;
//   fixed bodies never move (bit for bit), even when hit; kinematic bodies keep their prescribed velocity bit for
//   bit whatever the contact forces on them, and move by v t;
//   shortest_contact_duration = the Hertz duration of two of the lightest, smallest floes;
//   a state restored into a World built the same way continues bit for bit; a state of other bodies is refused.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <limits>
#include <numbers>
#include <stdexcept>

#include "dynamics/world.h"
#include "forcing/drift.h"
#include "test_support.h"
#include "world_checks.h"

using namespace polyfloe;
using geometry::Vec2;
using tsupport::expect_vertices_follow_body;
using tsupport::no_drift;

namespace {

std::shared_ptr<const geometry::ConvexPolygon> rect(double w, double h) {
  return std::make_shared<const geometry::ConvexPolygon>(geometry::ConvexPolygon::rectangle(w, h));
}

}  // namespace

TEST(World, TheFoundationForceModelNeedsTheExactNarrowPhase) {
  dynamics::WorldSettings ws = no_drift();
  ws.contact.force_model = contact::ForceModel::foundation;
  ws.narrow_phase = dynamics::PlanarNarrowPhase::gjk_epa;
  EXPECT_THROW(dynamics::World{ws}, std::invalid_argument);
  ws.narrow_phase = dynamics::PlanarNarrowPhase::exact;
  EXPECT_NO_THROW(dynamics::World{ws});
}

TEST(World, AddBodyRejectsBadBodies) {
  dynamics::World w(no_drift());
  const auto sq = rect(10, 10);
  EXPECT_EQ(w.add_body({.id = 5, .shape = sq}), 0);
  auto expect_rejected = [&](const dynamics::BodyDesc& d, const char* what) {
    EXPECT_THROW(w.add_body(d), std::invalid_argument) << what;
    EXPECT_EQ(w.size(), 1u) << what << ": a rejected body must leave the world unchanged";
    EXPECT_EQ(w.index_of(5), 0) << what;
    if (d.id != 5) {
      EXPECT_EQ(w.index_of(d.id), -1) << what;
    }
  };
  expect_rejected({.id = 5, .shape = sq}, "duplicate id");
  expect_rejected({.id = 6, .shape = nullptr}, "no shape");
  const auto many = std::make_shared<const geometry::ConvexPolygon>(
      geometry::ConvexPolygon::regular(contact::kMaxPolygonVertices + 1, 10.0));
  expect_rejected({.id = 7, .shape = many}, "too many vertices");
  const double nan = std::numeric_limits<double>::quiet_NaN(), inf = std::numeric_limits<double>::infinity();
  for (double h : {0.0, -1.0, nan, inf}) expect_rejected({.id = 8, .shape = sq, .thickness = h}, "bad thickness");
  for (double rho : {0.0, -920.0, nan}) expect_rejected({.id = 9, .shape = sq, .density = rho}, "bad density");
  // The largest allowed polygon is accepted.
  const auto most = std::make_shared<const geometry::ConvexPolygon>(
      geometry::ConvexPolygon::regular(contact::kMaxPolygonVertices, 10.0));
  EXPECT_EQ(w.add_body({.id = 10, .shape = most, .position = {100.0, 0.0}}), 1);
}

TEST(World, AddBodyReturnsConsecutiveIndicesIdsMapBothWaysAndUnknownIdsGiveMinusOne) {
  dynamics::World w(no_drift());
  const auto sq = rect(4, 4);
  const dynamics::BodyId ids[] = {1000, 7, 42, 0, 123456789012345ull};
  for (int k = 0; k < 5; ++k) EXPECT_EQ(w.add_body({.id = ids[k], .shape = sq, .position = {10.0 * k, 0.0}}), k);
  EXPECT_EQ(w.size(), 5u);
  for (int k = 0; k < 5; ++k) {
    EXPECT_EQ(w.id(k), ids[k]);
    EXPECT_EQ(w.index_of(ids[k]), k);
  }
  EXPECT_EQ(w.index_of(1), -1);
  EXPECT_EQ(w.index_of(999), -1);
}

TEST(World, PrismMassAndInertiaMatchClosedFormsAndDiagnosticsCountDynamicBodiesOnly) {
  dynamics::World w(no_drift());
  // 10 m x 4 m x 2 m prism, rho = 900: m = 72000 kg, I = m (10^2 + 4^2) / 12.
  const int a = w.add_body({.id = 1,
                            .shape = rect(10, 4),
                            .position = {3.0, -2.0},
                            .velocity = {0.5, 0.25},
                            .angular_velocity = 0.1,
                            .thickness = 2.0,
                            .density = 900.0});
  const int b = w.add_body({.id = 2, .shape = rect(6, 6), .position = {-20.0, 5.0}, .velocity = {-0.1, 0.0}});
  w.add_body({.id = 3, .shape = rect(100, 5), .position = {0.0, -40.0}, .motion = dynamics::Motion::fixed});
  const double m = 72000.0, inertia = m * 116.0 / 12.0;
  EXPECT_NEAR(w.mass(a), m, 1e-12 * m);
  EXPECT_NEAR(w.inertia(a), inertia, 1e-12 * inertia);
  EXPECT_EQ(w.thickness(a), 2.0);
  const double mb = 920.0 * 36.0, ib = mb * 72.0 / 12.0;
  EXPECT_NEAR(w.mass(b), mb, 1e-12 * mb);
  EXPECT_NEAR(w.inertia(b), ib, 1e-12 * ib);
  // Diagnostics count dynamic bodies only.
  const double ke = 0.5 * m * (0.25 + 0.0625) + 0.5 * inertia * 0.01 + 0.5 * mb * 0.01;
  EXPECT_NEAR(w.kinetic_energy(), ke, 1e-12 * ke);
  const Vec2 p = m * Vec2{0.5, 0.25} + mb * Vec2{-0.1, 0.0};
  EXPECT_NEAR((w.linear_momentum() - p).norm(), 0.0, 1e-12 * p.norm());
  const double l = m * (3.0 * 0.25 - (-2.0) * 0.5) + inertia * 0.1 + mb * (-20.0 * 0.0 - 5.0 * (-0.1));
  EXPECT_NEAR(w.angular_momentum(), l, 1e-12 * std::abs(l));
  EXPECT_NEAR(w.max_speed(), std::sqrt(0.3125), 1e-15);
}

TEST(World, ShortestContactIsHertzForTwoOfTheSmallestFloesAndInfiniteWithOnlyWalls) {
  dynamics::World w(no_drift());
  EXPECT_TRUE(std::isinf(w.shortest_contact_duration(1.0)));  // no floes
  w.add_body({.id = 1, .shape = rect(200, 10), .motion = dynamics::Motion::fixed});
  EXPECT_TRUE(std::isinf(w.shortest_contact_duration(1.0)));  // walls do not count
  w.add_body({.id = 2, .shape = rect(10, 10), .position = {0.0, 50.0}});
  w.add_body({.id = 3, .shape = rect(4, 4), .position = {30.0, 50.0}});
  // Two of the 4 m floes: m* = m/2, R* = R/2.
  const double m = 920.0 * 16.0, r = std::sqrt(16.0 / std::numbers::pi);
  const double k_n = 4.0 / 3.0 * w.contact_law().effective_modulus() * std::sqrt(0.5 * r);
  const double want = 3.2181 * std::pow(0.5 * m / k_n, 0.4) * std::pow(2.0, -0.2);
  EXPECT_NEAR(w.shortest_contact_duration(2.0), want, 1e-12 * want);
}

TEST(World, WorldVerticesFollowTheBody) {
  dynamics::World w(no_drift());
  std::mt19937_64 rng(11);
  for (int k = 0; k < 5; ++k) {
    const auto shape = tsupport::shape_of(tsupport::random_convex(rng, 5 + k, 6.0, 4.0));
    w.add_body({.id = static_cast<dynamics::BodyId>(k + 1),
                .shape = shape,
                .position = {40.0 * k, 1.0e4},
                .yaw = 0.7 * k - 1.0,
                .velocity = {0.3, -0.2},
                .angular_velocity = 0.05 * (k - 2)});
  }
  for (int k = 0; k < 5; ++k) expect_vertices_follow_body(w, k);
  for (int s = 0; s < 500; ++s) w.step(0.01);
  EXPECT_TRUE(w.contacts().empty());
  for (int k = 0; k < 5; ++k) {
    EXPECT_NEAR(w.yaws()[k], 0.7 * k - 1.0 + 0.05 * (k - 2) * 5.0, 1e-12);
    expect_vertices_follow_body(w, k);
  }
}

TEST(World, FreeFloeKeepsItsVelocityExactly) {
  dynamics::World w(no_drift());
  const Vec2 x0{123.0, -45.0}, v{0.37, -1.21};
  const double omega = 0.031;
  w.add_body({.id = 9, .shape = rect(8, 3), .position = x0, .yaw = 0.3, .velocity = v, .angular_velocity = omega});
  const double dt = 0.013;
  const int n = 5000;
  for (int s = 0; s < n; ++s) w.step(dt);
  EXPECT_EQ(w.velocities()[0].x(), v.x());
  EXPECT_EQ(w.velocities()[0].y(), v.y());
  EXPECT_EQ(w.angular_velocities()[0], omega);
  EXPECT_EQ(w.forces()[0].x(), 0.0);
  EXPECT_EQ(w.forces()[0].y(), 0.0);
  EXPECT_EQ(w.torques()[0], 0.0);
  const double t = n * dt;
  EXPECT_NEAR(w.time(), t, 1e-12 * t);
  EXPECT_EQ(w.step_count(), static_cast<std::uint64_t>(n));
  EXPECT_NEAR((w.positions()[0] - (x0 + t * v)).norm(), 0.0, 1e-9);  // 5000 additions of rounding
  EXPECT_NEAR(w.yaws()[0], 0.3 + t * omega, 1e-12);
}

TEST(World, FixedBodiesNeverMove) {
  dynamics::WorldSettings ws = no_drift();
  ws.contact.friction = 0.5;
  dynamics::World w(ws);
  // A fixed wall given a velocity (ignored) and a floe thrown at it obliquely, spinning.
  const int wall = w.add_body({.id = 1,
                               .shape = rect(100, 10),
                               .position = {0.0, -5.0},
                               .yaw = 0.0,
                               .velocity = {3.0, 1.0},
                               .angular_velocity = 0.5,
                               .motion = dynamics::Motion::fixed});
  const int floe = w.add_body({.id = 2,
                               .shape = rect(8, 4),
                               .position = {-10.0, 6.0},
                               .yaw = 0.4,
                               .velocity = {1.0, -2.0},
                               .angular_velocity = 0.2});
  EXPECT_EQ(w.velocities()[wall].norm(), 0.0);
  EXPECT_EQ(w.angular_velocities()[wall], 0.0);
  w.set_velocity(wall, {5.0, 5.0}, 1.0);  // ignored for fixed bodies
  EXPECT_EQ(w.velocities()[wall].norm(), 0.0);
  const std::vector<Vec2> verts0(w.world_vertices(wall).begin(), w.world_vertices(wall).end());
  const double dt = w.shortest_contact_duration(2.0) / 40.0;
  int contact_steps = 0;
  for (int s = 0; s < 20000; ++s) {
    w.step(dt);
    if (!w.contacts().empty()) ++contact_steps;
    ASSERT_EQ(w.positions()[wall], Vec2(0.0, -5.0));
    ASSERT_EQ(w.yaws()[wall], 0.0);
    ASSERT_EQ(w.velocities()[wall].norm(), 0.0);
    ASSERT_EQ(w.angular_velocities()[wall], 0.0);
  }
  for (std::size_t k = 0; k < verts0.size(); ++k) EXPECT_EQ(w.world_vertices(wall)[k], verts0[k]);
  EXPECT_GT(contact_steps, 10);
  EXPECT_GT(w.velocities()[floe].y(), 0.0);  // it bounced off
}

TEST(World, KinematicBodiesKeepTheirPrescribedMotion) {
  dynamics::WorldSettings ws = no_drift();
  ws.contact.friction = 0.3;
  dynamics::World w(ws);
  // A kinematic plate sweeping (and slowly turning) through a row of floes, pushing them ahead.
  const Vec2 x0{-12.0, 0.0}, v{1.5, 0.1};
  const double omega = 0.01;
  const int plate = w.add_body({.id = 1,
                                .shape = rect(4, 60),
                                .position = x0,
                                .velocity = v,
                                .angular_velocity = omega,
                                .motion = dynamics::Motion::kinematic});
  for (int k = 0; k < 6; ++k)
    w.add_body({.id = static_cast<dynamics::BodyId>(10 + k), .shape = rect(8, 8), .position = {0.0, -25.0 + 10.0 * k}});
  const double dt = w.shortest_contact_duration(2.0) / 40.0;
  const int n = static_cast<int>(std::ceil(15.0 / dt));
  int contact_steps = 0;
  double max_force = 0.0;
  for (int s = 0; s < n; ++s) {
    w.step(dt);
    if (!w.contacts().empty()) ++contact_steps;
    max_force = std::max(max_force, w.forces()[plate].norm());
    ASSERT_EQ(w.velocities()[plate], v);
    ASSERT_EQ(w.angular_velocities()[plate], omega);
  }
  const double t = w.time();
  EXPECT_NEAR((w.positions()[plate] - (x0 + t * v)).norm(), 0.0, 1e-9);
  EXPECT_NEAR(w.yaws()[plate], omega * t, 1e-12);
  expect_vertices_follow_body(w, plate);
  std::printf("kinematic plate: %d contact steps, max contact force on it %.3e N, velocity unchanged\n", contact_steps,
              max_force);
  EXPECT_GT(contact_steps, 100);
  EXPECT_GT(max_force, 1.0e3);
  for (int k = 1; k <= 6; ++k) EXPECT_GT(w.velocities()[k].x(), 0.5) << "floe " << k << " was pushed";
}

TEST(World, RestoredStateContinuesBitForBit) {
  // Two floes collide with friction: a state taken during the contact (spring history, forces) and restored into
  // a freshly built world must continue exactly as the original.
  auto build = [] {
    dynamics::WorldSettings ws;
    ws.contact.friction = 0.5;
    dynamics::World w(ws);
    const auto sq = std::make_shared<const geometry::ConvexPolygon>(geometry::ConvexPolygon::rectangle(10, 10));
    w.add_body({.id = 1, .shape = sq, .position = {0.0, 0.0}, .velocity = {1.0, 0.3}, .angular_velocity = 0.05});
    w.add_body({.id = 2, .shape = sq, .position = {10.5, 2.0}, .velocity = {-1.0, 0.0}});
    return w;
  };
  dynamics::World a = build();
  const double dt = 2e-4;
  for (int k = 0; k < 3000 && a.contact_cache().size() == 0; ++k) a.step(dt);
  for (int k = 0; k < 50; ++k) a.step(dt);
  ASSERT_GT(a.contact_cache().size(), 0u) << "the state must be taken during a contact";
  dynamics::World b = build();
  b.restore(a.state());
  for (int k = 0; k < 2000; ++k) {
    a.step(dt);
    b.step(dt);
  }
  for (std::size_t i = 0; i < 2; ++i) {
    EXPECT_EQ(std::memcmp(&a.positions()[i], &b.positions()[i], sizeof(Vec2)), 0);
    EXPECT_EQ(std::memcmp(&a.velocities()[i], &b.velocities()[i], sizeof(Vec2)), 0);
    EXPECT_EQ(a.angular_velocities()[i], b.angular_velocities()[i]);
  }
  EXPECT_EQ(a.time(), b.time());
  EXPECT_EQ(a.step_count(), b.step_count());
}

TEST(World, StateOfOtherBodiesIsRefused) {
  auto floes = [](int n) {
    dynamics::World w(no_drift());
    for (int i = 0; i < n; ++i)
      w.add_body({.id = static_cast<dynamics::BodyId>(100 + i),
                  .shape = rect(10, 10),
                  .position = {20.0 * i, 0.0},
                  .velocity = {1.0, 0.0}});
    return w;
  };
  dynamics::World a = floes(3);
  dynamics::World fewer = floes(2);
  EXPECT_THROW(fewer.restore(a.state()), std::invalid_argument);
  dynamics::WorldState s = a.state();
  s.ids[1] = 999;
  try {
    a.restore(s);
    FAIL() << "other ids must be refused";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("id 999"), std::string::npos) << e.what();
  }
  s = a.state();
  s.velocity[0] = {std::numeric_limits<double>::infinity(), 0.0};
  EXPECT_THROW(a.restore(s), std::invalid_argument);
  s = a.state();
  s.yaw.pop_back();
  EXPECT_THROW(a.restore(s), std::invalid_argument);
}
