// Ice velocity on a regular grid of cells, averaged over time (for paper Fig. 11-style maps).
//
// At each sample the velocity of the ice at every cell centre is taken from the floe covering that centre (its
// rigid-body velocity there, u + omega k x r; a centre covered by two overlapping floes takes the first). Between
// two take() calls the samples are averaged per cell over the samples in which the cell was covered:
//   velocity(cell) = mean over covered samples [m/s], NaN where no sample found ice;
//   ice_fraction(cell) = covered samples / samples [-] (the time-averaged ice cover of the cell).
// Cells are indexed (j, i) row-major: cell (j, i) spans x0 + [i, i+1] cell, y0 + [j, j+1] cell.
#pragma once

#include <cstdint>
#include <filesystem>
#include <memory>
#include <optional>
#include <vector>

#include "dynamics/world.h"
#include "io/hdf5_writer.h"
#include "io/vtk_writer.h"
#include "scene/scene.h"

namespace polyfloe::run {

using GridGeometry = io::ImageGrid;

// The velocity grid a scene asks for (its region, or every body of `world` at t = 0), checked against the size
// limit (throws SceneError past it).
GridGeometry velocity_grid_geometry(const scene::VelocityGridSettings& g, const dynamics::World& world);

class VelocityGrid {
 public:
  explicit VelocityGrid(const GridGeometry& grid);
  // The smallest grid of `cell`-sized cells that covers every body of `world` (walls included), with the lower-left
  // corner on a multiple of `cell`.
  static GridGeometry covering(const dynamics::World& world, double cell);

  // Adds one sample of the dynamic bodies' velocity field.
  void sample(const dynamics::World& world);
  int samples() const { return samples_; }

  struct Frame {
    std::vector<float> velocity;      // [ny * nx * 2] (u, v) per cell [m/s]; NaN where uncovered
    std::vector<float> ice_fraction;  // [ny * nx] [-]
    int samples = 0;                  // samples averaged
  };
  // The average since the last take() (or the start); then starts a new average.
  Frame take();
  const GridGeometry& geometry() const { return grid_; }

 private:
  GridGeometry grid_;
  std::vector<double> sum_u_, sum_v_;
  std::vector<std::int32_t> hits_;
  std::vector<std::int32_t> stamp_;  // the sample that last wrote each cell (first floe wins within a sample)
  int samples_ = 0;
  std::int32_t sample_id_ = 0;
};

// Samples a VelocityGrid every `sample_interval` and writes the average of each output interval, at each output
// frame, to results.h5 (/diagnostics/velocity_grid) and to a VTK image series (velocity.pvd):
//   /diagnostics/velocity_grid            attributes x0, y0, cell [m], nx, ny, sample_interval [s]
//     x [nx], y [ny]                      cell centres [m]
//     velocity [T, ny, nx, 2] float32     mean ice velocity (u, v) [m/s]; NaN where no ice was seen
//     ice_fraction [T, ny, nx] float32    fraction of the samples that found ice [-]
//     samples [T] int32                   samples averaged into the frame
class VelocityGridRecorder {
 public:
  // `vtk_dir` empty: no VTK series; `h5` null: no HDF5 series.
  VelocityGridRecorder(const GridGeometry& grid, double sample_interval, const std::filesystem::path& vtk_dir,
                       io::Hdf5Writer* h5, io::OutputManifest* manifest = nullptr);
  // Call after every step: samples when the time has reached the next sample time.
  void after_step(const dynamics::World& world);
  // Whether after_step() at time t [s] takes a sample (reads the world).
  bool due(double t) const { return t >= next_sample_ * (1.0 - 1e-12); }
  // Call at every output frame, before the HDF5 writer's write_frame (which flushes): writes the average since the
  // last frame (sampling now if nothing was sampled since).
  void write_frame(const dynamics::World& world);
  const GridGeometry& geometry() const { return grid_.geometry(); }
  // For checkpoints, taken right after a frame (nothing accumulated): the next sample time [s]; and resuming a run
  // at such a checkpoint with frames 0..frame_times.size()-1 on disk (the VTK series is cut back to them).
  double next_sample() const { return next_sample_; }
  void resume(double next_sample, std::span<const double> frame_times);

 private:
  VelocityGrid grid_;
  double interval_;
  double next_sample_;
  std::unique_ptr<io::VtkImageSeriesWriter> vtk_;
  std::optional<io::hdf5::Dataset> h5_velocity_, h5_fraction_, h5_samples_;
};

}  // namespace polyfloe::run
