#include "run/velocity_grid.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace polyfloe::run {

using geometry::Vec2;

VelocityGrid::VelocityGrid(const GridGeometry& grid) : grid_(grid) {
  if (!(grid.cell > 0.0) || !std::isfinite(grid.cell) || grid.nx <= 0 || grid.ny <= 0 || !std::isfinite(grid.x0) ||
      !std::isfinite(grid.y0)) {
    throw std::invalid_argument("velocity grid: cell size must be positive and finite, with at least one cell");
  }
  sum_u_.assign(grid.cells(), 0.0);
  sum_v_.assign(grid.cells(), 0.0);
  hits_.assign(grid.cells(), 0);
  stamp_.assign(grid.cells(), -1);
}

GridGeometry VelocityGrid::covering(const dynamics::World& world, double cell) {
  double lo_x = std::numeric_limits<double>::infinity(), lo_y = lo_x, hi_x = -lo_x, hi_y = -lo_x;
  for (int i = 0; i < static_cast<int>(world.size()); ++i) {
    for (const Vec2& v : world.world_vertices(i)) {
      lo_x = std::min(lo_x, v.x());
      lo_y = std::min(lo_y, v.y());
      hi_x = std::max(hi_x, v.x());
      hi_y = std::max(hi_y, v.y());
    }
  }
  GridGeometry g;
  g.cell = cell;
  if (!(hi_x >= lo_x)) {  // no bodies
    g.nx = g.ny = 1;
    return g;
  }
  g.x0 = std::floor(lo_x / cell) * cell;
  g.y0 = std::floor(lo_y / cell) * cell;
  // Counted in double and checked before any conversion to int (a tiny cell would overflow it).
  const double nx = std::max(1.0, std::ceil((hi_x - g.x0) / cell)), ny = std::max(1.0, std::ceil((hi_y - g.y0) / cell));
  if (!(nx * ny <= scene::VelocityGridSettings::kMaxCells))
    throw scene::SceneError("output.velocity_grid.cell: the bodies span " + std::to_string(nx) + " x " +
                            std::to_string(ny) + " cells of " + std::to_string(cell) + " m (at most " +
                            std::to_string(static_cast<long long>(scene::VelocityGridSettings::kMaxCells)) +
                            " cells): raise output.velocity_grid.cell or give output.velocity_grid.region");
  g.nx = static_cast<int>(nx);
  g.ny = static_cast<int>(ny);
  return g;
}

void VelocityGrid::sample(const dynamics::World& world) {
  ++samples_;
  ++sample_id_;
  const auto pos = world.positions();
  const auto vel = world.velocities();
  const auto om = world.angular_velocities();
  const double inv = 1.0 / grid_.cell;
  for (const int b : world.id_order()) {  // (each cell's sum in id order)
    if (world.motion(b) != dynamics::Motion::dynamic) continue;
    const auto ring = world.world_vertices(b);
    const std::size_t n = ring.size();
    double lo_y = ring[0].y(), hi_y = lo_y;
    for (const Vec2& v : ring) {
      lo_y = std::min(lo_y, v.y());
      hi_y = std::max(hi_y, v.y());
    }
    // Rows whose centre y0 + (j + 1/2) cell lies in [lo_y, hi_y].
    const int j0 = std::max(0, static_cast<int>(std::ceil((lo_y - grid_.y0) * inv - 0.5)));
    const int j1 = std::min(grid_.ny - 1, static_cast<int>(std::floor((hi_y - grid_.y0) * inv - 0.5)));
    const Vec2 c = pos[static_cast<std::size_t>(b)];
    const Vec2 u = vel[static_cast<std::size_t>(b)];
    const double w = om[static_cast<std::size_t>(b)];
    for (int j = j0; j <= j1; ++j) {
      const double y = grid_.y0 + (j + 0.5) * grid_.cell;
      // The chord of the convex polygon at height y: the span of its edges' crossings.
      double xl = std::numeric_limits<double>::infinity(), xr = -xl;
      for (std::size_t k = 0; k < n; ++k) {
        const Vec2& p = ring[k];
        const Vec2& q = ring[(k + 1) % n];
        if ((p.y() <= y && q.y() >= y) || (q.y() <= y && p.y() >= y)) {
          const double dy = q.y() - p.y();
          const double x = dy != 0.0 ? p.x() + (y - p.y()) / dy * (q.x() - p.x()) : std::min(p.x(), q.x());
          const double x2 = dy != 0.0 ? x : std::max(p.x(), q.x());
          xl = std::min(xl, x);
          xr = std::max(xr, x2);
        }
      }
      if (!(xr >= xl)) continue;
      const int i0 = std::max(0, static_cast<int>(std::ceil((xl - grid_.x0) * inv - 0.5)));
      const int i1 = std::min(grid_.nx - 1, static_cast<int>(std::floor((xr - grid_.x0) * inv - 0.5)));
      const double ry = y - c.y();
      const std::size_t row = static_cast<std::size_t>(j) * static_cast<std::size_t>(grid_.nx);
      for (int i = i0; i <= i1; ++i) {
        const std::size_t k = row + static_cast<std::size_t>(i);
        if (stamp_[k] == sample_id_) continue;
        stamp_[k] = sample_id_;
        const double rx = grid_.x0 + (i + 0.5) * grid_.cell - c.x();
        sum_u_[k] += u.x() - w * ry;
        sum_v_[k] += u.y() + w * rx;
        ++hits_[k];
      }
    }
  }
}

VelocityGrid::Frame VelocityGrid::take() {
  Frame f;
  const std::size_t n = grid_.cells();
  f.samples = samples_;
  f.velocity.resize(2 * n);
  f.ice_fraction.resize(n);
  const float nan = std::numeric_limits<float>::quiet_NaN();
  for (std::size_t k = 0; k < n; ++k) {
    const int h = hits_[k];
    f.velocity[2 * k] = h ? static_cast<float>(sum_u_[k] / h) : nan;
    f.velocity[2 * k + 1] = h ? static_cast<float>(sum_v_[k] / h) : nan;
    f.ice_fraction[k] = samples_ ? static_cast<float>(static_cast<double>(h) / samples_) : 0.0f;
  }
  std::fill(sum_u_.begin(), sum_u_.end(), 0.0);
  std::fill(sum_v_.begin(), sum_v_.end(), 0.0);
  std::fill(hits_.begin(), hits_.end(), 0);
  samples_ = 0;
  return f;
}

VelocityGridRecorder::VelocityGridRecorder(const GridGeometry& grid, double sample_interval,
                                           const std::filesystem::path& vtk_dir, io::Hdf5Writer* h5,
                                           io::OutputManifest* manifest)
    : grid_(grid), interval_(sample_interval), next_sample_(sample_interval) {
  if (!(sample_interval > 0.0) || !std::isfinite(sample_interval))
    throw std::invalid_argument("velocity grid: the sample interval must be positive");
  if (!vtk_dir.empty()) vtk_ = std::make_unique<io::VtkImageSeriesWriter>(vtk_dir, "velocity", grid, manifest);
  if (h5) {
    using io::hdf5::DType;
    io::hdf5::Group g = h5->diagnostics().create_group("velocity_grid");
    g.set_attribute("x0", grid.x0);
    g.set_attribute("y0", grid.y0);
    g.set_attribute("cell", grid.cell);
    g.set_attribute("nx", static_cast<std::int64_t>(grid.nx));
    g.set_attribute("ny", static_cast<std::int64_t>(grid.ny));
    g.set_attribute("sample_interval", sample_interval);
    g.set_attribute("description",
                    "ice velocity at the cell centres, averaged over the samples of each output interval in which "
                    "the centre was covered by a floe");
    auto centres = [&](double origin, int n) {
      std::vector<double> c(static_cast<std::size_t>(n));
      for (int i = 0; i < n; ++i) c[static_cast<std::size_t>(i)] = origin + (i + 0.5) * grid.cell;
      return c;
    };
    g.write_dataset<double>("x", centres(grid.x0, grid.nx)).set_attribute("units", "m");
    g.write_dataset<double>("y", centres(grid.y0, grid.ny)).set_attribute("units", "m");
    const auto nx = static_cast<std::uint64_t>(grid.nx), ny = static_cast<std::uint64_t>(grid.ny);
    h5_velocity_ = g.create_series("velocity", DType::f32, {ny, nx, 2}, 1, 1);
    h5_velocity_->set_attribute("units", "m/s");
    h5_velocity_->set_attribute("description", "[frame, y, x, (u, v)]; NaN where no sample found ice");
    h5_fraction_ = g.create_series("ice_fraction", DType::f32, {ny, nx}, 1, 1);
    h5_fraction_->set_attribute("units", "1");
    h5_fraction_->set_attribute("description", "[frame, y, x] fraction of the samples that found ice");
    h5_samples_ = g.create_series("samples", DType::i32, {}, 256);
    h5_samples_->set_attribute("units", "1");
  }
}

void VelocityGridRecorder::after_step(const dynamics::World& world) {
  const double t = world.time();
  if (!due(t)) return;
  grid_.sample(world);
  next_sample_ = interval_ * (std::floor(t / interval_ * (1.0 + 1e-12)) + 1.0);
}

void VelocityGridRecorder::resume(double next_sample, std::span<const double> frame_times) {
  if (!std::isfinite(next_sample)) throw std::invalid_argument("velocity grid: the next sample time must be finite");
  next_sample_ = next_sample;
  if (vtk_) vtk_->resume(frame_times);
}

void VelocityGridRecorder::write_frame(const dynamics::World& world) {
  if (grid_.samples() == 0) grid_.sample(world);
  const VelocityGrid::Frame f = grid_.take();
  if (vtk_) {
    std::vector<float> speed(f.ice_fraction.size());
    for (std::size_t k = 0; k < speed.size(); ++k) speed[k] = std::hypot(f.velocity[2 * k], f.velocity[2 * k + 1]);
    const io::CellField fields[] = {
        {"velocity", 2, f.velocity}, {"speed", 1, speed}, {"ice_fraction", 1, f.ice_fraction}};
    vtk_->write_frame(world.time(), world.step_count(), fields);
  }
  if (h5_velocity_) {
    h5_velocity_->append_rows<float>(f.velocity, 1);
    h5_fraction_->append_rows<float>(f.ice_fraction, 1);
    const std::int32_t n = f.samples;
    h5_samples_->append_rows<std::int32_t>({&n, 1}, 1);
  }
}

GridGeometry velocity_grid_geometry(const scene::VelocityGridSettings& g, const dynamics::World& world) {
  GridGeometry geo;
  if (g.region) {
    const auto& r = *g.region;
    geo.x0 = r[0];
    geo.y0 = r[1];
    geo.cell = g.cell;
    geo.nx = static_cast<int>(std::max(1.0, std::ceil((r[2] - r[0]) / g.cell)));
    geo.ny = static_cast<int>(std::max(1.0, std::ceil((r[3] - r[1]) / g.cell)));
    return geo;
  }
  // The automatic region: every body at t = 0 (covering() refuses a grid past the size limit).
  return VelocityGrid::covering(world, g.cell);
}

}  // namespace polyfloe::run
