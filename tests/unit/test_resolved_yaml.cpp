// The resolved scene (resolved_yaml): every example scene, every field kind and every non-default setting read
// back to the same Scene, with units in the comments.
#include <gtest/gtest.h>

#include <string>

#include "forcing/drift.h"
#include "scene/scene_reader.h"
#include "scene_compare.h"
#include "scene_test_support.h"

namespace polyfloe::scene {
namespace {

TEST(ResolvedYaml, RoundTripsTheExampleScenes) {
  expect_round_trip(read_scene(kSceneDir + "channel.yaml", {}));
  expect_round_trip(read_scene(kSceneDir + "two_floes.yaml", {}));
  expect_round_trip(read_scene(kSceneDir + "drift_tidal.yaml", {}));
  expect_round_trip(read_scene(kSceneDir + "drift_vortex.yaml", {}));
  expect_round_trip(read_scene(kSceneDir + "channel_realistic.yaml", {}));
  expect_round_trip(read_scene(kSceneDir + "pack_ice_sheet.yaml", {}));
  expect_round_trip(read_scene(kSceneDir + "uniaxial_compression.yaml", {}));
}

TEST(ResolvedYaml, RoundTripsEveryFieldKind) {
  const char* fields[] = {
      "{type: uniform, velocity: [0.25, -1e-3]}",
      ("{type: linear, velocity: [0.1, 0.2], origin: [10, -20], gradient: [[1e-3, -2e-3], [3e-4, 0]],"
       " depth_gradient: [0.01, 0.02]}"),
      "{type: solid_body, centre: [500, 400], angular_velocity: -2e-3, velocity: [0.1, 0]}",
      "{type: rankine, centre: [1, 2], core_radius: 300, max_speed: 0.7, velocity: [0, 0.05]}",
      "{type: tidal, velocity: [0.05, 0], amplitude: [0.3, 0.1], period: 44712, phase: 1.5}",
      "{type: time_series, times: [0, 60, 600.5], velocities: [[0, 0], [0.2, 0.1], [0.3, -0.1]], outside: cyclic}",
  };
  for (const char* f : fields) {
    SCOPED_TRACE(f);
    const Scene s = parse_scene(
        std::string(kOneFloe) + "forcing:\n  ocean: {field: " + f + "}\n  air: {field: " + f + "}\n", "f.yaml", {});
    EXPECT_EQ(s.ocean_field.kind, s.wind_field.kind);
    ASSERT_TRUE(s.world.drift.ocean && s.world.drift.wind);
    expect_round_trip(s);
  }
  const Scene lin =
      parse_scene(std::string(kOneFloe) + "forcing:\n  ocean: {field: " + fields[1] + "}\n", "f.yaml", {});
  EXPECT_EQ(lin.ocean_field.kind, forcing::FieldKind::linear);
  EXPECT_EQ(lin.ocean_field.gradient(0, 1), -2e-3);
  EXPECT_EQ(lin.ocean_field.gradient(1, 0), 3e-4);
  // The built field is the one described: u(10, -20 + 100, z = -1) = u0 + G (0, 100) + dudz z.
  const Vec2 u = lin.world.drift.ocean->at({10.0, 80.0, -1.0}, 0.0);
  EXPECT_NEAR((u - Vec2(0.1 - 0.2 - 0.01, 0.2 + 0.0 - 0.02)).norm(), 0.0, 1e-15);
}

TEST(ResolvedYaml, RoundTripsEveryNonDefaultSetting) {
  const Scene s = parse_scene(
      "name: 'odd \"name\"'\n"
      "run: {duration: 12.5, dt: 3.3e-5, steps_per_contact: 17, reference_speed: 0.7}\n"
      "output: {interval: 0.1, vtk: false, contacts: false, hdf5: false}\n"
      "ice: {density: 900.5, youngs_modulus: 3.3e8, poisson_ratio: 0.123456789012345}\n"
      "contact: {restitution: 0.1, friction: 0.7, damping_model: paper, force_model: foundation, broad_phase_cell: "
      "12}\n"
      "forcing:\n"
      "  treatment: explicit\n"
      "  quadrature: degree4\n"
      "  ocean: {density: 1000, current: [0.1, -0.2], skin_drag: {enabled: false, coefficient: 0.001},\n"
      "          form_drag: {enabled: false, coefficient: 0.3}, moment_drag: {enabled: false, coefficient: 0.2}}\n"
      "  air: {density: 1.3, wind: [-3, 7], drag: {enabled: false, coefficient: 0.002}}\n"
      "  coriolis: {enabled: true, latitude: -65.5, beta_plane: true, reference_y: 1234}\n"
      "floes:\n"
      "  - {regular: {sides: 7, radius: 3}, position: [100, 5], yaw_deg: 33, velocity: [1, 2],\n"
      "     angular_velocity: -0.3, thickness: 0.5, motion: kinematic, id: 99, external_force: [1e6, 2],\n"
      "     external_torque: 5}\n"
      "  - {rectangle: {width: 1, height: 2}, motion: fixed, position: [200, 0]}\n"
      "  - {polygon: [[0, 0], [1, 0], [0, 1]], position: [300, 0]}\n"
      "floe_field: {region: [-5, -6, 70, 80], concentration: 0.33, size: {min: 2, max: 9, exponent: 1},\n"
      "             corners: 6, aspect_max: 1.7, thickness: 1.5, velocity: [0.2, 0.1], seed: 18446744073709551615,\n"
      "             max_attempts: 77}\n"
      "channel: {basin_x_min: 1, basin_x_max: 2, basin_y_min: 3, basin_y_max: 400, funnel_length: 5,\n"
      "          opening: 6, strait_length: 7, wall_thickness: 8, jam_window: 33, jam_speed: 0.02}\n",
      "all.yaml", {});
  EXPECT_EQ(s.name, "odd \"name\"");
  EXPECT_EQ(s.floe_field->corners_min, 6);
  EXPECT_EQ(s.floe_field->aspect_max, 1.7);
  EXPECT_EQ(s.floe_field->corners_max, 6);
  EXPECT_EQ(s.floe_field->seed, 18446744073709551615ull);
  expect_round_trip(s);
  const std::string text = resolved_yaml(s);
  EXPECT_TRUE(contains(text, "duration: 12.5  # [s]")) << text;
  EXPECT_TRUE(contains(text, "dt: 3.3e-5  # [s]")) << text;
  EXPECT_TRUE(contains(text, "external_force: [1e6, 2]  # [N]")) << text;
  EXPECT_TRUE(contains(text, "youngs_modulus: 3.3e8  # [Pa]")) << text;
}

}  // namespace
}  // namespace polyfloe::scene
