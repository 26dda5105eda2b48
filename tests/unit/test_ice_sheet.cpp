// Level-ice sheets (scene/ice_sheet.h): Voronoi cells that tile the region exactly (areas sum to the region, no two
// overlap, each convex and inside), the cell count from cell_size, determinism, the area spread of Poisson-Voronoi
// cells against its known value and its reduction by Lloyd relaxation; the scene block and its errors.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "scene/floe_field.h"
#include "scene/ice_sheet.h"
#include "scene_test_support.h"

namespace polyfloe::scene {
namespace {

geometry::Aabb box_of(const std::vector<Vec2>& v) {
  geometry::Aabb b{v[0], v[0]};
  for (const Vec2& p : v) b.lo = b.lo.cwiseMin(p), b.hi = b.hi.cwiseMax(p);
  return b;
}

// Coefficient of variation of the areas of the cells that do not touch the region's sides.
double interior_area_cv(const IceSheetSpec& s, const std::vector<std::vector<Vec2>>& cells) {
  std::vector<double> a;
  const double eps = 1e-9 * (s.region_max - s.region_min).maxCoeff();
  for (const auto& c : cells) {
    const geometry::Aabb b = box_of(c);
    if (b.lo.x() <= s.region_min.x() + eps || b.lo.y() <= s.region_min.y() + eps ||
        b.hi.x() >= s.region_max.x() - eps || b.hi.y() >= s.region_max.y() - eps)
      continue;
    a.push_back(geometry::polygon_properties(c).area);
  }
  double mean = 0.0, var = 0.0;
  for (double x : a) mean += x;
  mean /= static_cast<double>(a.size());
  for (double x : a) var += (x - mean) * (x - mean);
  var /= static_cast<double>(a.size() - 1);
  return std::sqrt(var) / mean;
}

TEST(IceSheet, CellsTileTheRegionExactly) {
  IceSheetSpec s;
  s.region_min = {-40.0, 10.0};
  s.region_max = {160.0, 110.0};
  s.cell_size = 12.0;
  for (int relaxation : {0, 3}) {
    SCOPED_TRACE(relaxation);
    s.relaxation = relaxation;
    const auto cells = voronoi_sheet(s);
    const double region = (s.region_max - s.region_min).prod();
    EXPECT_EQ(cells.size(), static_cast<std::size_t>(std::round(region / (0.25 * std::numbers::pi * 144.0))));
    double area = 0.0;
    std::vector<geometry::Aabb> boxes;
    for (const auto& c : cells) {
      ASSERT_EQ(geometry::convexity_error(c), "");
      area += geometry::polygon_properties(c).area;
      for (const Vec2& v : c) {
        EXPECT_GE(v.x(), s.region_min.x() - 1e-9);
        EXPECT_LE(v.x(), s.region_max.x() + 1e-9);
        EXPECT_GE(v.y(), s.region_min.y() - 1e-9);
        EXPECT_LE(v.y(), s.region_max.y() + 1e-9);
      }
      boxes.push_back(box_of(c));
    }
    EXPECT_NEAR(area, region, 1e-9 * region);
    // No two cells overlap (neighbours share an edge: separation 0 to rounding), and each has a neighbour.
    std::vector<int> touching(cells.size(), 0);
    for (std::size_t i = 0; i < cells.size(); ++i) {
      for (std::size_t j = i + 1; j < cells.size(); ++j) {
        if (!boxes[i].overlaps(boxes[j])) continue;
        const double sep = polygon_separation(cells[i], cells[j]);
        ASSERT_GE(sep, -1e-7) << "cells " << i << " and " << j;
        if (sep < 1e-7) ++touching[i], ++touching[j];
      }
    }
    for (std::size_t i = 0; i < cells.size(); ++i) EXPECT_GE(touching[i], 2) << i;
  }
}

TEST(IceSheet, ShortEdgesAreCollapsed) {
  // Poisson-Voronoi cells have edges down to a millionth of their size; the sheet collapses edges shorter than
  // kMinEdgeFraction x cell_size where every cell touched stays convex (not along the region's boundary).
  IceSheetSpec s;
  s.region_max = {400.0, 400.0};
  s.cell_size = 10.0;
  const auto cells = voronoi_sheet(s);
  const double shortest = 1.0;  // kMinEdgeFraction (0.1) x cell_size
  std::size_t edges = 0, short_inside = 0;
  double least = 1e300;
  for (const auto& c : cells) {
    for (std::size_t j = 0; j < c.size(); ++j) {
      const Vec2 a = c[j], b = c[(j + 1) % c.size()];
      ++edges;
      const bool along_side =
          (a.x() == b.x() && (a.x() == 0.0 || a.x() == 400.0)) || (a.y() == b.y() && (a.y() == 0.0 || a.y() == 400.0));
      if (along_side) continue;
      least = std::min(least, (a - b).norm());
      if ((a - b).norm() < shortest) ++short_inside;
    }
  }
  std::printf("%zu cells, %zu edge sides: %zu inner ones shorter than %.1f m left, the shortest %.3g m\n", cells.size(),
              edges, short_inside, shortest, least);
  EXPECT_LT(static_cast<double>(short_inside), 0.01 * static_cast<double>(edges));
}

TEST(IceSheet, DeterministicForASeed) {
  IceSheetSpec s;
  s.relaxation = 1;
  const auto a = voronoi_sheet(s), b = voronoi_sheet(s);
  EXPECT_EQ(a, b);
  s.seed = 2;
  EXPECT_NE(voronoi_sheet(s), a);
}

TEST(IceSheet, AreaSpreadOfPoissonVoronoiCellsAndLloyd) {
  // The area of a planar Poisson-Voronoi cell (mean 1) has variance 0.280 (Weaire et al. 1986; Ferenc & Neda 2007):
  // coefficient of variation 0.529. Lloyd's relaxation evens the cells out.
  IceSheetSpec s;
  s.region_max = {1000.0, 1000.0};
  s.cell_size = 15.0;  // ~5,700 cells
  const auto poisson = voronoi_sheet(s);
  const double cv0 = interior_area_cv(s, poisson);
  EXPECT_NEAR(cv0, 0.529, 0.03) << poisson.size() << " cells";
  s.relaxation = 5;
  const double cv5 = interior_area_cv(s, voronoi_sheet(s));
  EXPECT_LT(cv5, 0.5 * cv0);
  std::printf("area coefficient of variation: %.3f (Poisson-Voronoi, theory 0.529), %.3f after 5 Lloyd iterations\n",
              cv0, cv5);
}

TEST(IceSheet, BodiesGetConsecutiveIdsTheSpecsValuesAndCellCentroidsAndTinyCellsAreRefused) {
  IceSheetSpec s;
  s.region_max = {50.0, 50.0};
  s.cell_size = 10.0;
  s.thickness = 0.8;
  s.velocity = {0.1, 0.0};
  const auto bodies = ice_sheet_bodies(s, 900.0, 7);
  const auto cells = voronoi_sheet(s);
  ASSERT_EQ(bodies.size(), cells.size());
  for (std::size_t i = 0; i < bodies.size(); ++i) {
    EXPECT_EQ(bodies[i].id, 7 + i);
    EXPECT_EQ(bodies[i].thickness, 0.8);
    EXPECT_EQ(bodies[i].density, 900.0);
    EXPECT_EQ(bodies[i].velocity, s.velocity);
    EXPECT_NEAR((bodies[i].position - geometry::polygon_properties(cells[i]).centroid).norm(), 0.0, 1e-9);
  }
  s.cell_size = 0.01;
  EXPECT_NE(error_of([&] { voronoi_sheet(s); }).find("raise ice_sheet.cell_size"), std::string::npos);
}

TEST(IceSheetScene, BlockKeysRoundTripAndErrors) {
  const std::string sheet =
      "ice_sheet: {region: [0, 0, 100, 60], cell_size: 8, relaxation: 2, thickness: 0.5, "
      "velocity: [0.2, 0], seed: 9}\n";
  const Scene s = parse_scene(sheet, "t.yaml", {});  // the sheet alone is enough dynamic ice
  ASSERT_TRUE(s.ice_sheet.has_value());
  EXPECT_EQ(s.ice_sheet->cell_size, 8.0);
  EXPECT_EQ(s.ice_sheet->relaxation, 2);
  EXPECT_EQ(s.ice_sheet->seed, 9u);
  const Scene r = parse_scene(resolved_yaml(s), "r.yaml", {});
  ASSERT_TRUE(r.ice_sheet.has_value());
  EXPECT_EQ(r.ice_sheet->region_max, s.ice_sheet->region_max);
  EXPECT_EQ(r.ice_sheet->thickness, 0.5);
  EXPECT_EQ(r.ice_sheet->velocity, s.ice_sheet->velocity);
  const dynamics::World w = build_world(s);
  EXPECT_EQ(w.size(), voronoi_sheet(*s.ice_sheet).size());

  std::string m = parse_error("ice_sheet: {cell_size: -1}\n");
  EXPECT_TRUE(starts_with(m, "t.yaml:1:24: key 'ice_sheet.cell_size': -1 is outside the allowed range (0, 1e9] [m]"))
      << m;
  m = parse_error("ice_sheet: {region: [0, 0, 1000, 1000], cell_size: 0.5}\n");
  EXPECT_TRUE(contains(m, "key 'ice_sheet.cell_size': the region holds") && contains(m, "raise ice_sheet.cell_size"))
      << m;
  m = parse_error("ice_sheet: {relaxation: -1}\n");
  EXPECT_TRUE(contains(m, "key 'ice_sheet.relaxation'")) << m;
  m = parse_error("ice_sheet: {cells: 10}\n");
  EXPECT_TRUE(contains(m,
                       "unknown key 'ice_sheet.cells'; allowed in 'ice_sheet': region, cell_size, relaxation, "
                       "thickness, velocity, seed, elements, bonds"))
      << m;
  // Elements and bonds.
  const Scene frozen = parse_scene(
      "ice_sheet: {elements: triangles, bonds: {tensile_strength: 0.5e6, shear_strength: 0.7e6, "
      "friction_angle: 0.5, points_per_face: 3, damping_ratio: 0.2}}\n",
      "f.yaml", {});
  EXPECT_EQ(frozen.ice_sheet->elements, SheetElements::triangles);
  ASSERT_TRUE(frozen.ice_sheet->bonds.has_value());
  const Scene back = parse_scene(resolved_yaml(frozen), "r.yaml", {});
  ASSERT_TRUE(back.ice_sheet->bonds.has_value());
  EXPECT_EQ(back.ice_sheet->elements, SheetElements::triangles);
  EXPECT_EQ(back.ice_sheet->bonds->tensile_strength, 0.5e6);
  EXPECT_EQ(back.ice_sheet->bonds->shear_strength, 0.7e6);
  EXPECT_EQ(back.ice_sheet->bonds->friction_angle, 0.5);
  EXPECT_EQ(back.ice_sheet->bonds->points_per_face, 3);
  EXPECT_EQ(back.ice_sheet->bonds->damping_ratio, 0.2);
  EXPECT_FALSE(parse_scene(resolved_yaml(s), "r.yaml", {}).ice_sheet->bonds.has_value());
  m = parse_error("ice_sheet: {bonds: {tensile_strength: 0}}\n");
  EXPECT_TRUE(contains(m, "key 'ice_sheet.bonds.tensile_strength': 0 is outside the allowed range (0, inf) [Pa]")) << m;
  m = parse_error("ice_sheet: {bonds: {points_per_face: 1}}\n");
  EXPECT_TRUE(contains(m, "key 'ice_sheet.bonds.points_per_face'")) << m;
  m = parse_error("ice_sheet: {bonds: {friction_angle: 1.6}}\n");
  EXPECT_TRUE(contains(m, "key 'ice_sheet.bonds.friction_angle'") && contains(m, "[rad]")) << m;
  m = parse_error("ice_sheet: {elements: quads}\n");
  EXPECT_TRUE(contains(m, "expected one of cells, triangles, got 'quads'")) << m;
  m = parse_error("ice_sheet: {bonds: {strength: 1}}\n");
  EXPECT_TRUE(contains(m, "unknown key 'ice_sheet.bonds.strength'")) << m;

  // A body inside the sheet is refused, naming both.
  const Scene clash = parse_scene(sheet +
                                      "floes:\n  - {regular: {sides: 4, radius: 3}, position: [50, 30], "
                                      "motion: fixed}\n",
                                  "c.yaml", {});
  m = error_of([&] { build_world(clash); });
  EXPECT_TRUE(contains(m, "(ice_sheet element") && contains(m, "overlaps c.yaml:3:5 (floes.0) initially")) << m;
}

// Found by fuzzing (tests/fuzz/fuzz_scene_parser.cpp): the reader allowed friction_angle in (0, pi/2] instead of the
// documented [0, pi/2), so the default 0, written out by resolved_yaml(), did not read back, and pi/2 passed the
// reader to fail later in the bond model without a line number.
TEST(IceSheetScene, FrictionAngleRangeIncludesZeroExcludesRightAngle) {
  const Scene s = parse_scene("ice_sheet: {bonds: {friction_angle: 0}}\n", "f.yaml", {});
  ASSERT_TRUE(s.ice_sheet->bonds.has_value());
  EXPECT_EQ(s.ice_sheet->bonds->friction_angle, 0.0);
  const Scene defaults = parse_scene("ice_sheet: {bonds: {}}\n", "d.yaml", {});
  const Scene back = parse_scene(resolved_yaml(defaults), "r.yaml", {});
  ASSERT_TRUE(back.ice_sheet->bonds.has_value());
  EXPECT_EQ(back.ice_sheet->bonds->friction_angle, 0.0);
  const std::string m = parse_error("ice_sheet: {bonds: {friction_angle: 1.5707963267948966}}\n");
  EXPECT_TRUE(contains(m, "t.yaml:1:37: key 'ice_sheet.bonds.friction_angle'")) << m;
  EXPECT_TRUE(contains(m, "outside the allowed range [0, 1.5707963267948966) [rad]")) << m;
}

}  // namespace
}  // namespace polyfloe::scene
