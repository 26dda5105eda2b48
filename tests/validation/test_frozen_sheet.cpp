// Frozen ice sheets (scene/ice_sheet.h with bonds) against their references: an intact sheet at rest keeps every
// bond, a sheet pulled apart breaks in the middle, the small-strain modulus converges as the elements refine, and a
// Voronoi strip bends like an Euler-Bernoulli cantilever of its own modulus. The bond mechanics on square elements
// are in test_bonds.cpp.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <limits>
#include <numeric>
#include <string>
#include <utility>
#include <vector>

#include "bond_support.h"
#include "bonds/bond_set.h"
#include "dynamics/world.h"
#include "scene/ice_sheet.h"
#include "scene/scene_reader.h"
#include "test_support.h"

using namespace polyfloe;
using geometry::Vec2;
using namespace tsupport::bond;

namespace {

TEST(FrozenSheet, EverySharedEdgeIsBondedAndTheSheetAtRestKeepsEveryBond) {
  // A 60 m x 60 m sheet of triangles (cells fanned from their centroids) in still water, all drag terms on: nothing
  // moves, no bond fails, and the contact law never acts between bonded elements.
  const std::string text =
      "run: {duration: 2}\n"
      "ice_sheet: {region: [0, 0, 60, 60], cell_size: 11.28, relaxation: 2, elements: triangles, "
      "bonds: {tensile_strength: 0.1e6, shear_strength: 0.1e6}}\n";
  const scene::Scene sc = scene::parse_scene(text, "frozen.yaml", {});
  dynamics::World w = scene::build_world(sc);
  const scene::SheetElementsOut el = scene::ice_sheet_elements(*sc.ice_sheet);
  ASSERT_NE(w.bonds(), nullptr);
  EXPECT_EQ(w.bonds()->faces(), el.faces.size());
  // Every edge is either on the region's boundary or bonded: sum of edge lengths = 2 x bonded + boundary (240 m).
  double all = 0.0, bonded = 0.0;
  for (const auto& p : el.polygons)
    for (std::size_t j = 0; j < p.size(); ++j) all += (p[(j + 1) % p.size()] - p[j]).norm();
  for (std::size_t f = 0; f < w.bonds()->faces(); ++f) bonded += w.bonds()->face_length(f);
  EXPECT_NEAR(all - 2.0 * bonded, 240.0, 1e-6);
  const double dt = scene::time_step(sc, w);
  EXPECT_NEAR(dt, scene::bond_time_step(w), 1e-15) << "the bonds set the step";
  // Elements that only share a corner (the triangles of a cell around its centroid) are corner pairs: locked while
  // the faces at their corner hold, so no contact acts anywhere in the intact sheet.
  EXPECT_FALSE(el.corners.empty());
  for (const scene::SheetCorner& c : el.corners) EXPECT_TRUE(w.bonds()->bonded(c.a, c.b));
  for (int k = 0; k < 3000; ++k) {
    w.step(dt);
    ASSERT_TRUE(w.contacts().empty()) << "step " << k;
  }
  EXPECT_EQ(w.bonds()->intact_faces(), w.bonds()->faces());
  EXPECT_EQ(w.bonds()->intact_points(), w.bonds()->points());
  EXPECT_LT(w.max_speed(), 1e-9);
}

TEST(FrozenSheet, PulledApartItBreaksInTheMiddle) {
  // A bonded sheet of cells whose two halves are set moving apart: the bonds across the middle fail in tension,
  // while those far from it hold.
  const std::string text =
      "run: {duration: 2}\n"
      "ice_sheet: {region: [0, 0, 60, 30], cell_size: 10, relaxation: 3, "
      "bonds: {tensile_strength: 0.05e6, shear_strength: 0.05e6}}\n";
  const scene::Scene sc = scene::parse_scene(text, "pull.yaml", {});
  dynamics::World w = scene::build_world(sc);
  const std::size_t faces = w.bonds()->faces();
  for (int i = 0; i < static_cast<int>(w.size()); ++i)
    w.set_velocity(i, {w.positions()[static_cast<std::size_t>(i)].x() < 30.0 ? -0.5 : 0.5, 0.0}, 0.0);
  const double dt = scene::time_step(sc, w);
  for (int k = 0; k < 4000; ++k) w.step(dt);
  EXPECT_LT(w.bonds()->intact_faces(), faces);
  EXPECT_GT(w.bonds()->intact_faces(), faces / 2) << "only the faces near the middle should go";
  std::size_t broken_far = 0;
  for (std::size_t f = 0; f < faces; ++f)
    if (!w.bonds()->face_intact(f) && std::abs(w.bonds()->face_midpoint0(f).x() - 30.0) > 15.0) ++broken_far;
  EXPECT_EQ(broken_far, 0u);
}

}  // namespace

namespace {

// Small-strain modulus of a frozen sheet: a `side` x `side` sheet squeezed slowly between two plates (quasi-static,
// far below the 1 km/s wave speed), stress = plate force / (side x h), strain = the slope of the elements' x
// displacement against x over the middle 60 % of the sheet (so the plate contacts' own compliance does not count).
struct Modulus {
  double e_eff = 0.0;  // [Pa]
  std::size_t elements = 0;
};

Modulus sheet_modulus(double side, double cell, const char* elements) {
  const std::string s = std::to_string(side), h = std::to_string(side + 20), c = std::to_string(side / 2);
  const std::string text =
      "forcing: {ocean: {form_drag: {enabled: false}, moment_drag: {enabled: false}, skin_drag: {enabled: false}},"
      " air: {drag: {enabled: false}}}\n"
      "ice_sheet: {region: [0, 0, " +
      s + ", " + s + "], cell_size: " + std::to_string(cell) + ", relaxation: 3, elements: " + elements +
      ", seed: 4,"
      " bonds: {tensile_strength: 1e12, shear_strength: 1e12, damping_ratio: 0.5}}\n"
      "floes:\n"
      "  - {rectangle: {width: 10, height: " +
      h + "}, position: [-5, " + c +
      "], velocity: [0.01, 0], motion: kinematic}\n"
      "  - {rectangle: {width: 10, height: " +
      h + "}, position: [" + std::to_string(side + 5) + ", " + c + "], velocity: [-0.01, 0], motion: kinematic}\n";
  const scene::Scene sc = scene::parse_scene(text, "modulus.yaml", {});
  dynamics::World w = scene::build_world(sc);
  const double dt = scene::time_step(sc, w);
  // Each element's start by id (the World stores its bodies anew as it steps: indices change, ids do not); the two
  // plates are the first two bodies built.
  std::vector<std::pair<dynamics::BodyId, Vec2>> x0;
  for (std::size_t i = 2; i < w.size(); ++i) x0.emplace_back(w.id(static_cast<int>(i)), w.positions()[i]);
  const dynamics::BodyId left = w.id(0), right = w.id(1);
  const double duration = 0.02 * side;  // 2e-4 strain at 0.02 m/s closing
  while (w.time() < duration) w.step(dt);
  const double force = 0.5 * (-w.forces()[static_cast<std::size_t>(w.index_of(left))].x() +
                              w.forces()[static_cast<std::size_t>(w.index_of(right))].x());
  double sx = 0, su = 0, sxx = 0, sxu = 0, n = 0;
  for (const auto& [id, start] : x0) {
    if (start.x() < 0.2 * side || start.x() > 0.8 * side) continue;
    const double x = start.x(), u = w.positions()[static_cast<std::size_t>(w.index_of(id))].x() - start.x();
    sx += x, su += u, sxx += x * x, sxu += x * u, n += 1;
  }
  const double slope = (n * sxu - sx * su) / (n * sxx - sx * sx);  // du/dx < 0 in compression
  return {force / (side * 1.0) / -slope, w.size() - 2};
}

TEST(FrozenSheet, SmallStrainModulusConvergesAsElementsRefine) {
  // The same 120 m sheet with cells of 24, 17 and 12 m (cells as elements, then fanned into triangles): the
  // effective modulus settles to a fixed fraction of E as the elements refine.
  std::vector<double> ratio_cells, ratio_tri;
  for (double cell : {24.0, 17.0, 12.0}) {
    const Modulus mc = sheet_modulus(120.0, cell, "cells");
    const Modulus mt = sheet_modulus(120.0, cell, "triangles");
    ratio_cells.push_back(mc.e_eff / kE);
    ratio_tri.push_back(mt.e_eff / kE);
    std::printf("cell %4.0f m: cells %4zu elements E_eff/E = %.3f; triangles %4zu elements E_eff/E = %.3f\n", cell,
                mc.elements, mc.e_eff / kE, mt.elements, mt.e_eff / kE);
  }
  for (const auto& r : {ratio_cells, ratio_tri}) {
    for (double x : r) {
      EXPECT_GT(x, 0.3);
      EXPECT_LT(x, 1.2);
    }
    EXPECT_LT(std::abs(r[2] - r[1]), std::abs(r[1] - r[0]) + 0.03) << "the ratio settles as the elements refine";
  }
}

}  // namespace

namespace {

// A frozen Voronoi strip (scene/ice_sheet.h, cells as elements) kStripLength x 10 m, with the elements whose
// centroids lie left of x = 5 m fixed (the clamp), loaded on the elements within 5 m of the far end.
constexpr double kStripLength = 60.0;  // [m]
struct VoronoiStrip {
  dynamics::World world;
  std::vector<int> loaded;
  double clamp_x = 0.0, load_x = 0.0;  // mean centroid x of the clamp's inner elements and of the loaded ones [m]
};

VoronoiStrip voronoi_strip() {
  scene::IceSheetSpec spec;
  spec.region_min = {0.0, 0.0};
  spec.region_max = {kStripLength, 10.0};
  spec.cell_size = 3.0;
  spec.relaxation = 3;
  spec.seed = 2;
  const scene::SheetElementsOut el = scene::ice_sheet_elements(spec);
  dynamics::WorldSettings ws;
  ws.drift = forcing::DriftSettings::none();
  VoronoiStrip st{dynamics::World(ws), {}, 0.0, 0.0};
  std::vector<Vec2> centre;
  for (std::size_t e = 0; e < el.polygons.size(); ++e) {
    Vec2 c{0, 0};
    auto shape =
        std::make_shared<const geometry::ConvexPolygon>(geometry::ConvexPolygon::from_vertices(el.polygons[e], &c));
    centre.push_back(c);
    st.world.add_body({.id = e,
                       .shape = shape,
                       .position = c,
                       .thickness = kH,
                       .density = kRho,
                       .motion = c.x() < 5.0 ? dynamics::Motion::fixed : dynamics::Motion::dynamic});
    if (c.x() > kStripLength - 5.0) st.loaded.push_back(static_cast<int>(e));
  }
  bonds::BondMaterial m = material(1e12);
  m.shear_strength = 1e12;
  m.damping_ratio = 0.7;
  bonds::BondSet b(m);
  double sum = 0.0;
  int n = 0;
  for (const scene::SheetFace& f : el.faces) {
    b.add_face({.a = f.a,
                .b = f.b,
                .id_a = static_cast<std::uint64_t>(f.a),
                .id_b = static_cast<std::uint64_t>(f.b),
                .p0 = f.p0,
                .p1 = f.p1,
                .thickness = kH,
                .centre_a = centre[static_cast<std::size_t>(f.a)],
                .centre_b = centre[static_cast<std::size_t>(f.b)]});
    const bool fa = centre[static_cast<std::size_t>(f.a)].x() < 5.0,
               fb = centre[static_cast<std::size_t>(f.b)].x() < 5.0;
    if (fa != fb) {  // a clamp face: the spring starts at the fixed element's centroid
      sum += centre[static_cast<std::size_t>(fa ? f.a : f.b)].x();
      ++n;
    }
  }
  for (const scene::SheetCorner& c : el.corners)
    if (!c.faces.empty()) b.add_corner_pair(c.a, c.b, c.faces);
  st.world.set_bonds(std::move(b));
  st.clamp_x = sum / n;
  double lx = 0.0;
  for (int e : st.loaded) lx += centre[static_cast<std::size_t>(e)].x();
  st.load_x = lx / static_cast<double>(st.loaded.size());
  return st;
}

TEST(FrozenSheet, VoronoiCantileverMatchesEulerBernoulliWithItsOwnModulus) {
  // A 60 m x 10 m strip of ~85 Voronoi cells, clamped at its left end: E_eff from an axial pull of the same strip,
  // then the end deflection under a transverse end load against P L^3 / (3 E_eff I), L from the clamp faces'
  // fixed centroids to the loaded centroids (the same strip at 100 m with 2.5 m cells: ratio 0.924).
  VoronoiStrip pull = voronoi_strip();
  const double P_axial = 1.0e6, L = pull.load_x - pull.clamp_x, w = 10.0, I = kH * w * w * w / 12.0;
  const Vec2 u = mean_displacement_under_load(pull.world, pull.loaded, {P_axial, 0.0}, 5.0, 5.0);
  const double e_eff = P_axial * L / (w * kH * u.x());
  VoronoiStrip bend = voronoi_strip();
  const double P = 1.0e4;  // [N]
  // (the first bending period is ~2 s)
  const Vec2 d = mean_displacement_under_load(bend.world, bend.loaded, {0.0, P}, 12.0, 8.0);
  const double euler_bernoulli = P * L * L * L / (3.0 * e_eff * I);
  std::printf(
      "Voronoi strip (%zu elements, L = %.1f m): axial E_eff / E = %.3f; end deflection %.5f m, "
      "Euler-Bernoulli %.5f m (ratio %.3f)\n",
      bend.world.size(), L, e_eff / kE, d.y(), euler_bernoulli, d.y() / euler_bernoulli);
  EXPECT_NEAR(d.y() / euler_bernoulli, 1.0, 0.10);
}

}  // namespace
