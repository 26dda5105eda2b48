// A run's outputs on their schedule: the frames (VTK series, the HDF5 results with the channel monitor's series,
// the ice velocity grid), the checkpoints with the results' snapshot, and results.xmf, all in one output folder
// (run/output_folder.h). BasicSimulation::run() steps the world and tells this object where it is. W is the world
// (dynamics::World or dynamics::SpatialWorld): a spatial run has its own VTK and HDF5 writers, and no channel,
// velocity grid or results.xmf.
#pragma once

#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <type_traits>
#include <vector>

#include "dynamics/spatial_world.h"
#include "dynamics/world.h"
#include "io/hdf5_writer.h"
#include "io/spatial_hdf5_writer.h"
#include "io/vtk_writer.h"
#include "run/channel_monitor.h"
#include "run/checkpoint.h"
#include "run/output_folder.h"
#include "run/simulation.h"
#include "run/velocity_grid.h"
#include "scene/scene.h"

namespace polyfloe::run {

template <class W>
class BasicRunOutputs {
 public:
  // Opens the output folder (fresh, or resumed for a restart) and the writers the scene asks for; a restart's
  // results.h5 is moved aside first (see kInterruptedResults) when `restart_results` is it. Nothing is written
  // into the folder before it is locked and each file listed.
  BasicRunOutputs(const scene::Scene& scene, const W& world, const RunOptions& options, double dt,
                  const std::string& signature, const std::optional<io::ImageGrid>& grid,
                  const std::optional<Checkpoint>& restart, const std::filesystem::path& restart_results);
  BasicRunOutputs(const BasicRunOutputs&) = delete;
  BasicRunOutputs& operator=(const BasicRunOutputs&) = delete;
  // Writes results.xmf when the run stops on an exception (after start()), whatever the checkpoint settings.
  ~BasicRunOutputs();

  // The first frame of a fresh run (forces computed at t = 0), or a restart's outputs taken up where its
  // checkpoint left them (frames adopted, monitors restored into `world`'s run).
  void start(W& world, const std::optional<Checkpoint>& restart);
  // After each step: the velocity grid's sample, and the frame and checkpoint that fall due.
  void after_step(const W& world);
  // Whether after_step() at time t [s] reads the world (a sample, a frame or a checkpoint is due); when not, it may
  // be left out (a world stepped elsewhere need not be brought here).
  bool wants_world(double t) const {
    if constexpr (kPlanar)
      if (velocity_grid_ && velocity_grid_->due(t)) return true;
    return schedule_.frame_due(t);
  }
  // VTK frames in pieces (output.vtk_pieces, planar): the frame after_step() at time t [s] writes, where it is
  // written in pieces and due, else -1; and, before the pieces of the next frame are written, their manifest entries
  // and folders (io::VtkSeriesWriter::begin_pieces).
  int vtk_pieces_due(double t) const {
    if constexpr (kPlanar)
      if (vtk_ && vtk_->pieces() > 0 && schedule_.frame_due(t)) return vtk_->frames();
    return -1;
  }
  void begin_vtk_pieces(const W& world) {
    if constexpr (kPlanar) vtk_->begin_pieces(world.bonds() != nullptr);
  }
  // An unstable run's state in DIR/checkpoints/unstable.h5 (when checkpoints are on): what to tell the user.
  std::string save_unstable(const W& world);
  // results.xmf at the end.
  void finish();

  // The step to take from time t [s].
  double step(double t) const { return schedule_.step(t, dt_); }
  bool at_end(double t) const { return schedule_.at_end(t); }
  int frames() const { return frames_; }
  const std::filesystem::path& path() const { return folder_.path(); }
  const ChannelMonitor* channel() const { return channel_ ? &*channel_ : nullptr; }

 private:
  void write_frame(const W& world);
  void checkpoint(const W& world, const char* kind, const std::filesystem::path& file);
  void snapshot_results();  // results.h5 copied to kResultsSnapshot, atomically
  void write_xdmf();        // results.xmf (planar runs)

  const scene::Scene& scene_;
  const RunOptions& options_;
  double dt_ = 0.0;  // [s]
  std::string signature_;
  OutputFolder folder_;
  static constexpr bool kPlanar = std::is_same_v<W, dynamics::World>;
  using VtkWriter = std::conditional_t<kPlanar, io::VtkSeriesWriter, io::SpatialVtkSeriesWriter>;
  using Hdf5Writer = std::conditional_t<kPlanar, io::Hdf5Writer, io::SpatialHdf5Writer>;
  std::unique_ptr<VtkWriter> vtk_;
  std::unique_ptr<Hdf5Writer> h5_;
  std::optional<ChannelMonitor> channel_;
  std::filesystem::path adopt_from_;  // a restart: the file the interrupted run's frames are copied from
  std::optional<VelocityGridRecorder> velocity_grid_;
  int frames_ = 0;
  std::vector<double> frame_times_;  // [s]
  FrameClock schedule_;
  std::vector<double> extra_values_;  // scratch: the channel monitor's row of a frame
  bool started_ = false;
};

extern template class BasicRunOutputs<dynamics::World>;
extern template class BasicRunOutputs<dynamics::SpatialWorld>;

}  // namespace polyfloe::run
