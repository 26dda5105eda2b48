// Checks on a planar World shared by its tests (needs GoogleTest).
#pragma once

#include <gtest/gtest.h>

#include <cmath>

#include "dynamics/world.h"
#include "forcing/drift.h"

namespace polyfloe::tsupport {

// World settings with every drift term off: contact dynamics alone.
inline dynamics::WorldSettings no_drift() {
  dynamics::WorldSettings ws;
  ws.drift = forcing::DriftSettings::none();
  return ws;
}

// World-frame vertices = position + R(yaw) x body-frame vertices, to 1e-12 relative.
inline void expect_vertices_follow_body(const dynamics::World& w, int i) {
  const double c = std::cos(w.yaws()[i]), s = std::sin(w.yaws()[i]);
  const auto& local = w.shape(i).vertices();
  const auto world = w.world_vertices(i);
  ASSERT_EQ(world.size(), local.size());
  for (std::size_t k = 0; k < local.size(); ++k) {
    const geometry::Vec2 want = w.positions()[i] + geometry::rotate(local[k], c, s);
    EXPECT_NEAR(world[k].x(), want.x(), 1e-12 * (1.0 + want.norm())) << "body " << w.id(i) << " vertex " << k;
    EXPECT_NEAR(world[k].y(), want.y(), 1e-12 * (1.0 + want.norm())) << "body " << w.id(i) << " vertex " << k;
  }
}

}  // namespace polyfloe::tsupport
