// Scenes compared setting by setting, and the resolved-YAML round trip (scene reader and field-file tests).
#pragma once

#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "scene/scene_reader.h"

namespace polyfloe::scene {

// Every setting of two scenes: each declared key's value as the resolved scene writes it (numbers in the shortest
// text that reads back to the same double, so equal text is equal bits), and the bodies' lists item by item (their
// text names where each body was given).

inline void expect_same_settings(const Scene& a, const Scene& b) {
  EXPECT_EQ(a.name, b.name);
  const std::vector<SchemaKey> ka = schema_keys(a, false), kb = schema_keys(b, false);
  ASSERT_EQ(ka.size(), kb.size());
  for (std::size_t i = 0; i < ka.size(); ++i) {
    ASSERT_EQ(ka[i].path, kb[i].path);
    if (ka[i].path == "floes" || ka[i].path == "spatial.bodies") continue;
    EXPECT_EQ(ka[i].value, kb[i].value) << ka[i].path;
  }
  EXPECT_EQ(a.ocean_field.grid != nullptr, b.ocean_field.grid != nullptr);
  EXPECT_EQ(a.wind_field.grid != nullptr, b.wind_field.grid != nullptr);
  if (a.spatial && b.spatial) {
    const auto &x = *a.spatial, &y = *b.spatial;
    ASSERT_EQ(x.bodies.size(), y.bodies.size());
    for (std::size_t i = 0; i < x.bodies.size(); ++i) {
      const auto &p = x.bodies[i], &q = y.bodies[i];
      EXPECT_EQ(p.box, q.box);
      EXPECT_EQ(p.polygon, q.polygon);
      EXPECT_EQ(p.thickness, q.thickness);
      EXPECT_EQ(p.position, q.position);
      EXPECT_EQ(p.rotation_axis, q.rotation_axis);
      EXPECT_EQ(p.rotation_angle, q.rotation_angle);
      EXPECT_EQ(p.velocity, q.velocity);
      EXPECT_EQ(p.angular_velocity, q.angular_velocity);
      EXPECT_EQ(p.density, q.density);
      EXPECT_EQ(p.motion, q.motion);
      EXPECT_EQ(p.id, q.id);
    }
  }
  ASSERT_EQ(a.bodies.size(), b.bodies.size());
  for (std::size_t i = 0; i < a.bodies.size(); ++i) {
    const BodySpec &x = a.bodies[i], &y = b.bodies[i];
    EXPECT_EQ(x.polygon, y.polygon) << i;
    EXPECT_EQ(x.position, y.position) << i;
    EXPECT_EQ(x.yaw, y.yaw) << i;
    EXPECT_EQ(x.velocity, y.velocity) << i;
    EXPECT_EQ(x.angular_velocity, y.angular_velocity) << i;
    EXPECT_EQ(x.thickness, y.thickness) << i;
    EXPECT_EQ(x.motion, y.motion) << i;
    EXPECT_EQ(x.id, y.id) << i;
    EXPECT_EQ(x.external_force, y.external_force) << i;
    EXPECT_EQ(x.external_torque, y.external_torque) << i;
  }
}

inline void expect_round_trip(const Scene& s) {
  const std::string text = resolved_yaml(s);
  SCOPED_TRACE(text);
  const Scene back = parse_scene(text, "resolved.yaml", {});
  expect_same_settings(s, back);
}

}  // namespace polyfloe::scene
