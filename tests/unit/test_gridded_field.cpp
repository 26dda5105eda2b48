// The gridded ocean field (dem/forcing/gridded_field.*): trilinear in space and linear in time reproduce any field
// that is linear in each of x, y, z, t exactly (to rounding); a smooth field converges at second order in the grid
// spacing; land, the grid's edge and the time boundaries do what the scene says, never garbage.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>

#include "forcing/analytic_fields.h"
#include "forcing/gridded_field.h"

namespace polyfloe::forcing {
namespace {

std::vector<double> axis(double a, double b, std::size_t n) {
  std::vector<double> v(n);
  for (std::size_t i = 0; i < n; ++i) v[i] = a + (b - a) * static_cast<double>(i) / static_cast<double>(n - 1);
  return v;
}

template <class F>
GridData make_grid(std::vector<double> x, std::vector<double> y, std::vector<double> z, std::vector<double> t,
                   F velocity) {
  GridData g{std::move(x), std::move(y), std::move(z), std::move(t), {}, {}, {}};
  g.u.resize(g.nodes_per_snapshot() * g.t.size());
  g.v.resize(g.u.size());
  g.wet.assign(g.nodes_per_snapshot(), 1);
  for (std::size_t it = 0; it < g.t.size(); ++it)
    for (std::size_t iz = 0; iz < g.z.size(); ++iz)
      for (std::size_t iy = 0; iy < g.y.size(); ++iy)
        for (std::size_t ix = 0; ix < g.x.size(); ++ix) {
          const Vec2 u = velocity(Vec3{g.x[ix], g.y[iy], g.z[iz]}, g.t[it]);
          g.u[g.index(it, iz, iy, ix)] = u.x();
          g.v[g.index(it, iz, iy, ix)] = u.y();
        }
  return g;
}

GriddedField field_of(GridData g, GriddedFieldOptions o = {}) {
  if (o.source.empty()) o.source = "test.h5";
  return GriddedField(std::make_shared<const GridData>(std::move(g)), o);
}

// Multilinear in (x, y, z) and linear in t, with every cross term: trilinear interpolation is exact for it.
Vec2 multilinear(const Vec3& p, double t) {
  const double x = p.x() / 100.0, y = p.y() / 100.0, z = p.z();
  return {0.3 + 0.2 * x - 0.1 * y + 0.05 * z + 0.01 * x * y * z + 0.002 * t + 0.001 * t * x,
          -0.1 + 0.05 * x * y + 0.3 * z - 0.1 * x * z + 0.004 * t * y};
}

TEST(GriddedField, ExactForMultilinearFieldsOnUniformAndNonUniformAxes) {
  // x uniform (fast path), y stretched (binary search), three z levels, three snapshots unevenly spaced.
  const std::vector<double> y{0.0, 10.0, 35.0, 80.0, 150.0, 200.0};
  const GriddedField f =
      field_of(make_grid(axis(-100.0, 400.0, 11), y, {-3.0, -1.0, -0.2}, {0.0, 60.0, 200.0}, multilinear));
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> ux(-100.0, 400.0), uy(0.0, 200.0), uz(-3.0, -0.2), ut(0.0, 200.0);
  double worst = 0.0;
  for (int k = 0; k < 2000; ++k) {
    const Vec3 p{ux(rng), uy(rng), uz(rng)};
    const double t = ut(rng);
    worst = std::max(worst, (f.at(p, t) - multilinear(p, t)).norm());
  }
  EXPECT_LT(worst, 1e-13);  // rounding only (velocities are O(1) m/s)
  // The nodes and the corners of the box themselves.
  EXPECT_LT((f.at({-100.0, 0.0, -3.0}, 0.0) - multilinear({-100.0, 0.0, -3.0}, 0.0)).norm(), 1e-15);
  EXPECT_LT((f.at({400.0, 200.0, -0.2}, 200.0) - multilinear({400.0, 200.0, -0.2}, 200.0)).norm(), 1e-14);
}

TEST(GriddedField, SmoothFieldConvergesAtSecondOrder) {
  const double k = 2.0 * std::numbers::pi / 1000.0;
  const auto smooth = [k](const Vec3& p, double) {
    return Vec2{std::sin(k * p.x()) * std::cos(k * p.y()), -std::cos(k * p.x()) * std::sin(k * p.y())};
  };
  std::vector<double> errors;
  for (const std::size_t n : {11u, 21u, 41u, 81u}) {
    const GriddedField f = field_of(make_grid(axis(0.0, 1000.0, n), axis(0.0, 1000.0, n), {-1.0}, {0.0}, smooth));
    std::mt19937_64 rng(3);
    std::uniform_real_distribution<double> u(0.0, 1000.0);
    double worst = 0.0;
    for (int i = 0; i < 4000; ++i) {
      const Vec3 p{u(rng), u(rng), -0.5};
      worst = std::max(worst, (f.at(p, 0.0) - smooth(p, 0.0)).norm());
    }
    errors.push_back(worst);
  }
  for (std::size_t i = 1; i < errors.size(); ++i) {
    const double order = std::log2(errors[i - 1] / errors[i]);
    EXPECT_NEAR(order, 2.0, 0.15) << "h/" << (1 << i) << ": error " << errors[i];
  }
  // The bilinear error bound per component, h^2/8 (|u_xx| + |u_yy|) = (k h)^2 / 4 (1.5e-3 at 80 cells per
  // wavelength), times sqrt(2) for the vector; the measured error sits at the per-component bound.
  const double kh = k * 1000.0 / 80.0;
  EXPECT_LT(errors.back(), std::sqrt(2.0) * kh * kh / 4.0);
  EXPECT_GT(errors.back(), 0.5 * kh * kh / 4.0);  // and it is not a lucky sample set
}

TEST(GriddedField, OneLevelIsTheSameAtEveryDepthAndDepthsBeyondTheLevelsClamp) {
  const GriddedField one = field_of(make_grid(axis(0, 10, 3), axis(0, 10, 3), {-1.0}, {0.0}, multilinear));
  EXPECT_EQ(one.at({5, 5, -0.1}, 0), one.at({5, 5, -7.0}, 0));
  const GriddedField two = field_of(make_grid(axis(0, 10, 3), axis(0, 10, 3), {-2.0, -1.0}, {0.0}, multilinear));
  EXPECT_EQ(two.at({5, 5, -9.0}, 0), two.at({5, 5, -2.0}, 0));
  EXPECT_EQ(two.at({5, 5, 0.0}, 0), two.at({5, 5, -1.0}, 0));
}

TEST(GriddedField, OutsideTheSnapshotsTimeClampsWrapsOrNamesTheFileAndOneSnapshotIsSteady) {
  const auto ramp = [](const Vec3&, double t) { return Vec2{t, 0.0}; };
  GridData g = make_grid(axis(0, 10, 2), axis(0, 10, 2), {-1.0}, {100.0, 200.0, 400.0}, ramp);
  const Vec3 p{5, 5, -1};
  EXPECT_DOUBLE_EQ(field_of(g).at(p, 150.0).x(), 150.0);
  EXPECT_DOUBLE_EQ(field_of(g).at(p, 0.0).x(), 100.0);  // clamp (the default)
  EXPECT_DOUBLE_EQ(field_of(g).at(p, 900.0).x(), 400.0);
  GriddedFieldOptions cyclic;
  cyclic.time_outside = TimeBoundary::cyclic;  // period 300 s
  EXPECT_NEAR(field_of(g, cyclic).at(p, 450.0).x(), 150.0, 1e-12);
  EXPECT_NEAR(field_of(g, cyclic).at(p, 50.0).x(), 350.0, 1e-12);
  EXPECT_NEAR(field_of(g, cyclic).at(p, 100.0 + 7 * 300.0 + 200.0).x(), 300.0, 1e-9);
  GriddedFieldOptions error;
  error.time_outside = TimeBoundary::error;
  EXPECT_DOUBLE_EQ(field_of(g, error).at(p, 400.0).x(), 400.0);
  try {
    (void)field_of(g, error).at(p, 400.5);
    FAIL() << "no error past the last snapshot";
  } catch (const FieldError& e) {
    EXPECT_NE(std::string(e.what()).find("test.h5: time 400.5 s is outside the field's snapshots [100, 400] s"),
              std::string::npos)
        << e.what();
  }
  // One snapshot: steady, whatever the boundary.
  GridData steady = make_grid(axis(0, 10, 2), axis(0, 10, 2), {-1.0}, {0.0}, ramp);
  EXPECT_EQ(field_of(steady, error).at(p, 1e6).x(), 0.0);
}

GridData with_land() {
  // 5 x 5 nodes, 10 m apart, u = 1 m/s; the column x = 40 m is land (a wall on the right).
  GridData g = make_grid(axis(0, 40, 5), axis(0, 40, 5), {-1.0}, {0.0}, [](const Vec3&, double) {
    return Vec2{1.0, 0.5};
  });
  for (std::size_t iy = 0; iy < 5; ++iy) {
    g.wet[g.index(0, 0, iy, 4)] = 0;
    g.u[g.index(0, 0, iy, 4)] = 99.0;  // whatever a dry node holds, it counts as zero
    g.v[g.index(0, 0, iy, 4)] = 99.0;
  }
  return g;
}

TEST(GriddedField, LandNodesCountAsZeroVelocityAndOnlyAllDryIsNoWater) {
  const GriddedField f = field_of(with_land());
  EXPECT_NEAR(f.at({20, 20, -1}, 0).x(), 1.0, 1e-15);
  EXPECT_NEAR(f.at({35, 20, -1}, 0).x(), 0.5, 1e-15);  // halfway to the wall: the no-slip value is 0 there
  EXPECT_NEAR(f.at({39.999, 20, -1}, 0).x(), 1e-4, 1e-9);
  try {
    (void)f.at({40, 20, -1}, 0);  // on the dry column
    FAIL() << "no error on land";
  } catch (const FieldError& e) {
    EXPECT_NE(std::string(e.what()).find("test.h5: no water at (40, 20, -1) m: on land"), std::string::npos)
        << e.what();
  }
  try {
    (void)f.at({-0.5, 20, -1}, 0);
    FAIL() << "no error outside the grid";
  } catch (const FieldError& e) {
    EXPECT_NE(std::string(e.what()).find("outside the field's grid x [0, 40], y [0, 40] m"), std::string::npos)
        << e.what();
    EXPECT_NE(std::string(e.what()).find("no_water: velocity"), std::string::npos) << e.what();
  }
  GriddedFieldOptions o;
  o.no_water = OutsideWater::velocity;
  o.no_water_velocity = {0.25, -0.5};
  const GriddedField fallback = field_of(with_land(), o);
  EXPECT_EQ(fallback.at({40, 20, -1}, 0), Vec2(0.25, -0.5));
  EXPECT_EQ(fallback.at({1e9, 20, -1}, 0), Vec2(0.25, -0.5));
  EXPECT_EQ(fallback.at({std::nan(""), 20, -1}, 0), Vec2(0.25, -0.5));  // a NaN point is nowhere: no NaN out
}

// A steady one-level field on a uniform grid (a depth-averaged OpenFOAM case) has its own fast loop; cells that touch
// land and points off the grid take the general one. Both against the bilinear formula written out, land corners
// counting zero, at random points over a grid with scattered land, and at the placed grid (offset).
TEST(GriddedField, TheSteadyOneLevelLoopIsTheBilinearFormula) {
  GridData g = make_grid(axis(0, 90, 10), axis(-20, 70, 10), {-1.0}, {0.0}, [](const Vec3& p, double) {
    return Vec2{std::sin(0.05 * p.x()) + 0.01 * p.y(), std::cos(0.03 * p.y()) - 0.02 * p.x()};
  });
  std::mt19937_64 rng(11);
  for (int k = 0; k < 12; ++k) g.wet[std::uniform_int_distribution<std::size_t>(0, 99)(rng)] = 0;
  GriddedFieldOptions o;
  o.no_water = OutsideWater::velocity;
  o.no_water_velocity = {7.0, 7.0};
  o.offset = {1000.0, -500.0};
  const GriddedField f = field_of(g, o);
  std::uniform_real_distribution<double> ux(-5.0, 95.0), uy(-25.0, 75.0);
  int fallback = 0;
  for (int k = 0; k < 5000; ++k) {
    const double x = ux(rng), y = uy(rng);
    Vec2 want{7.0, 7.0};
    if (x >= 0.0 && x <= 90.0 && y >= -20.0 && y <= 70.0) {
      const std::size_t ix = std::min<std::size_t>(static_cast<std::size_t>(x / 10.0), 8);
      const std::size_t iy = std::min<std::size_t>(static_cast<std::size_t>((y + 20.0) / 10.0), 8);
      const double wx = x / 10.0 - static_cast<double>(ix), wy = (y + 20.0) / 10.0 - static_cast<double>(iy);
      Vec2 sum{0.0, 0.0};
      double wet = 0.0;
      for (int c = 0; c < 4; ++c) {
        const std::size_t n = g.index(0, 0, iy + (c >> 1), ix + (c & 1));
        const double w = ((c & 1) ? wx : 1.0 - wx) * ((c >> 1) ? wy : 1.0 - wy);
        if (!g.wet[n] || w == 0.0) continue;
        wet += w;
        sum += w * Vec2(g.u[n], g.v[n]);
      }
      if (wet > 1e-9) want = sum;
    }
    fallback += want == Vec2(7.0, 7.0);
    EXPECT_LT((f.at({x + 1000.0, y - 500.0, -1.0}, 0.0) - want).norm(), 1e-13) << x << ", " << y;
  }
  EXPECT_GT(fallback, 100);  // some points off the grid or on land took the fallback
}

// Land as convex pieces: the rectangles tile the dry nodes' squares (each node's square half a spacing either side)
// exactly: every dry node's square centre lies in exactly one rectangle, no wet node's does, and the areas add up.
// The mask is the surface level's (nearest z = 0); a deeper level's land does not count.
TEST(GriddedField, LandRectanglesTileTheDryNodesSquares) {
  GridData g = make_grid(axis(0, 110, 12), axis(-50, 40, 10), {-3.0, -0.5}, {0.0}, [](const Vec3&, double) {
    return Vec2{1.0, 0.0};
  });
  std::mt19937_64 rng(3);
  std::size_t dry = 0;
  for (std::size_t iy = 0; iy < 10; ++iy)
    for (std::size_t ix = 0; ix < 12; ++ix) {
      // A coast along a diagonal, a rectangular island and scattered rocks; the deeper level all dry.
      const bool land = ix + iy < 6 || (ix >= 7 && ix <= 9 && iy >= 4 && iy <= 6) || rng() % 9 == 0;
      g.wet[g.index(0, 1, iy, ix)] = land ? 0 : 1;
      g.wet[g.index(0, 0, iy, ix)] = 0;
      dry += land;
    }
  const std::vector<LandRectangle> rects = land_rectangles(g);
  double area = 0.0;
  for (const LandRectangle& r : rects) area += (r.hi - r.lo).prod();
  EXPECT_NEAR(area, static_cast<double>(dry) * 100.0, 1e-9);
  for (std::size_t iy = 0; iy < 10; ++iy)
    for (std::size_t ix = 0; ix < 12; ++ix) {
      const Vec2 c{g.x[ix], g.y[iy]};
      int in = 0;
      for (const LandRectangle& r : rects) in += (c.array() > r.lo.array()).all() && (c.array() < r.hi.array()).all();
      EXPECT_EQ(in, g.wet[g.index(0, 1, iy, ix)] ? 0 : 1) << ix << ", " << iy;
    }
  // The edges: half a spacing beyond the grid's first and last nodes.
  EXPECT_NEAR(rects.front().lo.x(), -5.0, 1e-12);
  EXPECT_NEAR(rects.front().lo.y(), -55.0, 1e-12);
  EXPECT_LT(rects.size(), dry);  // merged
}

TEST(GriddedField, GridErrorsNameTheProblem) {
  const auto ok = [] { return make_grid(axis(0, 10, 3), axis(0, 10, 4), {-2.0, -1.0}, {0.0, 1.0}, multilinear); };
  EXPECT_EQ(grid_data_error(ok()), "");
  GridData g = ok();
  g.y[2] = g.y[1];
  EXPECT_EQ(grid_data_error(g), "axis y is not strictly increasing at index 2 (3.33333, 3.33333)");
  g = ok();
  g.x = {0.0};
  EXPECT_EQ(grid_data_error(g), "axis x has 1 values, needs at least 2");
  g = ok();
  g.t.clear();
  EXPECT_EQ(grid_data_error(g), "axis t has 0 values, needs at least 1");
  g = ok();
  g.z[0] = std::nan("");
  EXPECT_EQ(grid_data_error(g), "axis z is not finite at index 0");
  g = ok();
  g.u.pop_back();
  EXPECT_EQ(grid_data_error(g), "u has 47 values, expected 48 (t x z x y x x = 2 x 2 x 4 x 3)");
  g = ok();
  g.v[g.index(1, 0, 3, 2)] = INFINITY;
  EXPECT_EQ(grid_data_error(g), "v is not finite at node (t 1, z 0, y 3, x 2)");
  g = ok();
  g.wet[5] = 2;
  EXPECT_EQ(grid_data_error(g), "wet must be 0 or 1, found 2 at index 5");
  g = ok();
  g.wet.assign(g.wet.size(), 0);
  EXPECT_EQ(grid_data_error(g), "no node is wet");
  EXPECT_THROW(GriddedField(std::make_shared<const GridData>(g), {}), std::invalid_argument);
}

TEST(GriddedField, MadeFromASceneSpec) {
  FieldSpec s;
  s.kind = FieldKind::file;
  s.path = "/data/strait.h5";
  EXPECT_EQ(field_spec_error(s), "the field file '/data/strait.h5' is not loaded");
  s.grid = std::make_shared<const GridData>(with_land());
  EXPECT_EQ(field_spec_error(s), "");
  s.no_water = OutsideWater::velocity;
  s.no_water_velocity = {0.1, 0.0};
  const auto f = make_field(s);
  EXPECT_EQ(f->at({100, 0, -1}, 0), Vec2(0.1, 0.0));
  EXPECT_FALSE(f->uniform_in_space());
}

}  // namespace
}  // namespace polyfloe::forcing
