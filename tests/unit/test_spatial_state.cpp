// The spatial world's state (dynamics/spatial_world.h SpatialWorldState): a world restored from another's state
// continues bit for bit (threads: tests/regression/test_threads.cpp); restore() refuses a state that is not this world's; and the
// state goes through a checkpoint file (run/checkpoint.h, its spatial layout) and back unchanged.
#include <gtest/gtest.h>

#include <cstring>
#include <memory>
#include <stdexcept>
#include <string>

#include "dynamics/spatial_world.h"
#include "dynamics/world.h"
#include "run/checkpoint.h"
#include "same_run.h"
#include "scratch_dir.h"

namespace {

using namespace polyfloe;
using dynamics::Quat;
using geometry::Vec3;

// A plate and four tumbling boxes thrown onto it and into each other: friction springs, manifolds, gravity.
dynamics::SpatialWorld tumbling_boxes() {
  dynamics::SpatialSettings s;
  s.contact.friction = 0.4;
  s.contact_point = dynamics::ContactPointModel::manifold;
  s.gravity = {0.0, 0.0, -9.81};
  dynamics::SpatialWorld w(s);
  dynamics::SpatialBodyDesc plate;
  plate.id = 10;
  plate.shape = std::make_shared<geometry::ConvexPolyhedron>(geometry::ConvexPolyhedron::box({20.0, 20.0, 1.0}));
  plate.position = {0.0, 0.0, -0.5};
  plate.motion = dynamics::Motion::fixed;
  w.add_body(plate);
  for (int k = 0; k < 4; ++k) {
    dynamics::SpatialBodyDesc b;
    b.id = 20 + static_cast<dynamics::BodyId>(k);
    b.shape = std::make_shared<geometry::ConvexPolyhedron>(geometry::ConvexPolyhedron::box({1.0, 0.8, 0.5}));
    b.position = {1.1 * k, 0.2 * k, 0.6};
    b.orientation = Quat(Eigen::AngleAxisd(0.1 + 0.2 * k, Vec3(1.0, 0.5 * k, 0.3).normalized()));
    b.velocity = {k % 2 ? -0.8 : 0.8, 0.3, -1.0};
    b.angular_velocity = {0.5, -1.0 * k, 0.3};
    w.add_body(b);
  }
  return w;
}

constexpr double kDt = 2e-5;  // [s], about 1/40 of the shortest contact

}  // namespace

TEST(SpatialState, ARestoredWorldContinuesBitForBit) {
  dynamics::SpatialWorld whole = tumbling_boxes();
  for (int i = 0; i < 24000; ++i) whole.step(kDt);
  ASSERT_GT(whole.contacts().size(), 1u) << "the boxes must be in contact when the state is taken";
  const dynamics::SpatialWorldState mid = whole.state();
  ASSERT_FALSE(mid.contact_history.empty()) << "the friction springs must be part of the state taken";
  for (int i = 0; i < 3000; ++i) whole.step(kDt);
  dynamics::SpatialWorld resumed = tumbling_boxes();
  resumed.restore(mid);
  for (int i = 0; i < 3000; ++i) resumed.step(kDt);
  const auto a = tsupport::state_bytes(whole.state()), b = tsupport::state_bytes(resumed.state());
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t k = 0; k < a.size(); ++k) EXPECT_TRUE(a[k].second == b[k].second) << a[k].first << " differs";
}

TEST(SpatialState, RestoreRefusesAStateThatIsNotThisWorlds) {
  dynamics::SpatialWorld w = tumbling_boxes();
  for (int i = 0; i < 24000; ++i) w.step(kDt);
  const dynamics::SpatialWorldState good = w.state();
  auto refused = [&](const char* what, auto edit, const std::string& message) {
    SCOPED_TRACE(what);
    dynamics::SpatialWorldState s = good;
    edit(s);
    dynamics::SpatialWorld fresh = tumbling_boxes();
    const dynamics::SpatialWorldState before = fresh.state();
    try {
      fresh.restore(s);
      ADD_FAILURE() << "accepted";
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find(message), std::string::npos) << e.what();
    }
    // the refused state left the world as it was
    const auto a = tsupport::state_bytes(before), b = tsupport::state_bytes(fresh.state());
    for (std::size_t k = 0; k < a.size(); ++k) EXPECT_TRUE(a[k].second == b[k].second) << a[k].first << " changed";
  };
  refused(
      "other ids", [](auto& s) { s.ids[1] = 99; }, "its bodies (ids, order) are not this world's");
  refused(
      "short velocity", [](auto& s) { s.velocity.pop_back(); }, "velocity has 4 entries for 5 bodies");
  refused(
      "NaN angular momentum", [](auto& s) { s.angular_momentum[2].y() = std::nan(""); },
      "angular_momentum of body 21 is not finite");
  refused(
      "not a unit quaternion", [](auto& s) { s.orientation[3].coeffs() *= 1.01; },
      "the orientation of body 22 is not a unit quaternion");
  refused(
      "a spring of no pair",
      [](auto& s) {
        s.contact_history.push_back({contact::PairKey{20, 77}, Vec3::Zero()});
      },
      "spring of bodies 20 and 77");
  refused(
      "the fixed plate moved", [](auto& s) { s.position[0].z() += 0.1; },
      "fixed body 10 is not where the scene puts it");
  refused(
      "the fixed plate given a velocity", [](auto& s) { s.velocity[0].x() = 1.0; },
      "fixed body 10 does not move as the scene prescribes");
  refused(
      "negative time", [](auto& s) { s.time = -1.0; }, "time must be finite and >= 0");
}

TEST(SpatialState, ACheckpointHoldsTheSpatialStateAndIsRefusedForAPlanarScene) {
  const tsupport::TestDir dir;
  dynamics::SpatialWorld w = tumbling_boxes();
  for (int i = 0; i < 24000; ++i) w.step(kDt);
  run::Checkpoint c;
  c.body_signature = run::body_signature(w);
  c.dt = kDt;
  c.frames = 1;
  c.frame_times = {w.time()};
  c.next_frame = w.time() + 0.01;
  c.spatial = w.state();
  run::write_checkpoint(dir.path() / "c.h5", c);
  const run::Checkpoint back = run::read_checkpoint(dir.path() / "c.h5");
  ASSERT_TRUE(back.spatial.has_value());
  EXPECT_EQ(back.time(), w.time());
  const auto a = tsupport::state_bytes(*c.spatial), b = tsupport::state_bytes(*back.spatial);
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t k = 0; k < a.size(); ++k) EXPECT_TRUE(a[k].second == b[k].second) << a[k].first << " differs";
  EXPECT_NO_THROW(run::check_restart(back, dir.path() / "c.h5", w));

  dynamics::World planar{dynamics::WorldSettings{}};
  try {
    run::check_restart(back, dir.path() / "c.h5", planar);
    ADD_FAILURE() << "a spatial checkpoint was accepted for a planar world";
  } catch (const run::CheckpointError& e) {
    EXPECT_NE(std::string(e.what()).find("is the checkpoint of a spatial run; the scene is planar"), std::string::npos)
        << e.what();
  }
  // Another spatial scene's bodies (one box fewer): refused by the signature.
  dynamics::SpatialSettings s;
  dynamics::SpatialWorld other(s);
  try {
    run::check_restart(back, dir.path() / "c.h5", other);
    ADD_FAILURE() << "a checkpoint of other bodies was accepted";
  } catch (const run::CheckpointError& e) {
    EXPECT_NE(std::string(e.what()).find("other bodies than the scene builds"), std::string::npos) << e.what();
  }
}
