// Building a World from a scene: ids, walls, generated floes after explicit bodies, the time step, and errors that
// name the bodies' sources.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "geometry/space_order.h"
#include "scene/floe_field.h"
#include "scene/scene_reader.h"
#include "scene_test_support.h"

namespace polyfloe::scene {
namespace {

BodySpec square(const Vec2& position, double side = 2.0) {
  BodySpec b;
  const double h = 0.5 * side;
  b.polygon = {{-h, -h}, {h, -h}, {h, h}, {-h, h}};
  b.position = position;
  return b;
}

TEST(BuildWorld, TwoFloesSceneBuildsItsBodiesAndTheStepIsAFortiethContactUnlessDtIsGiven) {
  const Scene s = read_scene(kSceneDir + "two_floes.yaml", {});
  const dynamics::World w = build_world(s);
  ASSERT_EQ(w.size(), 2u);
  EXPECT_EQ(w.id(0), 0u);
  EXPECT_EQ(w.id(1), 1u);
  EXPECT_NEAR(w.positions()[0].x(), -6.0, 1e-12);
  EXPECT_NEAR(w.positions()[1].x(), 6.0, 1e-12);
  EXPECT_EQ(w.velocities()[1], Vec2(-1.0, 0.0));
  EXPECT_NEAR(w.mass(0), 920.0 * 100.0, 1e-6);
  EXPECT_EQ(reference_speed(s), 2.0);
  EXPECT_EQ(w.settings().contact.reference_speed, 2.0);
  const double dt = time_step(s, w);
  EXPECT_NEAR(dt, w.shortest_contact_duration(2.0) / 40.0, 1e-15);
  EXPECT_GT(dt, 0.0);
  Scene fixed = s;
  fixed.time.dt = 1e-4;
  EXPECT_EQ(time_step(fixed, w), 1e-4);
}

// Under the foundation force model the automatic step resolves the Hertz contacts by run.steps_per_contact and the
// flat faces by run.steps_per_flat_contact (auto: the same), each on its own; other models have no flat term.
TEST(BuildWorld, TheFoundationModelsFlatFacesTakeTheirOwnStepsPerContact) {
  Scene s = read_scene(kSceneDir + "two_floes.yaml", {"contact.force_model=foundation"});
  const dynamics::World w = build_world(s);
  const double hertz = w.shortest_hertz_contact_duration(2.0), flat = w.shortest_flat_contact_duration();
  ASSERT_LT(flat, hertz);  // two 10 m squares: the flat face is the shorter contact
  EXPECT_EQ(time_step(s, w), std::min(hertz, flat) / 40.0);
  s.time.steps_per_flat_contact = 20.0;
  EXPECT_EQ(time_step(s, w), std::min(hertz / 40.0, flat / 20.0));
  s.time.steps_per_flat_contact = 400.0;
  EXPECT_EQ(time_step(s, w), flat / 400.0);
  const Scene centroid = read_scene(kSceneDir + "two_floes.yaml", {});
  EXPECT_TRUE(std::isinf(build_world(centroid).shortest_flat_contact_duration()));
}

// Found by fuzzing (tests/fuzz/regressions/fuzz_scene_parser/check-step-count-overflows-long-long.yaml): a run of
// 1e300 s converted ceil(duration / dt) to a 64-bit integer (undefined behaviour; `check` printed a negative count).
TEST(BuildWorld, MoreStepsThanARunMayTakeIsAnError) {
  Scene s;
  s.source_path = "long.yaml";
  s.bodies = {square({0, 0})};
  const dynamics::World w = build_world(s);
  for (const double duration : {1e300, 1.1e9}) {
    s.time.duration = duration;
    s.time.dt = 1e-3;
    SCOPED_TRACE(duration);
    try {
      (void)time_step(s, w);
      ADD_FAILURE() << "accepted";
    } catch (const SceneError& e) {
      const std::string m = e.what();
      EXPECT_NE(m.find("long.yaml: run.duration"), std::string::npos) << m;
      EXPECT_NE(m.find("more than the 1e+12 a run may take; shorten run.duration or raise run.dt"), std::string::npos)
          << m;
    }
  }
  s.time.duration = 1e8;  // 1e11 steps: allowed, with frames no more often than 10^6 in all
  s.output.interval = 1e3;
  EXPECT_EQ(time_step(s, w), 1e-3);
  // Frames: one per interval, at most one per step, at most 10^6 in all; the message names output.interval.
  s.output.interval = 5.0;
  try {
    (void)time_step(s, w);
    ADD_FAILURE() << "2e7 frames accepted";
  } catch (const SceneError& e) {
    EXPECT_NE(std::string(e.what()).find("output.interval 5 s over run.duration 1e+08 s is 2e+07 frames"),
              std::string::npos)
        << e.what();
  }
  s.time.duration = 1e4;
  s.output.interval = 1e-9;  // 1e13 intervals, but a frame at most every step: 1e7 frames
  EXPECT_THROW((void)time_step(s, w), SceneError);
  s.time.duration = 10.0;  // 1e4 steps, a frame at every one: allowed
  EXPECT_EQ(time_step(s, w), 1e-3);
}

// The generated floes, bodies first..size()-1: their ids are first, first + 1, ... numbered largest first (the
// generator's), and they are stored in space order (geometry::space_key on cells of 4 x their mean equivalent
// radius, as the World sorts its slots).
void expect_field_in_space_order(const dynamics::World& w, int first) {
  const int n = static_cast<int>(w.size());
  ASSERT_GT(n - first, 10);
  std::vector<int> by_id(static_cast<std::size_t>(n - first), -1);
  double radius_sum = 0.0;
  for (int i = first; i < n; ++i) {
    const auto k = static_cast<std::size_t>(w.id(i)) - static_cast<std::size_t>(first);
    ASSERT_LT(k, by_id.size()) << "body " << i << " has id " << w.id(i);
    EXPECT_EQ(by_id[k], -1) << "id " << w.id(i) << " twice";
    by_id[k] = i;
    radius_sum += w.shape(i).equivalent_radius();
  }
  for (std::size_t k = 1; k < by_id.size(); ++k)
    EXPECT_LE(w.shape(by_id[k]).area(), w.shape(by_id[k - 1]).area() * (1.0 + 1e-12)) << "ids not largest first";
  const double cell = 4.0 * radius_sum / (n - first);
  std::size_t out_of_order = 0, moved = 0;
  for (int i = first + 1; i < n; ++i) {
    out_of_order += geometry::space_key(w.positions()[i], cell) < geometry::space_key(w.positions()[i - 1], cell);
    moved += w.id(i) != static_cast<dynamics::BodyId>(i);
  }
  EXPECT_EQ(out_of_order, 0u);
  EXPECT_GT(moved, static_cast<std::size_t>(n - first) / 2) << "the space order should differ from the size order";
}

TEST(BuildWorld, ChannelSceneHasSixWallsFirstThenItsFieldInSpaceOrderAndFreeDriftAsReferenceSpeed) {
  const Scene s = read_scene(kSceneDir + "channel.yaml", {});
  const double v = forcing::free_drift_velocity(s.world.drift, s.ocean_field.velocity, s.wind_field.velocity).norm();
  EXPECT_GT(v, 4.0);
  EXPECT_EQ(reference_speed(s), std::max(1.0, v));
  const dynamics::World w = build_world(s);
  EXPECT_EQ(w.settings().contact.reference_speed, reference_speed(s));
  ASSERT_GT(w.size(), 1006u);
  for (int i = 0; i < 6; ++i) {
    EXPECT_EQ(w.id(i), static_cast<dynamics::BodyId>(i));
    EXPECT_EQ(w.motion(i), dynamics::Motion::fixed);
  }
  for (int i = 6; i < static_cast<int>(w.size()); ++i) EXPECT_EQ(w.motion(i), dynamics::Motion::dynamic);
  expect_field_in_space_order(w, 6);
  EXPECT_GT(time_step(s, w), 0.0);
}

TEST(BuildWorld, GivenIdsAreKeptAndABodyWithoutOneGetsTheSmallestFreeId) {
  Scene s;
  s.bodies = {square({0, 0}), square({10, 0}), square({20, 0})};
  s.bodies[1].id = 0;
  s.bodies[2].id = 5;
  const dynamics::World w = build_world(s);
  EXPECT_EQ(w.id(0), 1u);
  EXPECT_EQ(w.id(1), 0u);
  EXPECT_EQ(w.id(2), 5u);
}

TEST(BuildWorld, ErrorsNameTheSources) {
  Scene s;
  s.bodies = {square({0, 0}), square({10, 0})};
  s.bodies[0].source.where = "a.yaml:3:5";
  s.bodies[1].source.where = "a.yaml:7:5";
  s.bodies[0].id = s.bodies[1].id = 4;
  std::string m = error_of([&] { build_world(s); });
  EXPECT_EQ(m, "a.yaml:7:5 (floes.1): id 4 is already used by a.yaml:3:5 (floes.0)");

  s.bodies[1].id.reset();
  s.bodies[1].position = {1.5, 0.5};
  m = error_of([&] { build_world(s); });
  EXPECT_TRUE(starts_with(m, "a.yaml:7:5 (floes.1): overlaps a.yaml:3:5 (floes.0) initially")) << m;

  s.bodies[1].position = {2.0, 0.0};  // touching edge to edge is fine
  EXPECT_NO_THROW(build_world(s));

  s.bodies[1].polygon = {{0, 0}, {0, 1}, {1, 0}};  // clockwise
  m = error_of([&] { build_world(s); });
  EXPECT_TRUE(starts_with(m, "a.yaml:7:5 (floes.1): polygon: vertices are clockwise")) << m;

  Scene c;
  c.bodies = {square({500, -10}, 4.0)};  // inside the lower basin wall
  c.bodies[0].source.where = "c.yaml:9:5";
  c.channel = ChannelSpec{};
  c.channel->source.where = "c.yaml:20:3";
  m = error_of([&] { build_world(c); });
  EXPECT_TRUE(starts_with(m, "c.yaml:9:5 (floes.0): overlaps c.yaml:20:3 (channel basin wall (y min)) initially")) << m;
  c.bodies[0].motion = dynamics::Motion::fixed;  // fixed bodies may overlap walls
  EXPECT_NO_THROW(build_world(c));
}

TEST(BuildWorld, GeneratedFloesAvoidExplicitBodiesAndComeLast) {
  Scene s;
  BodySpec island = square({100, 100}, 60.0);
  island.motion = dynamics::Motion::fixed;
  s.bodies = {island};
  FloeFieldSpec f;
  f.region_max = {200.0, 200.0};
  f.size_max = 30.0;
  f.concentration = 0.4;
  s.floe_field = f;
  const dynamics::World w = build_world(s);
  ASSERT_GT(w.size(), 10u);
  const std::vector<Vec2> island_world(w.world_vertices(0).begin(), w.world_vertices(0).end());
  expect_field_in_space_order(w, 1);
  for (int i = 1; i < static_cast<int>(w.size()); ++i) {
    const std::vector<Vec2> v(w.world_vertices(i).begin(), w.world_vertices(i).end());
    EXPECT_GT(polygon_separation(v, island_world), 0.0) << i;
  }
}

}  // namespace
}  // namespace polyfloe::scene
