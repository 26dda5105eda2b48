// The simulation driver: owns a World and steps it to the end, calling writers, the progress display and the
// instability guard on their schedules. It is the layer that knows about files; the World never does.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <stdexcept>
#include <string>

#include "dynamics/spatial_world.h"
#include "dynamics/world.h"
#include "io/vtk_writer.h"
#include "run/checkpoint.h"
#include "run/guard.h"
#include "scene/scene.h"

namespace polyfloe::run {

// Process exit codes of the command line.
enum ExitCode : int { kExitOk = 0, kExitFailure = 1, kExitBadInput = 2, kExitUnstable = 3 };

struct RunOptions {
  std::filesystem::path output_dir;  // created if missing
  int threads = 1;                   // worker threads of the step (World::set_threads; bitwise the same result)
  bool interactive = false;          // stderr is a terminal: redraw a progress line
  bool profile = false;              // print where the time went at the end
  std::string version;               // code version stored in the outputs
  // output.vtk_pieces under mpirun: the ranks, each writing its own piece of every VTK frame (io::write_vtk_piece)
  // before the outputs list the pieces; 0: one process, whose outputs write its one piece themselves.
  int vtk_piece_writers = 0;
};

// The interrupted run's results.h5 is moved here while a restart copies its frames into a new one (kept if the
// restart itself is interrupted, and used by the next restart).
inline constexpr const char* kInterruptedResults = ".results.h5.interrupted";
// A copy of results.h5 taken (atomically) with every checkpoint, just before it: HDF5 does not promise a file that a
// killed writer leaves behind; this copy holds every frame up to the newest checkpoint whatever the kill did. A
// restart copies its frames from the first of the interrupted file, results.h5 and this copy that reads back with
// the checkpoint's frames.
inline constexpr const char* kResultsSnapshot = "checkpoints/results.h5";

struct RunSummary {
  std::uint64_t steps = 0;  // taken by this run (a restart: since its checkpoint)
  double start_time = 0.0;  // where this run started (a restart: the checkpoint's time) [s]
  double simulated = 0.0;   // the time reached [s]
  double wall = 0.0;        // [s]
  double dt = 0.0;          // [s]
  int frames = 0;
  std::filesystem::path output_dir;
  std::optional<double> channel_area_passed;  // scenes with a channel: net ice area through the strait [m^2]
  std::optional<double> channel_jam_time;     // ... and when it jammed [s], if it did
  std::optional<double> first_contact;        // spatial runs: the end of this run's first step with a contact [s]
  std::uint64_t contact_steps = 0;            // ... and its steps that had one
};

// The output schedule of both drivers: steps of dt, the step before a frame time (a multiple of the output interval)
// or the end time shortened to land on it exactly (or stretched by at most 1e-6 dt, so as to leave no sliver of a
// step after it). Frames at t = 0, at every multiple of the interval and at the end. An interval shorter than the
// step writes a frame at every step instead (at the step times; the driver says so).
struct FrameClock {
  double interval = 0.0;    // [s]
  double end = 0.0;         // [s]
  double next = 0.0;        // the next frame time [s]
  bool every_step = false;  // interval < dt
  static FrameClock make(double interval, double end, double dt) {
    return {interval, end, interval, interval < dt * (1.0 - 1e-9)};
  }
  // The step to take from time t with the step size dt [s].
  double step(double t, double dt) const {
    const double left = (every_step ? end : std::min(next, end)) - t;
    return left <= dt * (1.0 + 1e-6) ? left : dt;
  }
  bool at_end(double t) const { return t >= end * (1.0 - 1e-12); }
  bool frame_due(double t) const { return every_step || at_end(t) || t >= next * (1.0 - 1e-12); }
  // After the frame at time t: the next frame time.
  void frame_written(double t) { next = interval * (std::floor(t / interval * (1.0 + 1e-12)) + 1.0); }
  // The note a driver prints when every_step is set.
  std::string note(double dt) const;
};

// A restart's checks and state, before any file is touched: the checkpoint `c` (read from `file`) against the scene
// and `world` (built from it), its state restored into `world`, and the interrupted run's outputs in `dir`. Returns
// the results file the restart copies the frames from (see kResultsSnapshot; empty without HDF5 output). `grid`:
// the run writes a velocity grid. Throws CheckpointError (bad input: exit 2). W: dynamics::World or SpatialWorld.
template <class W>
std::filesystem::path take_checkpoint(const scene::Scene& scene, W& world, const Checkpoint& c,
                                      const std::filesystem::path& file, const std::filesystem::path& dir, bool grid);

// The driver of both worlds (W: dynamics::World, the planar one, or dynamics::SpatialWorld): the same end-time and
// frame rule (FrameClock), outputs (run/run_outputs.h), checkpoints and restart, threads, guard, progress and
// profile. What only a planar scene has (the channel monitor, the velocity grid, results.xmf) is absent from a
// spatial run.
template <class W>
class BasicSimulation {
 public:
  // `world` as built from `scene`. With `restart` (a checkpoint of a run of this scene, read from `restart_file`),
  // the run continues from it in options.output_dir, where the interrupted run's outputs must be: the constructor
  // checks the checkpoint against the world and those outputs and restores the state, before any file is touched.
  // Throws CheckpointError or scene::SceneError (bad input: exit 2).
  BasicSimulation(const scene::Scene& scene, W world, const RunOptions& options,
                  std::optional<Checkpoint> restart = std::nullopt, const std::filesystem::path& restart_file = {});
  // Runs to scene.time.duration. Throws InstabilityError (exit 3) or std::exception (exit 1). With checkpoints on,
  // an unstable run leaves its state in DIR/checkpoints/unstable.h5 for inspection.
  RunSummary run();
  const W& world() const { return world_; }
  double dt() const { return dt_; }

 private:
  // After each step: the run guard on the step's report, and a spatial run's contact count.
  void guard(const dynamics::StepReport& report);

  const scene::Scene& scene_;
  W world_;
  RunOptions options_;
  double dt_ = 0.0;
  std::string signature_;
  std::optional<io::ImageGrid> grid_geometry_;
  std::optional<Checkpoint> restart_;
  std::filesystem::path restart_results_;  // a restart: the file its frames are copied from (see kResultsSnapshot)
  double reference_speed_ = 0.0;           // [m/s]
  RunSummary summary_;
};

using Simulation = BasicSimulation<dynamics::World>;
using SpatialSimulation = BasicSimulation<dynamics::SpatialWorld>;
extern template class BasicSimulation<dynamics::World>;
extern template class BasicSimulation<dynamics::SpatialWorld>;

}  // namespace polyfloe::run
