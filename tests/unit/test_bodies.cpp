// The planar World's bodies (dynamics/bodies.h): what add() derives of a body against closed forms, and the bodies
// it refuses without changing the arrays, and the one list of its per-body arrays that a permutation walks.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <memory>
#include <numbers>
#include <stdexcept>
#include <string>

#include "contact/contact_law.h"
#include "dynamics/bodies.h"

namespace polyfloe::dynamics {
namespace {

std::shared_ptr<const geometry::ConvexPolygon> rectangle(double w, double h) {
  return std::make_shared<const geometry::ConvexPolygon>(geometry::ConvexPolygon::rectangle(w, h));
}

BodyDesc plate(BodyId id, Motion motion = Motion::dynamic) {
  BodyDesc d;
  d.id = id;
  d.shape = rectangle(4.0, 2.0);
  d.position = {10.0, -3.0};
  d.velocity = {0.5, 0.25};
  d.angular_velocity = 0.1;
  d.thickness = 1.0;
  d.density = 900.0;
  d.motion = motion;
  return d;
}

TEST(Bodies, ARectangularPrismGetsItsMassInertiaDraftSideAreaAndQuadratureFromClosedForms) {
  Bodies b;
  ASSERT_EQ(b.add(plate(7), 1000.0, forcing::Quadrature::degree2), 0);
  const double m = 4.0 * 2.0 * 1.0 * 900.0;  // 7,200 kg
  EXPECT_NEAR(b.mass[0], m, 1e-9 * m);
  EXPECT_NEAR(b.inertia[0], m * (16.0 + 4.0) / 12.0, 1e-9 * m);  // m (a^2 + b^2) / 12
  EXPECT_NEAR(b.inv_mass[0], 1.0 / m, 1e-12 / m);
  EXPECT_NEAR(b.draft[0], 0.9, 1e-12);             // h rho_ice / rho_w
  EXPECT_NEAR(b.side_area[0], 12.0 * 0.9, 1e-12);  // perimeter x draft
  EXPECT_NEAR(b.plan_area[0], 8.0, 1e-12);
  EXPECT_NEAR(b.equivalent_radius[0], std::sqrt(8.0 / std::numbers::pi), 1e-12);
  EXPECT_EQ(b.radius[0], b.equivalent_radius[0]);
  EXPECT_NEAR(b.reach[0], std::sqrt(5.0), 1e-12);  // the corner's distance from the centroid
  EXPECT_EQ(b.vert_off[1] - b.vert_off[0], 4);
  EXPECT_EQ(b.local_xy.size(), 4u);
  // The quadrature points carry the area, centred on the centroid, and the second moment of a degree-2 rule.
  double area = 0.0, mx = 0.0, my = 0.0, jz = 0.0;
  for (int q = b.quad_off[0]; q < b.quad_off[1]; ++q) {
    area += b.quad_weight[q];
    mx += b.quad_weight[q] * b.quad_lx[q];
    my += b.quad_weight[q] * b.quad_ly[q];
    jz += b.quad_weight[q] * (b.quad_lx[q] * b.quad_lx[q] + b.quad_ly[q] * b.quad_ly[q]);
  }
  EXPECT_NEAR(area, 8.0, 1e-12);
  EXPECT_NEAR(mx, 0.0, 1e-12);
  EXPECT_NEAR(my, 0.0, 1e-12);
  EXPECT_NEAR(jz, 8.0 * (16.0 + 4.0) / 12.0, 1e-12);
  EXPECT_EQ(b.max_quad_points, static_cast<std::size_t>(b.quad_off[1]));
  EXPECT_EQ(b.max_vertices, 4u);
  EXPECT_EQ(b.pos[0], Vec2(10.0, -3.0));
  EXPECT_EQ(b.vel[0], Vec2(0.5, 0.25));
  EXPECT_EQ(b.omega[0], 0.1);
  EXPECT_EQ(b.dynamic_mass, b.mass[0]);
  EXPECT_EQ(b.dynamic_count, 1);
  EXPECT_EQ(b.index_of(7), 0);
  EXPECT_EQ(b.index_of(8), -1);
}

TEST(Bodies, FixedBodiesAreImmovableForTheContactLawAndDenseOnesSinkToTheirThickness) {
  Bodies b;
  BodyDesc wall = plate(1, Motion::fixed);
  wall.density = 2000.0;  // denser than water: fully submerged
  b.add(wall, 1025.0, forcing::Quadrature::centroid);
  EXPECT_EQ(b.inv_mass[0], 0.0);
  EXPECT_EQ(b.inv_inertia[0], 0.0);
  EXPECT_EQ(b.radius[0], contact::kInfinite);
  EXPECT_EQ(b.vel[0], Vec2(0.0, 0.0));  // a fixed body never moves, whatever it was given
  EXPECT_EQ(b.omega[0], 0.0);
  EXPECT_EQ(b.draft[0], 1.0);
  EXPECT_EQ(b.dynamic_mass, 0.0);
  EXPECT_EQ(b.dynamic_count, 0);
  b.add(plate(2, Motion::kinematic), 1025.0, forcing::Quadrature::centroid);
  EXPECT_EQ(b.vel[1], Vec2(0.5, 0.25));  // a kinematic body keeps its prescribed velocity
  EXPECT_EQ(b.inv_mass[1], 0.0);
  EXPECT_EQ(b.quad_off[2] - b.quad_off[1], 1);  // the centroid rule: one point
}

TEST(Bodies, ABodyRefusedNamesItselfAndLeavesTheArraysAsTheyWere) {
  Bodies b;
  b.add(plate(1), 1025.0, forcing::Quadrature::degree2);
  auto refused = [&](BodyDesc d, const std::string& words) {
    try {
      b.add(d, 1025.0, forcing::Quadrature::degree2);
      ADD_FAILURE() << "accepted: " << words;
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find(words), std::string::npos) << e.what();
    }
    EXPECT_EQ(b.size(), 1u);
    EXPECT_EQ(b.pos.size(), 1u);
    EXPECT_EQ(b.quad_off.size(), 2u);
    EXPECT_EQ(b.vert_off.size(), 2u);
  };
  refused(plate(1), "duplicate body id 1");
  BodyDesc d = plate(5);
  d.shape.reset();
  refused(d, "body 5 has no shape");
  d = plate(6);
  d.thickness = 0.0;
  refused(d, "body 6: thickness must be positive");
  d.thickness = std::numeric_limits<double>::quiet_NaN();
  refused(d, "body 6: thickness must be positive");
  d = plate(7);
  d.density = -1.0;
  refused(d, "body 7: density must be positive");
}

TEST(Bodies, EveryArrayHasARowPerBodyAndPermuteMovesEachRowWithItsBody) {
  Bodies b;
  for (int k = 0; k < 3; ++k) {
    BodyDesc d = plate(static_cast<BodyId>(10 + k));
    d.shape = std::make_shared<const geometry::ConvexPolygon>(geometry::ConvexPolygon::regular(3 + k, 1.0 + k));
    d.position = {1.0 * k, 0.0};
    d.motion = k == 1 ? Motion::fixed : Motion::dynamic;
    b.add(d, 1025.0, forcing::Quadrature::degree2);
  }
  b.ghost[2] = 1;
  // The list the permutation walks holds every array (the counts that the build holds against the members).
  std::size_t rows = 0, ranges = 0;
  Bodies::for_each_array(
      b,
      [&](const auto& a) {
        ++rows;
        EXPECT_TRUE(a.size() == 3u || a.empty()) << a.size();  // (the evaluation's are sized by the World)
      },
      [&](const std::vector<int>& off, const auto&... a) {
        ranges += 1 + sizeof...(a);
        EXPECT_EQ(off.size(), 4u);
        const std::size_t values = static_cast<std::size_t>(off.back());
        const std::size_t sizes[] = {a.size()...};
        for (const std::size_t n : sizes) EXPECT_EQ(n, values);
      });
  EXPECT_EQ(rows, Bodies::kRowArrays);
  EXPECT_EQ(ranges, Bodies::kRangeMembers);
  const Bodies before = b;
  const std::vector<int> from{2, 0, 1};
  b.permute(from);
  for (int k = 0; k < 3; ++k) {
    const auto i = static_cast<std::size_t>(from[static_cast<std::size_t>(k)]);
    const auto n = static_cast<std::size_t>(k);
    EXPECT_EQ(b.id[n], before.id[i]);
    EXPECT_EQ(b.index_of(b.id[n]), k);
    EXPECT_EQ(b.pos[n], before.pos[i]);
    EXPECT_EQ(b.mass[n], before.mass[i]);
    EXPECT_EQ(b.motion[n], before.motion[i]);
    EXPECT_EQ(b.ghost[n], before.ghost[i]);
    EXPECT_EQ(b.shape[n], before.shape[i]);
    ASSERT_EQ(b.vert_off[n + 1] - b.vert_off[n], before.vert_off[i + 1] - before.vert_off[i]);
    for (int v = 0; v < b.vert_off[n + 1] - b.vert_off[n]; ++v)
      EXPECT_EQ(b.local_xy[static_cast<std::size_t>(b.vert_off[n] + v)],
                before.local_xy[static_cast<std::size_t>(before.vert_off[i] + v)]);
    ASSERT_EQ(b.quad_off[n + 1] - b.quad_off[n], before.quad_off[i + 1] - before.quad_off[i]);
    for (int q = 0; q < b.quad_off[n + 1] - b.quad_off[n]; ++q)
      EXPECT_EQ(b.quad_weight[static_cast<std::size_t>(b.quad_off[n] + q)],
                before.quad_weight[static_cast<std::size_t>(before.quad_off[i] + q)]);
  }
  EXPECT_EQ(b.dynamic_mass, before.dynamic_mass);
}

}  // namespace
}  // namespace polyfloe::dynamics
