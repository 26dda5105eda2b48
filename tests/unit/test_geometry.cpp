#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "geometry/polygon.h"

using polyfloe::geometry::ConvexPolygon;
using polyfloe::geometry::GeometryError;
using polyfloe::geometry::Vec2;

TEST(Polygon, RectangleAreaPerimeterMomentCentroidRadiusAndCircularityMatchHandValues) {
  // 4 m x 2 m rectangle: A = 8, P = 12, J = A (a^2 + b^2) / 12 = 8 * 20 / 12.
  const std::vector<Vec2> v = {{1, 1}, {5, 1}, {5, 3}, {1, 3}};
  Vec2 offset;
  const ConvexPolygon p = ConvexPolygon::from_vertices(v, &offset);
  EXPECT_NEAR(p.area(), 8.0, 1e-12);
  EXPECT_NEAR(p.perimeter(), 12.0, 1e-12);
  EXPECT_NEAR(p.polar_moment(), 8.0 * 20.0 / 12.0, 1e-12);
  EXPECT_NEAR(offset.x(), 3.0, 1e-12);
  EXPECT_NEAR(offset.y(), 2.0, 1e-12);
  EXPECT_NEAR(p.circumradius(), std::sqrt(5.0), 1e-12);
  // Circularity (Eq. 17): 2 sqrt(pi A) / P.
  EXPECT_NEAR(p.circularity(), 2.0 * std::sqrt(std::numbers::pi * 8.0) / 12.0, 1e-12);
}

TEST(Polygon, RightTriangleAreaPerimeterCentroidAndPolarMomentMatchHandValues) {
  // Right triangle with legs 3 and 4: A = 6, centroid (1, 4/3), P = 12.
  const std::vector<Vec2> v = {{0, 0}, {3, 0}, {0, 4}};
  Vec2 offset;
  const ConvexPolygon p = ConvexPolygon::from_vertices(v, &offset);
  EXPECT_NEAR(p.area(), 6.0, 1e-12);
  EXPECT_NEAR(p.perimeter(), 12.0, 1e-12);
  EXPECT_NEAR(offset.x(), 1.0, 1e-12);
  EXPECT_NEAR(offset.y(), 4.0 / 3.0, 1e-12);
  // Polar moment about the centroid of a right triangle: A (a^2 + b^2) / 18 = 6 * 25 / 18.
  EXPECT_NEAR(p.polar_moment(), 6.0 * 25.0 / 18.0, 1e-12);
}

TEST(Polygon, RegularPolygonTendsToTheCircleAndASquaresCircularityIsRootPiOverTwo) {
  const ConvexPolygon p = ConvexPolygon::regular(720, 2.0);
  EXPECT_NEAR(p.area(), std::numbers::pi * 4.0, 1e-3);
  EXPECT_NEAR(p.polar_moment(), std::numbers::pi * 16.0 / 2.0, 1e-2);
  EXPECT_NEAR(p.circularity(), 1.0, 1e-5);
  // A square's circularity is sqrt(pi) / 2.
  EXPECT_NEAR(ConvexPolygon::rectangle(3, 3).circularity(), std::sqrt(std::numbers::pi) / 2.0, 1e-12);
}

TEST(Polygon, PrismMassInertiaAndFloatingDraftMatchClosedForms) {
  const ConvexPolygon sq = ConvexPolygon::rectangle(10, 10);
  const auto m = polyfloe::geometry::prism_mass(sq, 2.0, 920.0);
  EXPECT_NEAR(m.mass, 920.0 * 200.0, 1e-9);
  EXPECT_NEAR(m.inertia_z, m.mass * (100.0 + 100.0) / 12.0, 1e-6);
  EXPECT_NEAR(polyfloe::geometry::floating_draft(2.0, 920.0, 1025.0), 2.0 * 920.0 / 1025.0, 1e-15);
}

TEST(Polygon, FarFromOriginKeepsPrecision) {
  std::vector<Vec2> v = {{0, 0}, {2, 0}, {2, 1}, {0, 1}};
  for (Vec2& p : v) p += Vec2(1.0e7, -3.0e6);
  const ConvexPolygon p = ConvexPolygon::from_vertices(v);
  EXPECT_NEAR(p.area(), 2.0, 1e-8);
  EXPECT_NEAR(p.polar_moment(), 2.0 * 5.0 / 12.0, 1e-6);
}

TEST(Polygon, FewPointsClockwiseRepeatsCollinearReflexNonFiniteOrStarAreRefusedWithTheReason) {
  auto rejects = [](std::vector<Vec2> v, const char* what) {
    try {
      (void)ConvexPolygon::from_vertices(v);
      ADD_FAILURE() << "accepted: " << what;
    } catch (const GeometryError& e) {
      EXPECT_NE(std::string(e.what()).find(what), std::string::npos) << e.what();
    }
  };
  rejects({{0, 0}, {1, 0}}, "at least 3");
  rejects({{0, 0}, {0, 1}, {1, 0}}, "clockwise");
  rejects({{0, 0}, {1, 0}, {1, 0}, {0, 1}}, "repeat");
  rejects({{0, 0}, {1, 0}, {2, 0}, {1, 1}}, "collinear");
  rejects({{0, 0}, {2, 0}, {1, 0.2}, {2, 2}, {0, 2}}, "vertex 2");
  rejects({{0, 0}, {1, 0}, {NAN, 1}}, "not finite");
  rejects({{0, 0}, {1, 0}, {INFINITY, 1}}, "not finite");
  // A pentagram: every turn is to the left, but it winds twice.
  std::vector<Vec2> star;
  for (int i = 0; i < 5; ++i) {
    const double a = 2.0 * std::numbers::pi * (2 * i) / 5.0;
    star.emplace_back(std::cos(a), std::sin(a));
  }
  rejects(star, "winds");
}

// Found by fuzzing (tests/fuzz/fuzz_polygon.cpp): polygons so small or so large that the polar moment (~ size^4)
// underflowed to 0 or overflowed to inf were accepted (or refused as "collinear"); the size range is now checked.
TEST(Polygon, RejectsSizesOutsideTheSupportedRange) {
  auto square = [](double a) { return std::vector<Vec2>{{0, 0}, {a, 0}, {a, a}, {0, a}}; };
  for (double a : {1e-160, 1e-61, 1e61, 1e100, 1e160}) {
    SCOPED_TRACE(a);
    try {
      (void)ConvexPolygon::from_vertices(square(a));
      ADD_FAILURE() << "accepted";
    } catch (const GeometryError& e) {
      EXPECT_NE(std::string(e.what()).find("outside the range [1e-60, 1e+60] m"), std::string::npos) << e.what();
    }
  }
  EXPECT_THROW((void)ConvexPolygon::rectangle(1e-100, 1e-100), GeometryError);
  for (double a : {1e-55, 1e-6, 1e6, 1e55}) {  // inside the range: finite, positive properties
    SCOPED_TRACE(a);
    const ConvexPolygon p = ConvexPolygon::from_vertices(square(a));
    EXPECT_GT(p.polar_moment(), 0.0);
    EXPECT_TRUE(std::isfinite(p.polar_moment()));
    EXPECT_NEAR(p.area(), a * a, 1e-12 * a * a);
  }
}
