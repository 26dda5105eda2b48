// The run guard (run/guard.h check_stability), case by case against hand-built states: a non-finite state, a
// runaway body, runaway energy spread over many bodies (none fast enough for the per-body limit), an overlap deeper
// than half the smaller floe's radius (the World tracks the deepest in its contact sum), and the messages
// naming the body, the time and the step to try; the share of the ice an MPI rank checks.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>

#include "dynamics/spatial_world.h"
#include "dynamics/world.h"
#include "forcing/drift.h"
#include "run/guard.h"

using namespace polyfloe;
using geometry::Vec2;

namespace {

dynamics::World floes(int n, const Vec2& velocity) {
  dynamics::WorldSettings ws;
  ws.drift = forcing::DriftSettings::none();
  dynamics::World w(ws);
  const auto sq = std::make_shared<const geometry::ConvexPolygon>(geometry::ConvexPolygon::rectangle(10, 10));
  for (int i = 0; i < n; ++i)
    w.add_body(
        {.id = static_cast<dynamics::BodyId>(100 + i), .shape = sq, .position = {20.0 * i, 0.0}, .velocity = velocity});
  return w;
}

std::string guard_message(const dynamics::World& w, double dt, double v_ref) {
  try {
    run::check_stability(w, w.report(), dt, v_ref);
  } catch (const run::InstabilityError& e) {
    return e.what();
  }
  return {};
}

}  // namespace

TEST(RunGuard, QuietStatePasses) { EXPECT_EQ(guard_message(floes(50, {2.0, 0.0}), 1e-3, 1.0), ""); }

TEST(RunGuard, NonFiniteStateNamesTheBodyTimeAndStep) {
  dynamics::World w = floes(3, {1.0, 0.0});
  w.set_velocity(1, {std::numeric_limits<double>::quiet_NaN(), 0.0}, 0.0);
  w.set_time(12.5, 4000);
  const std::string m = guard_message(w, 1e-3, 1.0);
  EXPECT_NE(m.find("body 101 has a non-finite state"), std::string::npos) << m;
  EXPECT_NE(m.find("t = 12.5 s"), std::string::npos) << m;
  EXPECT_NE(m.find("set run.dt to 0.00025"), std::string::npos) << m;
}

TEST(RunGuard, BodyFasterThanTheSpeedLimitNamesTheBodyAndItsSpeed) {
  dynamics::World w = floes(3, {1.0, 0.0});
  w.set_velocity(2, {60.0, 0.0}, 0.0);  // limit max(50, 20 x 1 m/s)
  const std::string m = guard_message(w, 1e-3, 1.0);
  EXPECT_NE(m.find("body 102 moves at 60 m/s"), std::string::npos) << m;
}

TEST(RunGuard, RunawayEnergySpreadOverBodiesBelowTheSpeedLimitNamesTheMostEnergetic) {
  // 40 floes at 12 m/s: none near the per-body limit of 50 m/s, but together more kinetic energy than all of them
  // at 10 x the reference speed of 1 m/s.
  dynamics::World w = floes(40, {12.0, 0.0});
  w.set_velocity(7, {12.0, 5.0}, 0.0);  // the most energetic one
  const std::string m = guard_message(w, 1e-3, 1.0);
  EXPECT_NE(m.find("runaway energy"), std::string::npos) << m;
  EXPECT_NE(m.find("the most energetic is body 107"), std::string::npos) << m;
  // At 9 m/s they are below the bound.
  EXPECT_EQ(guard_message(floes(40, {9.0, 0.0}), 1e-3, 1.0), "");
  // The bound scales with the reference speed.
  EXPECT_EQ(guard_message(floes(40, {12.0, 0.0}), 1e-3, 2.0), "");
}

// A World holding a share of the ice (an MPI rank's): check_share leaves the energy to the ranks' sum, skips the
// ghosts (their owners check them) and names the first failing body as check_stability does.
TEST(RunGuard, AShareLeavesTheEnergyToTheIceAndTheGhostsToTheirOwners) {
  dynamics::World w = floes(4, {12.0, 0.0});  // over the limit of its own mass: a share, not the ice
  run::ShareCheck c = run::check_share(w, w.report(), 1e-3, 1.0);
  EXPECT_EQ(c.motion, "");
  EXPECT_EQ(c.overlap, "");
  EXPECT_GT(c.energy, run::runaway_energy_limit(w.dynamic_mass(), 1.0));
  EXPECT_DOUBLE_EQ(run::runaway_energy_limit(2.0, 1.0), 100.0);  // 2 kg, each at 10 m/s
  EXPECT_DOUBLE_EQ(run::runaway_energy_limit(2.0, 3.0), 900.0);  // ... at 30 m/s
  w.set_velocity(2, {60.0, 0.0}, 0.0);
  w.set_velocity(3, {std::numeric_limits<double>::quiet_NaN(), 0.0}, 0.0);
  EXPECT_NE(run::check_share(w, w.report(), 1e-3, 1.0).motion.find("body 102 moves at 60 m/s"), std::string::npos);
  w.set_ghost(2, true);  // its owner's to check; the next body is
  c = run::check_share(w, w.report(), 1e-3, 1.0);
  EXPECT_NE(c.motion.find("body 103 has a non-finite state"), std::string::npos) << c.motion;
  // The most energetic of the share: ghosts and non-finite bodies left out, the lowest id of equals.
  w.set_velocity(3, {12.0, 0.0}, 0.0);
  const auto [e, id] = run::most_energetic(w);
  EXPECT_EQ(id, 100u);
  EXPECT_DOUBLE_EQ(e, 0.5 * w.mass(0) * 144.0);
  const std::string m = run::runaway_energy(w, 3.0, 2.0, 101, 1.5, 1e-3);
  EXPECT_NE(m.find("the kinetic energy of the ice, 3 J, exceeds 2 J"), std::string::npos) << m;
  EXPECT_NE(m.find("the most energetic is body 101 with 1.5 J"), std::string::npos) << m;
}

TEST(RunGuard, OverlapDeeperThanHalfTheSmallerRadiusNamesThePair) {
  // 10 m squares (equivalent radius 5.64 m, so the limit is 2.82 m): one pair overlapping by 1 m, another by
  // 3.5 m; a tiny step so that the contact-resolution check passes first.
  dynamics::WorldSettings ws;
  ws.drift = forcing::DriftSettings::none();
  dynamics::World w(ws);
  const auto sq = std::make_shared<const geometry::ConvexPolygon>(geometry::ConvexPolygon::rectangle(10, 10));
  const double x[] = {0.0, 9.0, 100.0, 106.5};
  for (int i = 0; i < 4; ++i)
    w.add_body({.id = static_cast<dynamics::BodyId>(100 + i), .shape = sq, .position = {x[i], 0.0}});
  w.compute_forces(1e-7);
  ASSERT_EQ(w.contact_count(), 2u);
  EXPECT_NEAR(w.report().deepest.ratio, 3.5 / (0.5 * std::sqrt(100.0 / M_PI)), 1e-9);
  const std::string m = guard_message(w, 1e-7, 1.0);
  EXPECT_NE(m.find("bodies 102 and 103 overlap by 3.5 m"), std::string::npos) << m;
  // Only the 1 m overlap: quiet.
  dynamics::World shallow(ws);
  for (int i = 0; i < 2; ++i)
    shallow.add_body({.id = static_cast<dynamics::BodyId>(100 + i), .shape = sq, .position = {x[i], 0.0}});
  shallow.compute_forces(1e-7);
  ASSERT_EQ(shallow.contact_count(), 1u);
  EXPECT_EQ(guard_message(shallow, 1e-7, 1.0), "");
  // The records, listed on demand, agree with the count.
  EXPECT_EQ(w.contacts().size(), 2u);
}

TEST(RunGuard, TheStepsMotionSummaryAgreesWithTheBodies) {
  // The guard clears a step from the summary the final kick gathers (the step report's motion summary). Against each body's
  // own figures: 60 floes, some spinning and some colliding, one kinematic one faster than all (left out), stepped
  // on 1 and on 2 threads: the same bits on both, the largest speed and spin exactly, the energy to round-off.
  auto make = [](int threads) {
    dynamics::World w = floes(60, {0.5, 0.0});
    for (int i = 0; i < 60; i += 7) w.set_velocity(i, {-4.5, 0.25}, 0.05 * i);
    const auto sq = std::make_shared<const geometry::ConvexPolygon>(geometry::ConvexPolygon::rectangle(4, 4));
    w.add_body({.id = 999,
                .shape = sq,
                .position = {0.0, 50.0},
                .velocity = {30.0, 0.0},
                .motion = dynamics::Motion::kinematic});
    w.set_threads(threads);
    std::size_t contacts = 0;
    for (int s = 0; s < 3000; ++s) {
      w.step(1e-3);
      contacts += w.contact_count();
    }
    EXPECT_GT(contacts, 0u) << "the floes were meant to collide";
    return w;
  };
  const dynamics::World one = make(1), two = make(2);
  const dynamics::MotionSummary &a = one.report().motion, &b = two.report().motion;
  EXPECT_TRUE(a.all_finite);
  EXPECT_EQ(std::memcmp(&a.energy, &b.energy, sizeof a.energy), 0);
  EXPECT_EQ(a.max_speed2, b.max_speed2);
  EXPECT_EQ(a.max_spin_speed, b.max_spin_speed);
  double v2 = 0.0, spin = 0.0;
  for (int i = 0; i < static_cast<int>(one.size()); ++i) {
    if (one.motion(i) != dynamics::Motion::dynamic) continue;
    v2 = std::max(v2, one.velocities()[i].squaredNorm());
    spin = std::max(spin, std::abs(one.angular_velocities()[i]) * one.shape(i).circumradius());
  }
  EXPECT_EQ(a.max_speed2, v2);
  EXPECT_EQ(a.max_spin_speed, spin);
  EXPECT_GT(spin, 0.0);
  EXPECT_NEAR(a.energy, one.kinetic_energy(), 1e-12 * one.kinetic_energy());
  EXPECT_EQ(guard_message(one, 1e-3, 1.0), "");

  // A change from outside is seen: the summary is gathered anew, and the guard names the body.
  dynamics::World w = make(2);
  w.set_velocity(31, {0.0, std::numeric_limits<double>::infinity()}, 0.0);
  EXPECT_FALSE(w.report().motion.all_finite);
  const std::string m = guard_message(w, 1e-3, 1.0);
  EXPECT_NE(m.find("body 131 has a non-finite state"), std::string::npos) << m;
}

TEST(RunGuard, ASpatialStepIsCheckedByTheSameGuardAgainstAQuarterOfTheRadius) {
  // Two 2 m cubes overlapping by 0.6 m (the spatial limit: a quarter of the smaller equivalent radius) and two by
  // 0.1 m; a spinning third cube apart. The spatial world's report names the deeper pair and its motion summary
  // agrees with the bodies; the guard reads it as the planar one's.
  dynamics::SpatialWorld w(dynamics::SpatialSettings{});
  const auto cube = std::make_shared<const geometry::ConvexPolyhedron>(geometry::ConvexPolyhedron::box({2, 2, 2}));
  const double x[] = {0.0, 1.4, 10.0, 11.9};
  for (int i = 0; i < 4; ++i)
    w.add_body({.id = static_cast<dynamics::BodyId>(100 + i), .shape = cube, .position = {x[i], 0, 0}});
  w.add_body({.id = 200, .shape = cube, .position = {30, 0, 0}, .angular_velocity = {0.0, 0.0, 2.0}});
  w.compute_forces(1e-7);
  ASSERT_EQ(w.contacts().size(), 2u);
  const dynamics::StepReport& r = w.report();
  const double limit = dynamics::SpatialWorld::kOverlapLimit * cube->equivalent_radius();
  EXPECT_EQ(r.deepest.a, 0);
  EXPECT_EQ(r.deepest.b, 1);
  EXPECT_NEAR(r.deepest.depth, 0.6, 1e-12);
  EXPECT_NEAR(r.deepest.ratio, 0.6 / limit, 1e-9);
  ASSERT_GT(r.deepest.ratio, 1.0);
  EXPECT_TRUE(r.motion.all_finite);
  EXPECT_NEAR(r.motion.max_spin_speed, 2.0 * cube->circumradius(), 1e-12);
  EXPECT_NEAR(r.motion.energy, w.kinetic_energy(), 1e-12 * w.kinetic_energy());
  std::string m;
  try {
    run::check_stability(w, r, 1e-7, 1.0);
  } catch (const run::InstabilityError& e) {
    m = e.what();
  }
  EXPECT_NE(m.find("bodies 100 and 101 overlap by 0.6 m (more than a quarter of the smaller body's equivalent"),
            std::string::npos)
      << m;
  // The shallow pair alone: quiet, though the spinning cube turns its corners at 3.5 m/s.
  dynamics::SpatialWorld shallow(dynamics::SpatialSettings{});
  for (int i = 2; i < 4; ++i)
    shallow.add_body({.id = static_cast<dynamics::BodyId>(100 + i), .shape = cube, .position = {x[i], 0, 0}});
  shallow.add_body({.id = 200, .shape = cube, .position = {30, 0, 0}, .angular_velocity = {0.0, 0.0, 2.0}});
  shallow.compute_forces(1e-7);
  ASSERT_EQ(shallow.contacts().size(), 1u);
  EXPECT_NO_THROW(run::check_stability(shallow, shallow.report(), 1e-7, 1.0));
}
