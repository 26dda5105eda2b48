// Scene reader: defaults, the example scenes, every kind of error with its location, --set overrides (the resolved
// YAML round trip: test_resolved_yaml.cpp; building worlds from scenes: test_build_world.cpp).
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include "forcing/drift.h"
#include "scene/floe_field.h"
#include "scene/scene_reader.h"
#include "scene_compare.h"
#include "scene_test_support.h"

namespace polyfloe::scene {
namespace {

// --- defaults and example scenes ---

TEST(SceneReader, DefaultsFillEverythingNotGiven) {
  const Scene s = parse_scene(kOneFloe, "dir/my_scene.yaml", {});
  const Scene d;                  // the defaults of scene.h
  EXPECT_EQ(s.name, "my_scene");  // the file's stem
  EXPECT_EQ(s.source_path, "dir/my_scene.yaml");
  EXPECT_EQ(s.source_text, kOneFloe);
  EXPECT_FALSE(s.time.dt.has_value());
  EXPECT_FALSE(s.time.reference_speed.has_value());
  EXPECT_EQ(s.world.broad_phase_cell, 0.0);
  EXPECT_FALSE(s.floe_field.has_value());
  EXPECT_FALSE(s.ice_sheet.has_value());
  EXPECT_FALSE(s.channel.has_value());
  ASSERT_EQ(s.bodies.size(), 1u);
  const BodySpec& b = s.bodies[0];
  EXPECT_EQ(b.polygon.size(), 6u);
  EXPECT_NEAR(b.polygon[0].x(), 5.0, 1e-15);
  EXPECT_EQ(b.motion, dynamics::Motion::dynamic);
  EXPECT_EQ(b.thickness, 1.0);
  EXPECT_FALSE(b.id.has_value());
  EXPECT_EQ(b.source.where, "dir/my_scene.yaml:2:5");
  Scene expected = d;
  expected.name = "my_scene";
  expected.bodies = s.bodies;
  expect_same_settings(s, expected);
}

TEST(SceneReader, ChannelSceneGivesEveryValueInTheFileAndWhereTheFloeFieldWasGiven) {
  const Scene s = read_scene(kSceneDir + "channel.yaml", {});
  EXPECT_EQ(s.name, "channel");
  EXPECT_EQ(s.time.duration, 300.0);
  EXPECT_FALSE(s.time.dt.has_value());
  EXPECT_EQ(s.output.interval, 5.0);
  EXPECT_EQ(s.ice_density, 920.0);
  EXPECT_EQ(s.world.contact.youngs_modulus, 1.0e9);
  EXPECT_EQ(s.world.contact.poisson_ratio, 0.3);
  EXPECT_EQ(s.world.contact.restitution, 0.5);
  EXPECT_EQ(s.world.contact.friction, 0.3);
  EXPECT_EQ(s.ocean_field.kind, forcing::FieldKind::uniform);
  EXPECT_EQ(s.ocean_field.velocity, Vec2(4.0, 0.0));
  EXPECT_EQ(s.wind_field.velocity, Vec2(20.0, 0.0));
  EXPECT_EQ(s.world.drift.water_density, 1025.0);
  EXPECT_EQ(s.world.drift.air_density, 1.2);
  EXPECT_EQ(s.world.drift.skin_drag_coefficient, 0.0055);
  EXPECT_EQ(s.world.drift.air_drag_coefficient, 0.0012);
  ASSERT_TRUE(s.floe_field.has_value());
  EXPECT_EQ(s.floe_field->concentration, 0.5);
  EXPECT_EQ(s.floe_field->region_max, Vec2(1000.0, 1000.0));
  EXPECT_EQ(s.floe_field->size_min, 5.0);
  EXPECT_EQ(s.floe_field->size_max, 100.0);
  EXPECT_EQ(s.floe_field->exponent, 2.0);
  EXPECT_EQ(s.floe_field->corners_min, 5);
  EXPECT_EQ(s.floe_field->corners_max, 10);
  EXPECT_EQ(s.floe_field->seed, 1u);
  ASSERT_TRUE(s.channel.has_value());
  EXPECT_EQ(s.channel->opening, 250.0);
  EXPECT_EQ(s.channel->basin_x_min, -100.0);
  EXPECT_EQ(s.channel->basin_x_max, 1100.0);
  EXPECT_EQ(s.channel->funnel_length, 300.0);
  EXPECT_EQ(s.channel->strait_length, 600.0);
  EXPECT_EQ(s.channel->wall_thickness, 50.0);
  EXPECT_TRUE(s.bodies.empty());
  EXPECT_TRUE(starts_with(s.floe_field->source.where, kSceneDir + "channel.yaml:"));
}

TEST(SceneReader, TwoFloesSceneHasTwoFloesClosingAtItsReferenceSpeedWithSkinAndAirDragOff) {
  const Scene s = read_scene(kSceneDir + "two_floes.yaml", {});
  ASSERT_EQ(s.bodies.size(), 2u);
  EXPECT_EQ(s.bodies[0].velocity, Vec2(1.0, 0.0));
  EXPECT_EQ(s.bodies[1].velocity, Vec2(-1.0, 0.0));
  EXPECT_EQ(s.bodies[0].polygon.size(), 4u);
  EXPECT_FALSE(s.world.drift.skin_drag);
  EXPECT_FALSE(s.world.drift.air_drag);
  EXPECT_EQ(s.time.reference_speed, 2.0);
}

TEST(SceneReader, CubePlateSceneParsesAndReadsBack) {
  const Scene s = read_scene(kSceneDir + "cube_plate.yaml", {});
  ASSERT_TRUE(s.spatial.has_value());
  EXPECT_TRUE(s.bodies.empty());
  ASSERT_EQ(s.spatial->bodies.size(), 2u);
  EXPECT_EQ(s.spatial->bodies[0].motion, dynamics::Motion::fixed);
  EXPECT_EQ(s.spatial->bodies[1].box, geometry::Vec3(2.0, 2.0, 2.0));
  EXPECT_NEAR(s.spatial->bodies[1].rotation_angle, 15.0 * std::numbers::pi / 180.0, 1e-15);
  EXPECT_EQ(s.spatial->narrow_phase, dynamics::SpatialNarrowPhase::sat);
  EXPECT_EQ(s.spatial->contact_point, dynamics::ContactPointModel::witness);
  expect_round_trip(s);
}

TEST(SceneReader, SpatialKeysReadBack) {
  const Scene s = parse_scene(
      "spatial:\n"
      "  gravity: [0, 0, -9.81]\n"
      "  buoyancy: true\n"
      "  water_level: 0.5\n"
      "  water_density: 1000\n"
      "  narrow_phase: mpr\n"
      "  contact_point: manifold\n"
      "  bodies:\n"
      "    - polygon: [[0, 0], [4, 0], [2, 3]]\n"
      "      thickness: 1.5\n"
      "      position: [1, 2, 3]\n"
      "      rotation: {axis: [1, 1, 0], angle: 0.25}\n"
      "      velocity: [0.5, 0, 0]\n"
      "      angular_velocity: [0, 0.1, 0]\n"
      "      density: 900\n"
      "      id: 7\n"
      "    - box: [10, 10, 1]\n"
      "      position: [0, 0, -5]\n"
      "      motion: fixed\n",
      "spatial.yaml", {});
  ASSERT_TRUE(s.spatial.has_value());
  EXPECT_EQ(s.spatial->gravity, geometry::Vec3(0.0, 0.0, -9.81));
  EXPECT_TRUE(s.spatial->buoyancy);
  EXPECT_EQ(s.spatial->narrow_phase, dynamics::SpatialNarrowPhase::mpr);
  EXPECT_EQ(s.spatial->contact_point, dynamics::ContactPointModel::manifold);
  EXPECT_EQ(s.spatial->bodies[0].density, 900.0);
  EXPECT_EQ(s.spatial->bodies[0].id, 7u);
  EXPECT_EQ(s.spatial->bodies[0].polygon.size(), 3u);
  expect_round_trip(s);
  // The world: ids as given, then the next free; the prism's mass from its density.
  const auto w = build_spatial_world(s);
  ASSERT_EQ(w.size(), 2u);
  EXPECT_EQ(w.id(0), 7u);
  EXPECT_EQ(w.id(1), 0u);
  EXPECT_NEAR(w.mass(0), 900.0 * 6.0 * 1.5, 1e-9);
}

TEST(SceneReader, EveryFloeKeyReadsBackWithYawDegInRadiansAndTheFloesFileLine) {
  const Scene s = parse_scene(
      "floes:\n"
      "  - rectangle: {width: 20, height: 2}\n"
      "    position: [1, 2]\n"
      "    yaw_deg: 90\n"
      "    velocity: [0.5, -0.5]\n"
      "    angular_velocity: 0.1\n"
      "    thickness: 2\n"
      "    motion: kinematic\n"
      "    id: 7\n"
      "    external_force: [10, 0]\n"
      "    external_torque: -3\n"
      "  - polygon: [[0, 0], [4, 0], [0, 3]]\n"
      "    yaw: 0.25\n",
      "b.yaml", {});
  ASSERT_EQ(s.bodies.size(), 2u);
  const BodySpec& r = s.bodies[0];
  EXPECT_EQ(r.polygon, (std::vector<Vec2>{{-10, -1}, {10, -1}, {10, 1}, {-10, 1}}));
  EXPECT_EQ(r.position, Vec2(1, 2));
  EXPECT_DOUBLE_EQ(r.yaw, std::numbers::pi / 2);
  EXPECT_EQ(r.angular_velocity, 0.1);
  EXPECT_EQ(r.thickness, 2.0);
  EXPECT_EQ(r.motion, dynamics::Motion::kinematic);
  EXPECT_EQ(r.id, 7u);
  EXPECT_EQ(r.external_force, Vec2(10, 0));
  EXPECT_EQ(r.external_torque, -3.0);
  EXPECT_EQ(s.bodies[1].yaw, 0.25);
  EXPECT_EQ(s.bodies[1].source.where, "b.yaml:12:5");
}

// coordinates: world keeps a polygon where its vertices are: the body goes to the polygon's area centroid (a
// triangle's: the vertices' mean), so its outline lands on the given vertices. Refused with position or yaw, or for
// a centred shape.
TEST(SceneReader, APolygonInWorldCoordinatesStaysWhereItIs) {
  const Scene s = parse_scene(
      "floes:\n"
      "  - polygon: [[100, 0], [130, 0], [100, 30]]\n"
      "    coordinates: world\n"
      "    motion: fixed\n"
      "  - polygon: [[0, 0], [4, 0], [0, 3]]\n"
      "    coordinates: body\n"
      "    position: [50, 50]\n",
      "w.yaml", {});
  EXPECT_LT((s.bodies[0].position - Vec2(110, 10)).norm(), 1e-12);
  EXPECT_EQ(s.bodies[1].position, Vec2(50, 50));
  const dynamics::World w = build_world(s);
  std::vector<Vec2> v(w.world_vertices(0).begin(), w.world_vertices(0).end());
  ASSERT_EQ(v.size(), 3u);
  EXPECT_LT((v[0] - Vec2(100, 0)).norm(), 1e-12);
  EXPECT_LT((v[1] - Vec2(130, 0)).norm(), 1e-12);
  EXPECT_LT((v[2] - Vec2(100, 30)).norm(), 1e-12);
  // Read back from the resolved scene (body coordinates, the centroid as position): the same body.
  expect_same_settings(s, parse_scene(resolved_yaml(s), "r.yaml", {}));
  for (const char* extra : {"    position: [1, 2]\n", "    yaw: 0.5\n", "    yaw_deg: 5\n"})
    EXPECT_NE(
        parse_error("floes:\n  - polygon: [[0, 0], [4, 0], [0, 3]]\n    coordinates: world\n" + std::string(extra))
            .find("coordinates: world takes the body's place from its polygon: remove"),
        std::string::npos)
        << extra;
  EXPECT_NE(parse_error("floes:\n  - regular: {sides: 5, radius: 2}\n    coordinates: world\n")
                .find("'regular' and 'rectangle' are centred shapes"),
            std::string::npos);
  EXPECT_NE(parse_error("floes:\n  - polygon: [[0, 0], [4, 0], [0, 3]]\n    coordinates: global\n")
                .find("expected body or world"),
            std::string::npos);
}

TEST(SceneReader, AutoLeavesDtUnsetAndBroadPhaseZeroAndNumbersWithAPlusSignReadAsGiven) {
  const Scene s = parse_scene(std::string(kOneFloe) +
                                  "run: {dt: 1.0e-4, reference_speed: +2.5, steps_per_contact: 50}\n"
                                  "contact: {broad_phase_cell: 30, broad_phase_skin: 0.5, damping_model: paper}\n",
                              "t.yaml", {});
  EXPECT_EQ(s.time.dt, 1.0e-4);
  EXPECT_EQ(s.time.reference_speed, 2.5);
  EXPECT_EQ(s.time.steps_per_contact, 50.0);
  EXPECT_EQ(s.world.broad_phase_cell, 30.0);
  EXPECT_EQ(s.world.broad_phase_skin, 0.5);
  EXPECT_EQ(s.world.contact.damping, contact::DampingModel::paper);
  const Scene a = parse_scene(
      std::string(kOneFloe) + "run: {dt: auto}\ncontact: {broad_phase_cell: auto, broad_phase_skin: auto}\n", "t.yaml",
      {});
  EXPECT_FALSE(a.time.dt.has_value());
  EXPECT_EQ(a.world.broad_phase_cell, 0.0);
  EXPECT_EQ(a.world.broad_phase_skin, 0.0);
}

// --- errors, each with where and which key ---

TEST(SceneErrors, UnknownKeyNamesLineAndAllowedKeys) {
  const std::string m = parse_error(std::string(kOneFloe) +
                                    "contact:\n"
                                    "  restitution: 0.5\n"
                                    "  restitutoin: 0.4\n");
  EXPECT_TRUE(starts_with(m,
                          "t.yaml:5:3: unknown key 'contact.restitutoin'; allowed in 'contact': restitution, "
                          "friction, damping_model, narrow_phase, force_model, broad_phase_cell, broad_phase_skin"))
      << m;
  const std::string top = parse_error(std::string(kOneFloe) + "flooes: []\n");
  EXPECT_TRUE(starts_with(top, "t.yaml:3:1: unknown key 'flooes'; allowed at the top level: name, run, ")) << top;
  const std::string nested = parse_error("floes:\n  - regular: {sides: 6, radius: 5, angle: 3}\n");
  EXPECT_TRUE(starts_with(nested,
                          "t.yaml:2:36: unknown key 'floes.0.regular.angle'; allowed in 'floes.0.regular': "
                          "sides, radius"))
      << nested;
}

// Found by fuzzing (tests/fuzz/regressions/fuzz_scene_parser/slender-rectangle-does-not-read-back.yaml): a
// rectangle or regular polygon was only checked when the world was built, so resolved_yaml() wrote it as a polygon
// that did not read back. Both are checked by the reader now, at the key's line.
TEST(SceneErrors, UnusableRectangleOrRegularPolygonIsRefusedByTheReader) {
  std::string m = parse_error("floes:\n  - rectangle: {width: 1e-6, height: 1e9}\n");
  EXPECT_TRUE(
      contains(m, "t.yaml:2:16: key 'floes.0.rectangle': the rectangle's outline is unusable: vertices 0 and 1"))
      << m;
  m = parse_error("floes:\n  - regular: {sides: 5, radius: 1e-70}\n");
  EXPECT_TRUE(contains(m,
                       "t.yaml:2:14: key 'floes.0.regular': the regular polygon's outline is unusable: the "
                       "polygon's size"))
      << m;
}

// yaml-cpp 0.7 takes a quoted string left open at the end of the file as the rest of the file; a control byte
// means the file is not text. Both are syntax errors with the line.
TEST(SceneErrors, UnclosedQuoteAndControlByteAreRefusedAtTheirLineAndColumn) {
  std::string m = parse_error("run: {duration: 1}\nname: \"abc\nfloes: []\n");
  EXPECT_TRUE(contains(m, "t.yaml:2:7: YAML syntax error: the quoted string that starts here is never closed")) << m;
  m = parse_error("name: 'it''s\n");
  EXPECT_TRUE(contains(m, "t.yaml:1:7: YAML syntax error: the quoted string")) << m;
  m = parse_error("run: {duration: 1}\n  \x01\n");
  EXPECT_TRUE(contains(m, "t.yaml:2:3: not a text file: control byte 0x01")) << m;
  const Scene s = parse_scene("name: \"a \\\" b\"\nfloes:\n  - rectangle: {width: 1, height: 1}\n", "ok.yaml", {});
  EXPECT_EQ(s.name, "a \" b");
  m = parse_error("name: \"../up\"\n");
  EXPECT_TRUE(contains(m, "t.yaml:1:7: key 'name': expected a name usable as a folder name")) << m;
}

TEST(SceneErrors, WrongTypeNamesTheLineKeyExpectedTypeAndWhatWasGiven) {
  std::string m = parse_error(std::string(kOneFloe) + "run:\n  duration: long\n");
  EXPECT_EQ(m, "t.yaml:4:13: key 'run.duration': expected a number [s], got 'long'");
  m = parse_error(std::string(kOneFloe) + "run:\n  duration: '300'\n");
  EXPECT_TRUE(starts_with(m, "t.yaml:4:13: key 'run.duration': expected a number [s], got the quoted string")) << m;
  m = parse_error(std::string(kOneFloe) + "run: 5\n");
  EXPECT_TRUE(starts_with(m, "t.yaml:3:6: key 'run': expected a block of keys (a map), got '5'")) << m;
  m = parse_error(std::string(kOneFloe) + "forcing:\n  ocean:\n    current: [1, 2, 3]\n");
  EXPECT_TRUE(starts_with(m, "t.yaml:5:14: key 'forcing.ocean.current': expected a list of 2 numbers [x, y] [m/s]"))
      << m;
  m = parse_error(std::string(kOneFloe) + "output:\n  vtk: maybe\n");
  EXPECT_EQ(m, "t.yaml:4:8: key 'output.vtk': expected true or false, got 'maybe'");
  m = parse_error(std::string(kOneFloe) + "contact: {damping_model: fast}\n");
  EXPECT_TRUE(contains(m, "key 'contact.damping_model': expected one of speed_independent, paper, got 'fast'")) << m;
  m = parse_error(std::string(kOneFloe) + "contact: {force_model: energy}\n");
  EXPECT_TRUE(contains(m, "key 'contact.force_model': expected one of centroid, gradient, foundation, got 'energy'"))
      << m;
  // The foundation model integrates over the overlap polygon, which the paper's GJK-EPA does not give.
  m = parse_error(std::string(kOneFloe) + "contact: {force_model: foundation, narrow_phase: gjk_epa}\n");
  EXPECT_TRUE(contains(m, "key 'contact.narrow_phase': force_model 'foundation'") &&
              contains(m, "set narrow_phase: exact"))
      << m;
  m = parse_error(std::string(kOneFloe) + "run: {dt: soon}\n");
  EXPECT_TRUE(contains(m, "key 'run.dt': expected a number [s] or 'auto', got 'soon'")) << m;
  m = parse_error(std::string(kOneFloe) + "floe_field: {corners: [5, 7.5]}\n");
  EXPECT_TRUE(contains(m, "key 'floe_field.corners.1': expected an integer in [3, 64], got '7.5'")) << m;
  m = parse_error(std::string(kOneFloe) + "floe_field: {seed: -1}\n");
  EXPECT_TRUE(contains(m, "key 'floe_field.seed': expected a non-negative integer")) << m;
  m = parse_error("floes: {a: 1}\n");
  EXPECT_TRUE(starts_with(m, "t.yaml:1:8: key 'floes': expected a list of floes")) << m;
}

TEST(SceneErrors, OutOfRangeSaysTheRangeAndUnit) {
  std::string m = parse_error(std::string(kOneFloe) + "contact:\n  restitution: 1.5\n");
  EXPECT_EQ(m, "t.yaml:4:16: key 'contact.restitution': 1.5 is outside the allowed range (0, 1] [-]");
  m = parse_error(std::string(kOneFloe) + "run: {duration: -5}\n");
  EXPECT_EQ(m, "t.yaml:3:17: key 'run.duration': -5 is outside the allowed range (0, inf) [s]");
  m = parse_error(std::string(kOneFloe) + "ice: {poisson_ratio: 0.5}\n");
  EXPECT_TRUE(contains(m, "key 'ice.poisson_ratio': 0.5 is outside the allowed range [0, 0.5) [-]")) << m;
  m = parse_error(std::string(kOneFloe) + "run: {steps_per_contact: 9}\n");
  EXPECT_TRUE(contains(m, "[10, inf) [-]")) << m;
  m = parse_error(std::string(kOneFloe) + "floe_field: {concentration: 0.8}\n");
  EXPECT_TRUE(contains(m, "key 'floe_field.concentration': 0.8 is outside the allowed range (0, 0.7] [-]")) << m;
  m = parse_error("floe_field:\n  size: {min: 10, max: 5}\n");
  EXPECT_TRUE(starts_with(m, "t.yaml:2:24: key 'floe_field.size.max': size.max = 5 m must be >= size.min = 10 m")) << m;
  m = parse_error("floe_field:\n  region: [0, 0, -10, 100]\n");
  EXPECT_TRUE(contains(m, "key 'floe_field.region.2': xmax = -10 must be > xmin = 0 [m]")) << m;
}

TEST(SceneErrors, NonFiniteNumbersAreRejected) {
  for (const char* bad : {".nan", ".NaN", ".inf", "-.inf", "1e999"}) {
    const std::string m = parse_error(std::string(kOneFloe) + "contact:\n  friction: " + bad + "\n");
    EXPECT_TRUE(starts_with(m, "t.yaml:4:13: key 'contact.friction': ")) << m;
    EXPECT_TRUE(contains(m, "is not a finite number")) << m;
  }
  const std::string m = parse_error("floes:\n  - polygon: [[0, 0], [1, .nan], [0, 1]]\n");
  EXPECT_TRUE(starts_with(m, "t.yaml:2:27: key 'floes.0.polygon.1.1': .nan is not a finite number")) << m;
}

TEST(SceneErrors, MissingRequiredKeysOrBothOfTwoExclusiveKeysAreRefusedNamingTheKeys) {
  std::string m = parse_error("floes:\n  - position: [0, 0]\n");
  EXPECT_TRUE(starts_with(m,
                          "t.yaml:2:5: key 'floes.0': missing the shape: give one of 'polygon', 'regular' or "
                          "'rectangle'"))
      << m;
  m = parse_error("floes:\n  - regular: {sides: 6}\n");
  EXPECT_TRUE(contains(m, "key 'floes.0.regular': missing required key 'radius'")) << m;
  m = parse_error("floes:\n  - rectangle: {width: 1, height: 1}\n    regular: {sides: 3, radius: 1}\n");
  EXPECT_TRUE(contains(m, "give only one of")) << m;
  m = parse_error("floes:\n  - regular: {sides: 3, radius: 1}\n    yaw: 1\n    yaw_deg: 3\n");
  EXPECT_TRUE(contains(m, "give only one of 'yaw' [rad] and 'yaw_deg' [deg]")) << m;
}

TEST(SceneErrors, ClockwiseNonConvexOrTwoPointPolygonsAreRefusedWithTheReason) {
  std::string m = parse_error("floes:\n  - polygon: [[0, 0], [0, 1], [1, 0]]\n");  // clockwise
  EXPECT_TRUE(starts_with(m, "t.yaml:2:14: key 'floes.0.polygon': vertices are clockwise")) << m;
  m = parse_error("floes:\n  - polygon: [[0, 0], [2, 0], [1, 0.1], [2, 2], [0, 2]]\n");
  EXPECT_TRUE(contains(m, "not strictly convex")) << m;
  m = parse_error("floes:\n  - polygon: [[0, 0], [1, 0]]\n");
  EXPECT_TRUE(contains(m, "at least 3 points")) << m;
}

TEST(SceneErrors, DuplicateKeyOrIdIsRefusedAtItsSecondUseNamingTheFirst) {
  std::string m = parse_error(std::string(kOneFloe) + "run: {duration: 1, duration: 2}\n");
  EXPECT_TRUE(starts_with(m, "t.yaml:3:20: key 'run.duration': duplicate key (first given at t.yaml:3:7)")) << m;
  m = parse_error("floes:\n  - {regular: {sides: 3, radius: 1}, id: 4}\n  - {regular: {sides: 3, radius: 1}, id: 4}\n");
  EXPECT_TRUE(starts_with(m, "t.yaml:3:42: key 'floes.1.id': id 4 is already used by floes.0 (t.yaml:2:5)")) << m;
}

TEST(SceneErrors, EmptyOrAllFixedSceneHasNoDynamicBodyAndANonMapSceneIsRefused) {
  EXPECT_TRUE(contains(parse_error(""), "the scene has no dynamic body"));
  EXPECT_TRUE(contains(parse_error("floes:\n  - {regular: {sides: 3, radius: 1}, motion: fixed}\n"),
                       "the scene has no dynamic body"));
  EXPECT_TRUE(starts_with(parse_error("[1, 2]"), "t.yaml:1:1: a scene is a block of keys"));
}

TEST(SceneErrors, YamlSyntaxNamesFileAndLine) {
  const std::string m = parse_error("floes:\n  - regular: {sides: 6, radius: 5\nrun:\n  duration: 3\n");
  EXPECT_TRUE(starts_with(m, "t.yaml:")) << m;
  EXPECT_TRUE(contains(m, "YAML syntax error")) << m;
  const std::string tab = parse_error("run:\n  duration: 3\n\tdt: 1\n");
  EXPECT_TRUE(starts_with(tab, "t.yaml:3:")) << tab;
}

TEST(SceneErrors, MissingFileNamesTheFile) {
  const std::string m = error_of([] { read_scene("/nonexistent/dir/scene.yaml", {}); });
  EXPECT_TRUE(starts_with(m, "/nonexistent/dir/scene.yaml: cannot read the scene file")) << m;
  const std::string d = error_of([] { read_scene(kSceneDir, {}); });
  EXPECT_TRUE(contains(d, "is a directory")) << d;
}

TEST(SceneErrors, ChannelValidationNamesTheKeyAndLine) {
  const std::string m = parse_error(std::string(kOneFloe) + "channel:\n  opening: 1200\n");
  EXPECT_TRUE(starts_with(m, "t.yaml:4:12: key 'channel.opening': 1200 is outside the allowed range (0, 1000)")) << m;
}

// --- overrides ---

TEST(SceneOverrides, AppliedBeforeValidation) {
  const Scene s = read_scene(kSceneDir + "channel.yaml",
                             {"forcing.ocean.current=[0.5,0]", "floe_field.concentration=0.6", "run.dt=1e-3",
                              "output.vtk=false", "name=renamed", "floe_field.size.exponent=1.6"});
  EXPECT_EQ(s.ocean_field.velocity, Vec2(0.5, 0.0));
  EXPECT_EQ(s.floe_field->concentration, 0.6);
  EXPECT_EQ(s.floe_field->exponent, 1.6);
  EXPECT_EQ(s.time.dt, 1e-3);
  EXPECT_FALSE(s.output.vtk);
  EXPECT_EQ(s.name, "renamed");
  EXPECT_EQ(s.overrides.size(), 6u);
}

TEST(SceneOverrides, SetReachesListItemsByIndexCreatesOrRemovesBlocksAndReplacesWholeLists) {
  const Scene s = read_scene(kSceneDir + "two_floes.yaml", {"floes.0.position=[1,2]", "floes.1.velocity=[-2, 0]",
                                                            "contact.restitution=1", "floes.1.motion=fixed"});
  EXPECT_EQ(s.bodies[0].position, Vec2(1, 2));
  EXPECT_EQ(s.bodies[1].velocity, Vec2(-2, 0));
  EXPECT_EQ(s.bodies[1].motion, dynamics::Motion::fixed);
  EXPECT_EQ(s.world.contact.restitution, 1.0);
  // A block that the file lacks is created; a whole list can be replaced.
  const Scene t = parse_scene(kOneFloe, "t.yaml",
                              {"channel.opening=100",
                               "floes=[{rectangle: {width: 2, height: 3}}, "
                               "{regular: {sides: 5, radius: 1}}]"});
  ASSERT_TRUE(t.channel.has_value());
  EXPECT_EQ(t.channel->opening, 100.0);
  EXPECT_EQ(t.bodies.size(), 2u);
  EXPECT_EQ(t.bodies[0].source.where, "--set floes");
  // null removes an optional block.
  EXPECT_FALSE(read_scene(kSceneDir + "channel.yaml", {"channel=~"}).channel.has_value());
}

TEST(SceneOverrides, ErrorsSayWhichSet) {
  std::string m = parse_error(kOneFloe, {"contact.restitution=1.5"});
  EXPECT_EQ(m, "--set contact.restitution: key 'contact.restitution': 1.5 is outside the allowed range (0, 1] [-]");
  m = parse_error(kOneFloe, {"contct.restitution=0.5"});
  EXPECT_TRUE(starts_with(m, "--set contct.restitution: unknown key 'contct'; allowed at the top level: name, ")) << m;
  m = parse_error(kOneFloe, {"run.durration=5"});
  EXPECT_TRUE(starts_with(m, "--set run.durration: unknown key 'run.durration'; allowed in 'run': duration, dt, "))
      << m;
  m = parse_error(kOneFloe, {"floes.3.position=[1,2]"});
  EXPECT_TRUE(starts_with(m, "--set floes.3.position: 'floes' is a list of 1 items; '3' is not one of its indices"))
      << m;
  m = parse_error(kOneFloe, {"floes.0.regular.sides=two"});
  EXPECT_EQ(m, "--set floes.0.regular.sides: key 'floes.0.regular.sides': expected an integer in [3, 64], got 'two'");
  m = parse_error(std::string(kOneFloe) + "run: {duration: 3}\n", {"run.duration.x=1"});
  EXPECT_TRUE(starts_with(m, "--set run.duration.x: 'run.duration' is a single value")) << m;
  m = parse_error(kOneFloe, {"run.duration"});
  EXPECT_TRUE(starts_with(m, "--set 'run.duration': expected key.path=value")) << m;
  m = parse_error(kOneFloe, {"run..duration=3"});
  EXPECT_TRUE(contains(m, "empty name")) << m;
  m = parse_error(kOneFloe, {"forcing.ocean.current=[1, 2"});
  EXPECT_TRUE(starts_with(m, "--set forcing.ocean.current: cannot read the value '[1, 2' as YAML")) << m;
  m = parse_error("name: x\n", {"floes.0.position=[1,2]"});
  EXPECT_TRUE(starts_with(m, "--set floes.0.position: there is no list 'floes'")) << m;
  // Errors in the file itself keep the file's location even with overrides elsewhere.
  m = parse_error(std::string(kOneFloe) + "run: {duration: 0}\n", {"run.dt=1"});
  EXPECT_TRUE(starts_with(m, "t.yaml:3:17: key 'run.duration'")) << m;
}

TEST(SceneErrors, EachBadForcingOrDensityKeyIsRefusedNamingTheKeyAndWhatItNeeds) {
  const std::string one(kOneFloe);
  std::string m = parse_error(one + "forcing:\n  ocean: {current: [1, 0], field: {type: uniform}}\n");
  EXPECT_TRUE(contains(m, "key 'forcing.ocean': give only one of 'current' (uniform) and 'field'")) << m;
  m = parse_error(one + "forcing:\n  ocean:\n    field: {velocity: [1, 0]}\n");
  EXPECT_TRUE(starts_with(m, "t.yaml:5:12: key 'forcing.ocean.field': missing required key 'type'")) << m;
  m = parse_error(one + "forcing:\n  ocean:\n    field: {type: swirl}\n");
  EXPECT_TRUE(contains(m,
                       "key 'forcing.ocean.field.type': expected one of uniform, linear, solid_body, rankine, "
                       "tidal, time_series, file, got 'swirl'"))
      << m;
  m = parse_error(one + "forcing:\n  ocean:\n    field: {type: uniform, angular_velocity: 1}\n");
  EXPECT_TRUE(contains(m,
                       "unknown key 'forcing.ocean.field.angular_velocity'; allowed in 'forcing.ocean.field': "
                       "type, velocity"))
      << m;
  m = parse_error(one + "forcing:\n  ocean:\n    field: {type: rankine, core_radius: 100}\n");
  EXPECT_TRUE(contains(m, "missing required key 'max_speed'")) << m;
  m = parse_error(one + "forcing:\n  ocean:\n    field: {type: rankine, core_radius: 0, max_speed: 1}\n");
  EXPECT_TRUE(contains(m, "key 'forcing.ocean.field.core_radius': 0 is outside the allowed range (0, 1e9] [m]")) << m;
  m = parse_error(one + "forcing:\n  ocean:\n    field: {type: tidal, amplitude: [1, 0]}\n");
  EXPECT_TRUE(contains(m, "missing required key 'period' [s]")) << m;
  m = parse_error(one +
                  "forcing:\n  ocean:\n    field: {type: time_series, times: [0, 10, 10], "
                  "velocities: [[0, 0], [1, 0], [2, 0]]}\n");
  EXPECT_TRUE(contains(m, "key 'forcing.ocean.field.times.2': 10 s must be after the previous time 10 s")) << m;
  m = parse_error(one + "forcing:\n  ocean:\n    field: {type: time_series, times: [0, 10], velocities: [[0, 0]]}\n");
  EXPECT_TRUE(contains(m, "key 'forcing.ocean.field.velocities': expected one velocity per time (2), got 1")) << m;
  m = parse_error(one + "forcing:\n  ocean:\n    field: {type: linear, gradient: [[1, 2]]}\n");
  EXPECT_TRUE(contains(m, "expected a list of 2 rows [[du/dx, du/dy], [dv/dx, dv/dy]] [1/s]")) << m;
  m = parse_error(one +
                  "run: {duration: 100}\nforcing:\n  air:\n    field: {type: time_series, times: [0, 50], "
                  "velocities: [[0, 0], [1, 0]], outside: error}\n");
  EXPECT_TRUE(contains(m,
                       "key 'forcing.air.field.times': the series covers [0, 50] s but the run spans [0, 100] s "
                       "with outside: error"))
      << m;
  m = parse_error(one + "forcing: {quadrature: degree3}\n");
  EXPECT_TRUE(contains(m, "expected one of centroid, degree1, degree2, degree4, degree5, got 'degree3'")) << m;
  m = parse_error(one + "forcing: {update_every: 0}\n");
  EXPECT_TRUE(contains(m, "key 'forcing.update_every'")) << m;
  EXPECT_TRUE(contains(m, "[1, 1000]")) << m;
  m = parse_error(one + "forcing: {treatment: explicit, update_every: 8}\n");
  EXPECT_TRUE(contains(m, "key 'forcing.update_every': update_every = 8 needs forcing.treatment: semi_implicit")) << m;
  m = parse_error(one + "forcing: {coriolis: {latitude: 91}}\n");
  EXPECT_TRUE(contains(m, "key 'forcing.coriolis.latitude': 91 is outside the allowed range [-90, 90] [deg]")) << m;
  m = parse_error(one + "forcing: {ocean: {form_drag: {coefficient: -0.1}}}\n");
  EXPECT_TRUE(contains(m, "key 'forcing.ocean.form_drag.coefficient': -0.1 is outside the allowed range [0, 10] [-]"))
      << m;
  m = parse_error(one + "ice: {density: 1100}\n");
  EXPECT_TRUE(contains(m,
                       "key 'ice.density': ice density 1100 kg/m^3 must be below the water density "
                       "forcing.ocean.density = 1025 kg/m^3, or the floes would sink"))
      << m;
  // Only the water density given: the message points at it (and no yaml-cpp error about the missing 'ice' block).
  m = parse_error(one + "forcing: {ocean: {density: 900}}\n");
  EXPECT_TRUE(starts_with(m, "t.yaml:3:28: key 'forcing.ocean.density': ice density 920 kg/m^3 must be below")) << m;
}

}  // namespace
}  // namespace polyfloe::scene

namespace polyfloe::scene {
namespace {

// JSON is YAML's subset and quotes every word: "auto" and enumerated values read as words, plain or quoted; a
// quoted number is still refused as text.
TEST(SceneReader, AJsonSceneReadsItsWords) {
  const Scene s = parse_scene(R"({"run": {"duration": 1, "dt": "auto", "reference_speed": "auto"},
    "contact": {"narrow_phase": "exact", "force_model": "gradient"},
    "output": {"velocity_grid": {"enabled": true, "region": "auto"}},
    "floes": [{"rectangle": {"width": 10, "height": 10}}]})",
                              "t.json");
  EXPECT_FALSE(s.time.dt.has_value());
  EXPECT_FALSE(s.output.velocity_grid.region.has_value());
  try {
    (void)parse_scene(R"({"run": {"duration": "1"}, "floes": [{"rectangle": {"width": 10, "height": 10}}]})", "t.json");
    ADD_FAILURE() << "a quoted number was read as a number";
  } catch (const SceneError& e) {
    EXPECT_NE(std::string(e.what()).find("got the quoted string '1'"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace polyfloe::scene
