// Convex polyhedra: mass properties against closed forms, validation, the submerged part.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include <Eigen/Geometry>

#include "geometry/polyhedron.h"
#include "placed_polyhedron.h"

namespace {

using polyfloe::geometry::ConvexPolygon;
using polyfloe::geometry::ConvexPolyhedron;
using polyfloe::geometry::Mat3;
using polyfloe::geometry::Vec3;

using polyfloe::tsupport::placed;

TEST(Polyhedron, BoxVolumeAndInertiaAreTheClosedForms) {
  const auto b = ConvexPolyhedron::box({2.0, 3.0, 5.0});
  EXPECT_NEAR(b.volume(), 30.0, 1e-12);
  // I_xx = V (ly^2 + lz^2) / 12 per unit density
  const Mat3& i = b.unit_inertia();
  EXPECT_NEAR(i(0, 0), 30.0 * (9.0 + 25.0) / 12.0, 1e-10);
  EXPECT_NEAR(i(1, 1), 30.0 * (4.0 + 25.0) / 12.0, 1e-10);
  EXPECT_NEAR(i(2, 2), 30.0 * (4.0 + 9.0) / 12.0, 1e-10);
  EXPECT_NEAR(i(0, 1), 0.0, 1e-10);
  EXPECT_NEAR(i(1, 2), 0.0, 1e-10);
  EXPECT_EQ(b.faces().size(), 6u);
  for (const auto& f : b.faces()) EXPECT_NEAR(f.normal.norm(), 1.0, 1e-14);
  EXPECT_NEAR(b.circumradius(), 0.5 * std::sqrt(4.0 + 9.0 + 25.0), 1e-12);
}

TEST(Polyhedron, PrismOfAPolygonMatchesThePlanarMassProperties) {
  const auto p = ConvexPolygon::regular(7, 3.0);
  const double h = 1.5;
  const auto s = ConvexPolyhedron::prism(p, h);
  EXPECT_NEAR(s.volume(), p.area() * h, 1e-12 * s.volume());
  // I_zz = polar moment x h; I_xx = I_yy by symmetry (7-fold), = (polar / 2 + A h^2 / 12) h
  EXPECT_NEAR(s.unit_inertia()(2, 2), p.polar_moment() * h, 1e-10 * p.polar_moment() * h);
  EXPECT_NEAR(s.unit_inertia()(0, 0), (0.5 * p.polar_moment() + p.area() * h * h / 12.0) * h,
              1e-10 * s.unit_inertia()(0, 0));
  EXPECT_NEAR(s.unit_inertia()(0, 0), s.unit_inertia()(1, 1), 1e-10 * s.unit_inertia()(0, 0));
}

TEST(Polyhedron, BadSizesAreRefused) {
  EXPECT_THROW(ConvexPolyhedron::box({1.0, 0.0, 1.0}), polyfloe::geometry::GeometryError);
  EXPECT_THROW(ConvexPolyhedron::box({1.0, NAN, 1.0}), polyfloe::geometry::GeometryError);
  EXPECT_THROW(ConvexPolyhedron::prism(ConvexPolygon::regular(5, 1.0), -1.0), polyfloe::geometry::GeometryError);
}

TEST(Polyhedron, SubmergedPartOfATiltedBoxIsExact) {
  const auto b = ConvexPolyhedron::box({2.0, 2.0, 2.0});
  // level box, centre at z = 0.4: 0.6 m of its 2 m height below z = 0
  auto w = placed(b, Mat3::Identity(), {1.0, -2.0, 0.4});
  auto s = polyfloe::geometry::submerged_part(b, w, 0.0);
  EXPECT_NEAR(s.volume, 4.0 * 0.6, 1e-12);
  EXPECT_NEAR(s.centroid.x(), 1.0, 1e-12);
  EXPECT_NEAR(s.centroid.y(), -2.0, 1e-12);
  EXPECT_NEAR(s.centroid.z(), -0.3, 1e-12);
  // edge-down at 45 degrees about y, centre at the water level: half the volume, by symmetry under the centre
  const Mat3 r = Eigen::AngleAxisd(std::numbers::pi / 4, Vec3::UnitY()).toRotationMatrix();
  w = placed(b, r, {0.0, 0.0, 0.0});
  s = polyfloe::geometry::submerged_part(b, w, 0.0);
  EXPECT_NEAR(s.volume, 4.0, 1e-12);
  EXPECT_NEAR(s.centroid.x(), 0.0, 1e-12);
  // the submerged half is a triangular prism of height sqrt(2) below the centre: centroid at -sqrt(2)/3
  EXPECT_NEAR(s.centroid.z(), -std::sqrt(2.0) / 3.0, 1e-12);
  // wholly under and wholly above
  w = placed(b, r, {0.0, 0.0, -5.0});
  EXPECT_NEAR(polyfloe::geometry::submerged_part(b, w, 0.0).volume, 8.0, 1e-12);
  w = placed(b, r, {0.0, 0.0, 5.0});
  EXPECT_EQ(polyfloe::geometry::submerged_part(b, w, 0.0).volume, 0.0);
}

// A 64-gon floe (the most corners a scene allows) 5 km from the origin, at its draft: the submerged volume is area x
// draft and its centre under the centroid, to 1e-12 relative (every face vertex kept; coordinates taken from the
// body, not the world origin).
TEST(Polyhedron, SubmergedPartOfA64GonFarFromTheOrigin) {
  const auto s = ConvexPolyhedron::prism(ConvexPolygon::regular(64, 20.0), 1.0);
  const double draft = 0.8976;
  const auto w = placed(s, Mat3::Identity(), {5000.0, -5000.0, 0.5 - draft});
  const auto sub = polyfloe::geometry::submerged_part(s, w, 0.0);
  const double area = s.volume() / 1.0;
  EXPECT_NEAR(sub.volume, area * draft, 1e-12 * area * draft);
  EXPECT_NEAR(sub.centroid.x(), 5000.0, 1e-12 * 5000.0);
  EXPECT_NEAR(sub.centroid.y(), -5000.0, 1e-12 * 5000.0);
  EXPECT_NEAR(sub.centroid.z(), -0.5 * draft, 1e-12);
}

}  // namespace
