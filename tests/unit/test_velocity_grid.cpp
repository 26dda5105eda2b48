// Ice velocity on a grid (run/velocity_grid.h): which cells a floe covers (against a brute-force point-in-polygon
// test), the rigid-body velocity at each cell centre (u + omega k x r, exact), the average over samples and the
// ice fraction, the covering grid, and the recorder's HDF5 / VTK image output.
#include <gtest/gtest.h>

#include <vtkCellData.h>
#include <vtkDataArray.h>
#include <vtkDataSetAttributes.h>
#include <vtkImageData.h>
#include <vtkNew.h>
#include <vtkXMLImageDataReader.h>

#include <cmath>
#include <filesystem>
#include <random>

#include "scratch_dir.h"
#include "dynamics/world.h"
#include "formats/hdf5_file.h"
#include "io/hdf5_writer.h"
#include "run/velocity_grid.h"
#include "test_support.h"

using namespace polyfloe;
using geometry::Vec2;

namespace {

dynamics::World empty_world() {
  dynamics::WorldSettings ws;
  ws.drift = forcing::DriftSettings::none();
  return dynamics::World(ws);
}

Vec2 centre(const run::GridGeometry& g, int i, int j) { return {g.x0 + (i + 0.5) * g.cell, g.y0 + (j + 0.5) * g.cell}; }

TEST(VelocityGrid, RigidBodyVelocityOnCoveredCellsExactly) {
  dynamics::World w = empty_world();
  const auto shape = tsupport::shape_of({{-23.0, -11.0}, {19.0, -17.0}, {27.0, 9.0}, {-3.0, 21.0}, {-26.0, 6.0}});
  const Vec2 c{51.3, 48.7};
  const Vec2 u{1.5, -0.25};
  const double omega = 0.02;
  w.add_body({.id = 1, .shape = shape, .position = c, .yaw = 0.4, .velocity = u, .angular_velocity = omega});
  w.compute_forces(0.0);
  const run::GridGeometry g{.x0 = 0.0, .y0 = 0.0, .cell = 2.5, .nx = 40, .ny = 40};
  run::VelocityGrid grid(g);
  grid.sample(w);
  const run::VelocityGrid::Frame f = grid.take();
  ASSERT_EQ(f.samples, 1);
  const auto ring = w.world_vertices(0);
  const std::vector<Vec2> poly(ring.begin(), ring.end());
  int covered = 0;
  for (int j = 0; j < g.ny; ++j) {
    for (int i = 0; i < g.nx; ++i) {
      const std::size_t k = static_cast<std::size_t>(j * g.nx + i);
      const Vec2 p = centre(g, i, j);
      const bool inside = tsupport::inside_convex(poly, p, 0.0);
      ASSERT_EQ(f.ice_fraction[k] == 1.0f, inside) << "cell " << i << "," << j;
      if (!inside) {
        EXPECT_TRUE(std::isnan(f.velocity[2 * k]) && std::isnan(f.velocity[2 * k + 1]));
        EXPECT_EQ(f.ice_fraction[k], 0.0f);
        continue;
      }
      ++covered;
      const Vec2 r = p - c;
      EXPECT_FLOAT_EQ(f.velocity[2 * k], static_cast<float>(u.x() - omega * r.y()));
      EXPECT_FLOAT_EQ(f.velocity[2 * k + 1], static_cast<float>(u.y() + omega * r.x()));
    }
  }
  // The covered cells tile the floe: their count times the cell area approaches its area.
  EXPECT_NEAR(covered * g.cell * g.cell, shape->area(), 0.05 * shape->area());
}

TEST(VelocityGrid, CoverageMatchesPointInPolygonForManyFloes) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> U(0.0, 1.0);
  dynamics::World w = empty_world();
  std::vector<std::vector<Vec2>> placed;
  for (int n = 0; n < 60; ++n) {  // scattered floes, 3-16 corners, allowed to overlap (first one wins)
    const auto v = tsupport::random_convex(rng, 3 + static_cast<int>(13 * U(rng)), 3 + 20 * U(rng), 3 + 20 * U(rng));
    w.add_body({.id = static_cast<dynamics::BodyId>(n + 1),
                .shape = tsupport::shape_of(v),
                .position = {300 * U(rng), 200 * U(rng)},
                .yaw = 6.3 * U(rng),
                .velocity = {U(rng), U(rng)}});
  }
  w.add_body({.id = 99,
              .shape = tsupport::shape_of({{-5, -5}, {5, -5}, {5, 5}, {-5, 5}}),
              .position = {150, 100},
              .motion = dynamics::Motion::fixed});  // walls carry no ice velocity
  w.compute_forces(0.0);
  const run::GridGeometry g = run::VelocityGrid::covering(w, 3.0);
  run::VelocityGrid grid(g);
  grid.sample(w);
  const auto f = grid.take();
  std::vector<std::vector<Vec2>> rings;
  for (int b = 0; b < static_cast<int>(w.size()); ++b) {
    const auto r = w.world_vertices(b);
    rings.emplace_back(r.begin(), r.end());
  }
  int checked = 0;
  for (int j = 0; j < g.ny; ++j) {
    for (int i = 0; i < g.nx; ++i) {
      const Vec2 p = centre(g, i, j);
      int first = -1;
      bool ambiguous = false;
      for (int b = 0; b < static_cast<int>(w.size()) - 1 && first < 0; ++b) {
        if (tsupport::inside_convex(rings[static_cast<std::size_t>(b)], p, -1e-9))
          first = b;  // clearly inside
        else if (tsupport::inside_convex(rings[static_cast<std::size_t>(b)], p, 1e-9))
          ambiguous = true;
      }
      if (ambiguous) continue;
      const std::size_t k = static_cast<std::size_t>(j * g.nx + i);
      ++checked;
      ASSERT_EQ(f.ice_fraction[k] == 1.0f, first >= 0) << "cell " << i << "," << j;
      if (first < 0) continue;
      // Overlapping floes: some covering floe's velocity (they are all rigid motions; check it is one of them).
      bool matches = false;
      for (int b = 0; b < static_cast<int>(w.size()) - 1; ++b) {
        if (!tsupport::inside_convex(rings[static_cast<std::size_t>(b)], p, 1e-9)) continue;
        const Vec2 v = w.velocities()[static_cast<std::size_t>(b)];
        matches |= f.velocity[2 * k] == static_cast<float>(v.x()) && f.velocity[2 * k + 1] == static_cast<float>(v.y());
      }
      EXPECT_TRUE(matches) << "cell " << i << "," << j;
    }
  }
  EXPECT_GT(checked, g.nx * g.ny * 9 / 10);
  // The covering grid holds every vertex.
  for (const auto& r : rings) {
    for (const Vec2& v : r) {
      EXPECT_GE(v.x(), g.x0);
      EXPECT_LE(v.x(), g.x0 + g.nx * g.cell);
      EXPECT_GE(v.y(), g.y0);
      EXPECT_LE(v.y(), g.y0 + g.ny * g.cell);
    }
  }
}

TEST(VelocityGrid, AveragesOverSamplesAndCountsIceFraction) {
  dynamics::World w = empty_world();
  // A 10 m square moving at 2 m/s along +x over a row of 5 m cells.
  w.add_body({.id = 1,
              .shape = tsupport::shape_of({{-5, -5}, {5, -5}, {5, 5}, {-5, 5}}),
              .position = {10.0, 5.0},
              .velocity = {2.0, 0.0}});
  w.compute_forces(0.0);
  run::VelocityGrid grid({.x0 = 0.0, .y0 = 0.0, .cell = 5.0, .nx = 6, .ny = 2});
  grid.sample(w);  // covers x in [5, 15]: cells 1 and 2
  w.step(2.5);     // moves 5 m: covers [10, 20]: cells 2 and 3
  w.set_velocity(0, {4.0, 1.0}, 0.0);
  grid.sample(w);
  const auto f = grid.take();
  ASSERT_EQ(f.samples, 2);
  const float nan_check = f.velocity[0];
  EXPECT_TRUE(std::isnan(nan_check));
  EXPECT_FLOAT_EQ(f.ice_fraction[1], 0.5f);
  EXPECT_FLOAT_EQ(f.ice_fraction[2], 1.0f);
  EXPECT_FLOAT_EQ(f.ice_fraction[3], 0.5f);
  EXPECT_FLOAT_EQ(f.velocity[2 * 1], 2.0f);      // seen once, at 2 m/s
  EXPECT_FLOAT_EQ(f.velocity[2 * 2], 3.0f);      // mean of 2 and 4
  EXPECT_FLOAT_EQ(f.velocity[2 * 2 + 1], 0.5f);  // mean of 0 and 1
  EXPECT_FLOAT_EQ(f.velocity[2 * 3], 4.0f);
  EXPECT_FLOAT_EQ(f.ice_fraction[6 + 2], 1.0f);  // the upper row too
  // take() starts a new average.
  EXPECT_EQ(grid.samples(), 0);
  const auto empty = grid.take();
  EXPECT_EQ(empty.ice_fraction[2], 0.0f);
}

TEST(VelocityGrid, ZeroCellSizeNoColumnsOrANanOriginThrowsInvalidArgument) {
  EXPECT_THROW(run::VelocityGrid({.cell = 0.0, .nx = 1, .ny = 1}), std::invalid_argument);
  EXPECT_THROW(run::VelocityGrid({.cell = 1.0, .nx = 0, .ny = 1}), std::invalid_argument);
  EXPECT_THROW(run::VelocityGrid({.x0 = NAN, .cell = 1.0, .nx = 1, .ny = 1}), std::invalid_argument);
}

TEST(VelocityGridRecorder, WritesHdf5AndImageSeries) {
  namespace fs = std::filesystem;
  const fs::path dir = polyfloe::tsupport::scratch_dir("polyfloe_test_velocity_grid");
  fs::remove_all(dir);
  dynamics::World w = empty_world();
  w.add_body({.id = 1,
              .shape = tsupport::shape_of({{-5, -5}, {5, -5}, {5, 5}, {-5, 5}}),
              .position = {10.0, 5.0},
              .velocity = {1.0, 0.5}});
  w.compute_forces(0.0);
  const run::GridGeometry g{.x0 = 0.0, .y0 = 0.0, .cell = 2.0, .nx = 15, .ny = 6};
  {
    io::Hdf5Writer h5(dir / "results.h5", w, {}, 1025.0);
    run::VelocityGridRecorder rec(g, 0.5, dir, &h5);
    rec.write_frame(w);  // t = 0: one sample
    h5.write_frame(w);
    for (int s = 0; s < 8; ++s) {
      w.step(0.25);
      rec.after_step(w);  // samples at 0.5, 1.0, 1.5, 2.0
    }
    rec.write_frame(w);
    h5.write_frame(w);
  }
  io::hdf5::File f(dir / "results.h5", io::hdf5::File::Mode::read_only);
  const auto grp = f.root().open_group("diagnostics").open_group("velocity_grid");
  EXPECT_EQ(grp.int_attribute("nx"), 15);
  EXPECT_EQ(grp.double_attribute("cell"), 2.0);
  const auto vel = grp.open_dataset("velocity");
  EXPECT_EQ(vel.dims(), (io::hdf5::Dims{2, 6, 15, 2}));
  const auto samples = grp.open_dataset("samples").read<std::int32_t>();
  EXPECT_EQ(samples, (std::vector<std::int32_t>{1, 4}));
  const auto x = grp.open_dataset("x").read<double>();
  EXPECT_EQ(x.front(), 1.0);
  EXPECT_EQ(x.back(), 29.0);
  const auto v = vel.read<float>();
  const std::size_t k = (2 * 15 + 5) * 2;  // cell (j = 2, i = 5), centre (11, 5): covered at every sample
  EXPECT_FLOAT_EQ(v[k], 1.0f);
  EXPECT_FLOAT_EQ(v[k + 1], 0.5f);

  vtkNew<vtkXMLImageDataReader> reader;
  reader->SetFileName((dir / "velocity" / "velocity_000001.vti").c_str());
  reader->Update();
  vtkImageData* img = reader->GetOutput();
  int dims[3];
  img->GetDimensions(dims);
  EXPECT_EQ(dims[0], 16);
  EXPECT_EQ(dims[1], 7);
  vtkDataArray* a = img->GetCellData()->GetArray("velocity");
  ASSERT_NE(a, nullptr);
  EXPECT_EQ(a->GetNumberOfComponents(), 3);
  EXPECT_FLOAT_EQ(static_cast<float>(a->GetComponent(2 * 15 + 5, 0)), 1.0f);
  EXPECT_EQ(a->GetComponent(2 * 15 + 5, 2), 0.0);
  ASSERT_NE(img->GetCellData()->GetArray("ice_fraction"), nullptr);
  ASSERT_NE(img->GetCellData()->GetArray("speed"), nullptr);
  // Ice-free cells (NaN velocity) are hidden with VTK's ghost array, covered ones shown.
  vtkDataArray* ghost = img->GetCellData()->GetArray("vtkGhostType");
  ASSERT_NE(ghost, nullptr);
  EXPECT_EQ(ghost->GetComponent(2 * 15 + 5, 0), 0.0);
  int hidden = 0;
  for (vtkIdType c = 0; c < 15 * 6; ++c) {
    const bool nan = std::isnan(a->GetComponent(c, 0));
    EXPECT_EQ(ghost->GetComponent(c, 0), nan ? double(vtkDataSetAttributes::HIDDENCELL) : 0.0) << c;
    hidden += nan;
  }
  EXPECT_GT(hidden, 0);
  EXPECT_TRUE(fs::exists(dir / "velocity.pvd"));
  fs::remove_all(dir);
}

}  // namespace
