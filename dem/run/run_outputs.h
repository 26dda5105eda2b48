// The planar driver's outputs on their schedule: the frames (VTK series, the HDF5 results with the channel
// monitor's series, the ice velocity grid), the checkpoints with the results' snapshot, and results.xmf, all in one
// output folder (run/output_folder.h). Simulation::run() steps the World and tells this object where it is.
#pragma once

#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "dynamics/world.h"
#include "io/hdf5_writer.h"
#include "io/vtk_writer.h"
#include "run/channel_monitor.h"
#include "run/checkpoint.h"
#include "run/output_folder.h"
#include "run/simulation.h"
#include "run/velocity_grid.h"
#include "scene/scene.h"

namespace polyfloe::run {

class RunOutputs {
 public:
  // Opens the output folder (fresh, or resumed for a restart) and the writers the scene asks for; a restart's
  // results.h5 is moved aside first (see kInterruptedResults) when `restart_results` is it. Nothing is written
  // into the folder before it is locked and each file listed.
  RunOutputs(const scene::Scene& scene, const dynamics::World& world, const RunOptions& options, double dt,
             const std::string& signature, const std::optional<io::ImageGrid>& grid,
             const std::optional<Checkpoint>& restart, const std::filesystem::path& restart_results);
  RunOutputs(const RunOutputs&) = delete;
  RunOutputs& operator=(const RunOutputs&) = delete;
  // Writes results.xmf when the run stops on an exception (after start()), whatever the checkpoint settings.
  ~RunOutputs();

  // The first frame of a fresh run (forces computed at t = 0), or a restart's outputs taken up where its
  // checkpoint left them (frames adopted, monitors restored into `world`'s run).
  void start(dynamics::World& world, const std::optional<Checkpoint>& restart);
  // After each step: the velocity grid's sample, and the frame and checkpoint that fall due.
  void after_step(const dynamics::World& world);
  // An unstable run's state in DIR/checkpoints/unstable.h5 (when checkpoints are on): what to tell the user.
  std::string save_unstable(const dynamics::World& world);
  // results.xmf at the end.
  void finish();

  // The step to take from time t [s].
  double step(double t) const { return schedule_.step(t, dt_); }
  bool at_end(double t) const { return schedule_.at_end(t); }
  int frames() const { return frames_; }
  const std::filesystem::path& path() const { return folder_.path(); }
  const ChannelMonitor* channel() const { return channel_ ? &*channel_ : nullptr; }

 private:
  void write_frame(const dynamics::World& world);
  void checkpoint(const dynamics::World& world, const char* kind, const std::filesystem::path& file);
  void snapshot_results();  // results.h5 copied to kResultsSnapshot, atomically

  const scene::Scene& scene_;
  const RunOptions& options_;
  double dt_ = 0.0;  // [s]
  std::string signature_;
  OutputFolder folder_;
  std::unique_ptr<io::VtkSeriesWriter> vtk_;
  std::unique_ptr<io::Hdf5Writer> h5_;
  std::optional<ChannelMonitor> channel_;
  std::filesystem::path adopt_from_;  // a restart: the file the interrupted run's frames are copied from
  std::optional<VelocityGridRecorder> velocity_grid_;
  int frames_ = 0;
  std::vector<double> frame_times_;  // [s]
  FrameClock schedule_;
  std::vector<double> extra_values_;  // scratch: the channel monitor's row of a frame
  bool started_ = false;
};

}  // namespace polyfloe::run
