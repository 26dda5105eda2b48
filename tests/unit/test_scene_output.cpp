// Scene reader, output block: the velocity grid's keys, defaults, errors with their locations, and the round trip
// through the resolved YAML.
#include <gtest/gtest.h>

#include "scene_test_support.h"

namespace polyfloe::scene {
namespace {

TEST(SceneOutput, VelocityGridDefaultsAndKeys) {
  Scene s = parse_scene(kOneFloe, "t.yaml", {});
  EXPECT_FALSE(s.output.velocity_grid.enabled);
  EXPECT_EQ(s.output.velocity_grid.cell, 10.0);
  EXPECT_FALSE(s.output.velocity_grid.region.has_value());
  EXPECT_EQ(s.output.velocity_grid.samples_per_frame, 10);
  s = parse_scene(std::string(kOneFloe) +
                      "output:\n  velocity_grid: {enabled: true, cell: 2.5, region: [-10, 0, 90, 50], "
                      "samples_per_frame: 4}\n",
                  "t.yaml", {});
  EXPECT_TRUE(s.output.velocity_grid.enabled);
  EXPECT_EQ(s.output.velocity_grid.cell, 2.5);
  EXPECT_EQ(s.output.velocity_grid.region, (std::array<double, 4>{-10, 0, 90, 50}));
  EXPECT_EQ(s.output.velocity_grid.samples_per_frame, 4);
  s = parse_scene(kOneFloe, "t.yaml", {"output.velocity_grid.enabled=true", "output.velocity_grid.region=auto"});
  EXPECT_TRUE(s.output.velocity_grid.enabled);
  EXPECT_FALSE(s.output.velocity_grid.region.has_value());
  // The channel scene asks for the grid.
  EXPECT_TRUE(read_scene(kSceneDir + "channel.yaml", {}).output.velocity_grid.enabled);
}

TEST(SceneOutput, VelocityGridErrorsNameKeyLineAndRange) {
  const std::string one(kOneFloe);
  std::string m = parse_error(one + "output:\n  velocity_grid: {cell: 0}\n");
  EXPECT_TRUE(
      starts_with(m, "t.yaml:4:25: key 'output.velocity_grid.cell': 0 is outside the allowed range (0, 1e9] [m]"))
      << m;
  m = parse_error(one + "output:\n  velocity_grid: {samples_per_frame: 0}\n");
  EXPECT_TRUE(contains(m, "key 'output.velocity_grid.samples_per_frame'") && contains(m, "1") && contains(m, "1000"))
      << m;
  m = parse_error(one + "output:\n  velocity_grid: {region: [0, 0, 10]}\n");
  EXPECT_TRUE(contains(m, "key 'output.velocity_grid.region': expected a list of 4 numbers [xmin, ymin, xmax, ymax]"))
      << m;
  m = parse_error(one + "output:\n  velocity_grid: {region: [0, 0, -10, 10]}\n");
  EXPECT_TRUE(contains(m, "xmax = -10 must be > xmin = 0 [m]")) << m;
  m = parse_error(one + "output:\n  velocity_grid: {region: everywhere}\n");
  EXPECT_TRUE(contains(m, "key 'output.velocity_grid.region'")) << m;
  m = parse_error(one + "output:\n  velocity_grid: {cell: 0.1, region: [0, 0, 1000, 1000]}\n");
  EXPECT_TRUE(contains(m, "key 'output.velocity_grid.cell': the velocity grid would have 1e8 cells (at most 4e6)"))
      << m;
  m = parse_error(one + "output:\n  velocity_grid: {spacing: 5}\n");
  EXPECT_TRUE(contains(m,
                       "unknown key 'output.velocity_grid.spacing'; allowed in 'output.velocity_grid': enabled, "
                       "cell, region, samples_per_frame"))
      << m;
  m = parse_error(one + "output:\n  velocity_grid: {enabled: sometimes}\n");
  EXPECT_TRUE(contains(m, "key 'output.velocity_grid.enabled': expected true or false")) << m;
}

TEST(SceneOutput, VelocityGridRoundTripsThroughResolvedYaml) {
  for (const char* grid : {"{enabled: true, cell: 7.5, region: [-1.5, 2, 300, 400.25], samples_per_frame: 3}",
                           "{enabled: false, cell: 20}"}) {
    SCOPED_TRACE(grid);
    const Scene a = parse_scene(std::string(kOneFloe) + "output:\n  velocity_grid: " + grid + "\n", "t.yaml", {});
    const Scene b = parse_scene(resolved_yaml(a), "resolved.yaml", {});
    EXPECT_EQ(a.output.velocity_grid.enabled, b.output.velocity_grid.enabled);
    EXPECT_EQ(a.output.velocity_grid.cell, b.output.velocity_grid.cell);
    EXPECT_EQ(a.output.velocity_grid.region, b.output.velocity_grid.region);
    EXPECT_EQ(a.output.velocity_grid.samples_per_frame, b.output.velocity_grid.samples_per_frame);
  }
}

}  // namespace
}  // namespace polyfloe::scene
