// HDF5 time series of a spatial run (dynamics/spatial_world.h), the same layout as a planar run's where it can be:
//
//   /time [T]                                  [s]
//   /bodies/id [N] uint64, mass [N] [kg], inertia [N,3,3] [kg m^2] (body frame), motion [N] int8
//          (0 dynamic, 1 fixed, 2 kinematic), vertex_offsets [N+1] int64, vertices [V,3] [m] (body frame)
//   /state/position [T,N,3] [m], orientation [T,N,4] (w, x, y, z), velocity [T,N,3] [m/s],
//          angular_velocity [T,N,3] [rad/s] (world frame)
//   /diagnostics/kinetic_energy [T] [J], contact_energy [T] [J], contact_count [T], linear_momentum [T,3]
//          [kg m/s], angular_momentum [T,3] [kg m^2/s] (about the origin), narrow_phase_failures [T] (queries the
//          chosen method failed and sat answered, cumulative)
//
// Root attributes as a planar run's (scene_path, scene_text, code_version, overrides, dt, created_by) plus
// mode = "spatial". SWMR from the first frame (or start_swmr()), flushed per frame.
#pragma once

#include <filesystem>
#include <memory>

#include "io/hdf5_writer.h"

namespace polyfloe::dynamics {
class SpatialWorld;
}

namespace polyfloe::io {

class SpatialHdf5Writer {
 public:
  SpatialHdf5Writer(const std::filesystem::path& file, const dynamics::SpatialWorld& world, const RunInfo& info);
  ~SpatialHdf5Writer();
  // Appends one frame at world.time() and flushes. Throws IoError if the bodies differ from the first frame's.
  void write_frame(const dynamics::SpatialWorld& world);
  void flush();
  // As Hdf5Writer: single-writer/multiple-reader mode from here on (done by the first write_frame() if not before),
  // and a restart's frames 0..frames-1 copied from the interrupted run's file.
  void start_swmr();
  void adopt_frames(const std::filesystem::path& previous, int frames);
  int frames() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace polyfloe::io
