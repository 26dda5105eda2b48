// geometry::inside_all_edges, the kept topologies' chain test: each vector variant (SSE2, AVX2) gives the scalar
// formula's answer for every point, including points within a few margins of an edge (where round-off decides),
// for every corner count from 3 to 20; and the answers are right where they are known in closed form.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <random>
#include <vector>

#include "geometry/inside_edges.h"
#include "test_support.h"

using namespace polyfloe;
using geometry::EdgeSimd;
using geometry::Vec2;

namespace {

// The documented formula, edge by edge.
bool reference(const std::vector<Vec2>& poly, const Vec2& origin, const Vec2& v, double margin) {
  const std::size_t n = poly.size();
  for (std::size_t k = 0; k < n; ++k) {
    const Vec2 q0 = poly[(k + n - 1) % n] - origin, q1 = poly[k] - origin;
    const Vec2 e = q1 - q0;
    if (!(geometry::perp_right(e).dot(v - q0) < -margin * e.squaredNorm())) return false;
  }
  return true;
}

constexpr EdgeSimd kVariants[] = {EdgeSimd::sse2, EdgeSimd::avx2, EdgeSimd::best};

}  // namespace

TEST(InsideAllEdges, SquareMarginsAreTheDistanceToTheNearestEdgeAndPointsOutsideOrNanFail) {
  const std::vector<Vec2> square{{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  const Vec2 origin{0.0, 0.0};
  for (const EdgeSimd s : kVariants) {
    // The centre lies 0.5 m inside every 1 m edge: inside by a margin of 0.4, not of 0.6.
    EXPECT_TRUE(geometry::inside_all_edges(square, origin, {0.5, 0.5}, 0.4, s));
    EXPECT_FALSE(geometry::inside_all_edges(square, origin, {0.5, 0.5}, 0.6, s));
    // 0.05 m from the top edge: inside by 0.04, not by 0.06; outside it, never.
    EXPECT_TRUE(geometry::inside_all_edges(square, origin, {0.5, 0.95}, 0.04, s));
    EXPECT_FALSE(geometry::inside_all_edges(square, origin, {0.5, 0.95}, 0.06, s));
    EXPECT_FALSE(geometry::inside_all_edges(square, origin, {0.5, 1.01}, 0.0, s));
    // Each edge alone decides: just outside any one of them fails.
    for (const Vec2& v : {Vec2{0.5, -0.01}, Vec2{1.01, 0.5}, Vec2{-0.01, 0.5}})
      EXPECT_FALSE(geometry::inside_all_edges(square, origin, v, 0.0, s));
    // A NaN fails.
    EXPECT_FALSE(geometry::inside_all_edges(square, origin, {std::nan(""), 0.5}, 0.0, s));
  }
}

// Random convex polygons of 3 to 20 corners, 5 km from the world origin and measured from a point near them (as
// the narrow phase measures from a vertex of the other floe), tested at random points and at points placed 0.5 to
// 2 margins either side of each edge's line and right on it: every variant gives the formula's answer.
TEST(InsideAllEdges, EveryVariantGivesTheFormulasAnswer) {
  std::mt19937_64 rng(4242);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  const double margin = 1e-9;
  long inside = 0, outside = 0;
  for (int n = 3; n <= 20; ++n) {
    for (int poly_index = 0; poly_index < 20; ++poly_index) {
      const double r = 2.0 + 48.0 * u(rng);
      const Vec2 where{5000.0 * (2.0 * u(rng) - 1.0), 5000.0 * (2.0 * u(rng) - 1.0)};
      const auto poly =
          tsupport::transform(tsupport::random_convex(rng, n, r, r * (0.3 + 0.7 * u(rng))), 6.3 * u(rng), where);
      const Vec2 origin = where + r * Vec2{2.0 * u(rng) - 1.0, 2.0 * u(rng) - 1.0};
      std::vector<Vec2> points;
      for (int k = 0; k < 40; ++k) points.push_back(where + 1.2 * r * Vec2{2.0 * u(rng) - 1.0, 2.0 * u(rng) - 1.0});
      for (int k = 0; k < n; ++k) {
        const Vec2 q0 = poly[static_cast<std::size_t>((k + n - 1) % n)], q1 = poly[static_cast<std::size_t>(k)];
        const Vec2 e = q1 - q0, out = geometry::perp_right(e).normalized();
        for (const double c : {-2.0, -1.01, -1.0, -0.99, -0.5, 0.0, 0.5, 2.0}) {
          const double t = 0.05 + 0.9 * u(rng);  // along the edge, clear of its corners
          points.push_back(q0 + t * e + c * margin * e.norm() * out);
        }
      }
      for (const Vec2& p : points) {
        const Vec2 v = p - origin;
        const bool expected = reference(poly, origin, v, margin);
        (expected ? inside : outside) += 1;
        for (const EdgeSimd s : kVariants)
          ASSERT_EQ(geometry::inside_all_edges(poly, origin, v, margin, s), expected)
              << n << " corners, polygon " << poly_index << ", variant " << static_cast<int>(s);
      }
    }
  }
  // Both answers occur often (a test that only ever saw one could not tell the variants apart).
  EXPECT_GT(inside, 10000);
  EXPECT_GT(outside, 10000);
  std::printf("%ld inside, %ld not; AVX2 %s\n", inside, outside, geometry::has_avx2() ? "tested" : "not available");
}
