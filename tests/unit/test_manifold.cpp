// The face-clipping contact manifold of two polyhedra (contact/manifold.h): a face on a face gives its four corners
// and a centred force, an edge on a face the edge's two ends at their depths.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include <Eigen/Geometry>

#include "contact/manifold.h"
#include "geometry/polyhedron.h"
#include "placed_polyhedron.h"

namespace {

using polyfloe::geometry::ConvexPolyhedron;
using polyfloe::geometry::Mat3;
using polyfloe::geometry::Vec3;
using polyfloe::tsupport::placed;

TEST(Manifold, FaceOnFaceGivesFourPointsAndACentredForce) {
  const auto plate = ConvexPolyhedron::box({10.0, 10.0, 1.0});
  const auto cube = ConvexPolyhedron::box({2.0, 2.0, 2.0});
  const Mat3 id = Mat3::Identity();
  const auto wp = placed(plate, id, {0.0, 0.0, -0.5});  // top face at z = 0
  const auto wc = placed(cube, id, {0.3, -0.2, 0.99});  // 1 cm into the plate
  const auto m = polyfloe::contact::clip_manifold(plate, id, wp, cube, id, wc, Vec3::UnitZ());
  ASSERT_EQ(m.count, 4);
  EXPECT_NEAR(m.max_depth(), 0.01, 1e-12);
  EXPECT_NEAR((m.normal - Vec3::UnitZ()).norm(), 0.0, 1e-14);
  const Vec3 c = m.centre();
  EXPECT_NEAR(c.x(), 0.3, 1e-12);  // no lever arm: the face-on force makes no torque
  EXPECT_NEAR(c.y(), -0.2, 1e-12);
}

TEST(Manifold, EdgeOnFaceGivesTheEdgeAndItsMidpoint) {
  const auto plate = ConvexPolyhedron::box({10.0, 10.0, 1.0});
  const auto cube = ConvexPolyhedron::box({2.0, 2.0, 2.0});
  const Mat3 id = Mat3::Identity();
  const double alpha = 20.0 * std::numbers::pi / 180.0;
  const Mat3 r = Eigen::AngleAxisd(alpha, Vec3::UnitY()).toRotationMatrix();
  const auto wp = placed(plate, id, {0.0, 0.0, -0.5});
  // the lowest edge is the one at body (x, z) with the lowest world z; put it 2 mm into the plate
  Vec3 low = Vec3::Zero();
  for (const auto& v : cube.vertices()) {
    if ((r * v).z() < low.z()) low = r * v;
  }
  const auto wc = placed(cube, r, {0.0, 0.0, -low.z() - 0.002});
  const auto m = polyfloe::contact::clip_manifold(plate, id, wp, cube, r, wc, Vec3::UnitZ());
  ASSERT_EQ(m.count, 2);
  EXPECT_NEAR(m.depths[0], 0.002, 1e-12);
  EXPECT_NEAR(m.depths[1], 0.002, 1e-12);
  const Vec3 c = m.centre();
  EXPECT_NEAR(c.x(), low.x(), 1e-12);  // lever arm of the striking edge: r cos(alpha + pi/4)
  EXPECT_NEAR(std::abs(c.x()), std::sqrt(2.0) * std::cos(alpha + std::numbers::pi / 4), 1e-12);
  EXPECT_NEAR(c.y(), 0.0, 1e-12);
}

}  // namespace
