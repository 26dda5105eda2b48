// HDF5 time series of a run: static floe data once, then one row per frame of state and diagnostics.
//
//   /time [T]                                  [s]
//   /floes/id [N] uint64, thickness [N] [m], mass [N] [kg], inertia [N] [kg m^2], motion [N] int8
//          (0 dynamic, 1 fixed, 2 kinematic), polygon_offsets [N+1] int64, polygon_xy [V,2] [m]
//          (body-frame vertices of body i: rows polygon_offsets[i] .. polygon_offsets[i+1]-1, counter-clockwise)
//   /state/position [T,N,3] [m]                centre of mass; z = h/2 - draft
//          orientation [T,N,4]                 unit quaternion (w, x, y, z) = (cos(yaw/2), 0, 0, sin(yaw/2))
//          velocity [T,N,3] [m/s], angular_velocity [T,N,3] [rad/s] (0, 0, omega)
//          vertices_xy [T,V,2] float32 [m]     every polygon where it is (rows as polygon_xy): for viewing
//   /diagnostics/kinetic_energy [T] [J], contact_count [T], max_speed [T] [m/s], mean_speed [T] [m/s]
//          (both over dynamic bodies), max_overlap_depth [T] [m], linear_momentum [T,2] [kg m/s],
//          angular_momentum [T] [kg m^2/s]; with walls or plates: boundary_ids [K], boundary_force [T,K,2] [N]
//          (the force of the ice on each fixed or kinematic body)
//   /bonds (a World with bonds): attributes of the bond material; face_id_a, face_id_b [F], face_length [F] [m],
//          face_normal [F,2], face_midpoint [F,2] [m] (when frozen); series intact_faces [T], intact_points [T],
//          max_tensile_stress [T], max_shear_stress [T] [Pa], face_intact [T,F] uint8, point_intact [T,P] uint8
//
// Every dataset carries a "units" attribute; the root carries scene_path, scene_text, code_version, overrides,
// dt, water_density and created_by = "PolyFloe". From the first frame on the file is in HDF5's single-writer/
// multiple-reader mode and flushed after each frame: the file on disk is consistent at every moment, so a run
// killed at any instant leaves every flushed frame readable (by SWMR readers: h5py.File(path, "r", swmr=True);
// io::hdf5::File opens such files itself). The set of bodies must not change during the run.
#pragma once

#include <filesystem>
#include <memory>
#include <span>
#include <vector>
#include <string>

#include "formats/hdf5_file.h"

namespace polyfloe::dynamics {
class World;
}

namespace polyfloe::io {

class OutputManifest;

struct RunInfo {
  std::string scene_path;  // the scene file as given
  std::string scene_text;  // its full text
  std::string version;     // code version
  std::string overrides;   // the --set arguments joined by newlines
  double dt = 0.0;         // time step [s]
};

// The root attributes every results file carries: created_by = "PolyFloe", code_version, scene_path, scene_text,
// overrides, dt.
void write_run_attributes(hdf5::Group& root, const RunInfo& info);

// A scalar series the driver adds to /diagnostics/<group>/<name>, one value per frame.
struct ExtraSeries {
  std::string group;  // e.g. "channel"
  std::string name;   // e.g. "area_flux"
  std::string units;  // e.g. "m^2/s"
  std::string description;
};

class Hdf5Writer {
 public:
  // Creates (replaces) `file` and writes the static data of `world`'s bodies. Throws IoError naming the file.
  Hdf5Writer(const std::filesystem::path& file, const dynamics::World& world, const RunInfo& info, double water_density,
             const std::vector<ExtraSeries>& extra = {});
  ~Hdf5Writer();
  Hdf5Writer(Hdf5Writer&&) noexcept;
  Hdf5Writer& operator=(Hdf5Writer&&) noexcept;

  // Appends one frame at world.time() and flushes; `extra` holds one value per ExtraSeries, in their order.
  // Throws IoError if the bodies differ from the first frame's or `extra` has the wrong length.
  void write_frame(const dynamics::World& world, std::span<const double> extra = {});
  void flush();
  // Switches the file to single-writer/multiple-reader mode (see above) once every dataset exists; from then on
  // the file is consistent on disk at every moment. Done by the first write_frame() if not called before.
  void start_swmr();
  int frames() const;
  // Continues a run: copies frames 0..frames-1 of every series (extendible dataset) from `previous` (the file of
  // the interrupted run, same layout) into this newly created file, so that the next write_frame() writes frame
  // `frames`. Call after every series exists (the driver's too). Throws IoError naming the file when `previous`
  // cannot be read, lacks a series, has fewer frames, or its series differ in shape.
  void adopt_frames(const std::filesystem::path& previous, int frames);
  // Writes `xmf` (atomically): an XDMF 2 description of the file's frames so far as a temporal collection of the
  // bodies' polygons (state/vertices_xy) with their cell data (velocity, angular velocity, id, thickness, motion;
  // units as Information items), which every XDMF reader of ParaView reads (its Xdmf3 readers drop a hyperslab of
  // a series and crash on a geometry without data, so every array is a whole dataset). The arrays live in files
  // of their own beside `xmf`, xdmf/frames_FIRST-LAST.h5, one per call with the frames written since the last
  // (io/xdmf_frames.h: each written atomically, and results.xmf opens while the run goes on). With `manifest`
  // (the output folder's), they are listed in it; a restarted run keeps the interrupted run's files that hold only
  // frames it adopted (checked against their times) and rewrites or removes the others. Throws IoError naming the
  // file.
  void write_xdmf(const std::filesystem::path& xmf, OutputManifest* manifest = nullptr);
  // The /diagnostics group, for series the driver writes itself: append their row for a frame before
  // write_frame(), which flushes the file.
  hdf5::Group& diagnostics();
  const std::filesystem::path& path() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace polyfloe::io
