// Channel walls (scene/channel.h): convex, touching, leaving the opening where the spec puts it; validation names
// the key and the range.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "geometry/polygon.h"
#include "scene/channel.h"
#include "scene/floe_field.h"

namespace polyfloe::scene {
namespace {

TEST(Channel, WallsAreConvexTouchingAndLeaveTheOpening) {
  ChannelSpec c;  // the paper-like defaults: opening 250 m
  const std::vector<WallPolygon> walls = channel_walls(c);
  ASSERT_EQ(walls.size(), 6u);
  for (const WallPolygon& w : walls) EXPECT_EQ(geometry::convexity_error(w.vertices), "") << w.name;
  for (std::size_t i = 0; i < walls.size(); ++i)
    for (std::size_t j = i + 1; j < walls.size(); ++j)
      EXPECT_GE(polygon_separation(walls[i].vertices, walls[j].vertices), -1e-9)
          << walls[i].name << " / " << walls[j].name;

  auto y_range = [](const WallPolygon& w, double& lo, double& hi) {
    lo = INFINITY;
    hi = -INFINITY;
    for (const Vec2& v : w.vertices) lo = std::min(lo, v.y()), hi = std::max(hi, v.y());
  };
  double lo0, hi0, lo1, hi1;
  y_range(walls[4], lo0, hi0);  // strait (y min)
  y_range(walls[5], lo1, hi1);  // strait (y max)
  EXPECT_NEAR(lo1 - hi0, c.opening, 1e-9);
  EXPECT_NEAR(0.5 * (lo1 + hi0), 500.0, 1e-9);
  EXPECT_NEAR(hi0 - lo0, c.wall_thickness, 1e-9);
  // Basin walls lie outside the basin.
  y_range(walls[0], lo0, hi0);
  y_range(walls[1], lo1, hi1);
  EXPECT_NEAR(hi0, 0.0, 1e-12);
  EXPECT_NEAR(lo1, 1000.0, 1e-12);
  // The strait ends at basin_x_max + funnel + strait.
  double x_end = -INFINITY;
  for (const Vec2& v : walls[5].vertices) x_end = std::max(x_end, v.x());
  EXPECT_NEAR(x_end, 1100.0 + 300.0 + 600.0, 1e-9);

  c.opening = 100.0;
  const auto narrow = channel_walls(c);
  y_range(narrow[4], lo0, hi0);
  y_range(narrow[5], lo1, hi1);
  EXPECT_NEAR(lo1 - hi0, 100.0, 1e-9);
}

TEST(Channel, ValidationNamesTheKey) {
  auto message = [](ChannelSpec c) {
    c.source.where = "c.yaml:3:1";
    try {
      validate_channel(c);
    } catch (const SceneError& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  ChannelSpec c;
  c.opening = 1000.0;
  EXPECT_EQ(message(c).rfind("c.yaml:3:1: key 'channel.opening': 1000 is outside the allowed range (0, 1000)", 0), 0u)
      << message(c);
  c = {};
  c.opening = 0.0;
  EXPECT_NE(message(c).find("'channel.opening'"), std::string::npos);
  c = {};
  c.funnel_length = -1.0;
  EXPECT_NE(message(c).find("'channel.funnel_length'"), std::string::npos);
  c = {};
  c.strait_length = 0.0;
  EXPECT_NE(message(c).find("'channel.strait_length'"), std::string::npos);
  c = {};
  c.basin_y_max = -5.0;
  EXPECT_NE(message(c).find("'channel.basin_y_max'"), std::string::npos);
  EXPECT_EQ(message(ChannelSpec{}), "");
}

}  // namespace
}  // namespace polyfloe::scene
