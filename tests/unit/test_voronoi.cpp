// Voronoi cells of a box (Boost.Polygon behind geometry/voronoi.h), against the definition: the cells tile the box
// (areas sum to its area, 1e-9), each is a convex counter-clockwise polygon containing its site, and every cell
// vertex is at least as close to its own site as to any other (brute force, within twice the snapping step of
// box size / 2^28, here 7.5e-6 m); bad sites are refused.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "geometry/polygon.h"
#include "geometry/voronoi.h"

using namespace polyfloe::geometry;

namespace {

TEST(Voronoi, CellsTileTheBoxAndMatchTheDefinition) {
  const Aabb box{{-200.0, 100.0}, {800.0, 700.0}};
  for (int n : {1, 2, 7, 500, 3000}) {
    std::mt19937_64 rng(static_cast<unsigned>(n));
    std::uniform_real_distribution<double> ux(-199.0, 799.0), uy(101.0, 699.0);
    std::vector<Vec2> sites(static_cast<std::size_t>(n));
    for (Vec2& s : sites) s = {ux(rng), uy(rng)};
    const auto cells = voronoi_cells(sites, box);
    ASSERT_EQ(cells.size(), sites.size());
    double area = 0.0;
    double worst = 0.0;
    for (std::size_t i = 0; i < cells.size(); ++i) {
      const auto& c = cells[i];
      ASSERT_GE(c.size(), 3u) << i;
      EXPECT_EQ(convexity_error(c), "") << "cell " << i;
      const PolygonProperties p = polygon_properties(c);
      area += p.area;
      // the site is inside its cell
      for (std::size_t k = 0; k < c.size(); ++k)
        EXPECT_GE(cross(c[(k + 1) % c.size()] - c[k], sites[i] - c[k]), 0.0) << "cell " << i;
      // every vertex is no closer to another site (ties: the vertex is on the shared boundary)
      for (const Vec2& v : c) {
        const double own = (v - sites[i]).norm();
        for (std::size_t j = 0; j < sites.size(); ++j) worst = std::max(worst, own - (v - sites[j]).norm());
      }
    }
    const double box_area = (box.hi - box.lo).prod();
    std::printf("%d sites: cell areas sum to %.12f of the box; worst vertex nearer another site by %.2e m\n", n,
                area / box_area, worst);
    EXPECT_NEAR(area, box_area, 1e-9 * box_area);
    EXPECT_LT(worst, 2.0 * 1000.0 / 268435456.0);
  }
}

TEST(Voronoi, BadSitesAreRefused) {
  const Aabb box{{0.0, 0.0}, {10.0, 10.0}};
  const std::vector<Vec2> outside{{1.0, 1.0}, {10.0, 5.0}};
  EXPECT_THROW(voronoi_cells(outside, box), VoronoiError);
  const std::vector<Vec2> same{{1.0, 1.0}, {5.0, 5.0}, {1.0, 1.0 + 1e-12}};
  try {
    voronoi_cells(same, box);
    ADD_FAILURE() << "coincident sites accepted";
  } catch (const VoronoiError& e) {
    EXPECT_NE(std::string(e.what()).find("sites 0 and 2 coincide"), std::string::npos) << e.what();
  }
  EXPECT_THROW(voronoi_cells(same, Aabb{{0.0, 0.0}, {0.0, 10.0}}), VoronoiError);
}

}  // namespace
