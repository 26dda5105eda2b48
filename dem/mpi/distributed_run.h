// `polyfloe run` under mpirun: the planar World cut among the ranks (domain::DistributedWorld), with the outputs of
// a run in one process (run/run_outputs.h), written by rank 0 from the whole ice gathered whenever they read it (a
// frame, a velocity grid sample, a checkpoint). results.h5, the VTK frames and the checkpoints are bitwise those of
// one process, on any number of ranks and threads, and a checkpoint restarts on any number of ranks.
//
// The ranks stop together: an error only rank 0 meets (its output folder, a checkpoint that does not fit) is
// agreed on before the next collective, and an unstable step is agreed on every step (the guard of run/guard.h:
// each rank checks its own floes, and the ice's kinetic energy is every rank's share summed). An error one rank
// meets in the middle of a step (the ice left a field file's grid) cannot be agreed on: that rank reports it and
// aborts the job (MPI_Abort).
#pragma once

#include <mpi.h>

#include <filesystem>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "domain/distributed_world.h"
#include "dynamics/world.h"
#include "run/checkpoint.h"
#include "run/simulation.h"
#include "scene/scene.h"

namespace polyfloe::run {
template <class W>
class BasicRunOutputs;
}

namespace polyfloe::mpi {

// Thrown on the ranks other than 0 where rank 0 stopped on an error it reports: these ranks stop too, silently.
class PeerStopped : public std::runtime_error {
 public:
  PeerStopped() : std::runtime_error("rank 0 stopped") {}
};

// Collective: the largest of the ranks' `code`s (exit codes: 0 where a rank has nothing to report).
int agree(MPI_Comm comm, int code);

// Whether mpirun (OpenMPI's, or a PMI launcher) started this process.
bool launched_by_mpirun();

// MPI for the life of a program's main(), when mpirun started the process (none otherwise). The ranks other than 0
// then write nothing to std::cout and std::cerr: every rank meets the same bad input, and rank 0 reports it.
class Session {
 public:
  Session(int& argc, char**& argv);
  ~Session();
  Session(const Session&) = delete;
  Session& operator=(const Session&) = delete;
  bool active() const { return active_; }

 private:
  bool active_ = false;
};

class DistributedRun {
 public:
  // Collective over `comm`. Every rank gives the scene's World as built and `descs`, its bodies' descriptions in
  // the order it was given them (scene::build_world's); rank 0 keeps `world` as the whole ice its outputs show.
  // `restart` (a checkpoint read from `restart_file`, every rank given it): checked on rank 0 against the scene
  // and the interrupted run's outputs in options.output_dir, then restored on every rank. Throws on rank 0 what
  // BasicSimulation's constructor throws (CheckpointError, SceneError), PeerStopped on the others.
  DistributedRun(MPI_Comm comm, const scene::Scene& scene, dynamics::World world, std::vector<dynamics::BodyDesc> descs,
                 const run::RunOptions& options, std::optional<run::Checkpoint> restart = std::nullopt,
                 const std::filesystem::path& restart_file = {});
  ~DistributedRun();
  // Collective: runs to scene.time.duration. Throws run::InstabilityError (every rank), domain::CollectiveError
  // (every rank), on rank 0 what the outputs throw (PeerStopped on the others); aborts the job on an error one
  // rank meets in a step.
  run::RunSummary run();

  int rank() const { return rank_; }
  int ranks() const { return ranks_; }
  std::size_t size() const { return descs_size_; }  // bodies of the whole ice
  double dt() const { return dt_; }
  const domain::DistributedWorld& ice() const { return *ice_; }
  double start_time() const { return ice_->local().time(); }  // [s]
  std::uint64_t start_step() const { return ice_->local().step_count(); }

 private:
  // Rank 0's mirror: the whole ice at the time of the ranks' World, gathered (collective).
  void gather();
  // Collective (output.vtk_pieces): frame `frame`'s VTK pieces, each rank's its own, listed first by rank 0's
  // `outputs`. Throws io::IoError on every rank where one rank could not write its piece (the first such rank's
  // message), PeerStopped on the others where rank 0 could not list them.
  void write_pieces(run::BasicRunOutputs<dynamics::World>* outputs, int frame);
  // Collective, where some rank found the step unstable (`unstable`: this rank's finding, or empty): throws
  // run::InstabilityError on every rank with the lowest such rank's message, the state saved where it can be.
  [[noreturn]] void stop_unstable(run::BasicRunOutputs<dynamics::World>* outputs, std::string unstable);
  // Collective: the ice's kinetic energy [J], every rank's share (`mine`) summed in rank order (the same bits on
  // every rank).
  double ice_energy(double mine) const;
  // Collective, where the ice's energy passed energy_limit_: run::runaway_energy's message, naming the most
  // energetic floe of every rank's (the lowest id of equals), the same on every rank.
  std::string runaway_energy(double energy) const;

  MPI_Comm comm_;
  int rank_ = 0, ranks_ = 1;
  const scene::Scene& scene_;
  run::RunOptions options_;
  std::size_t descs_size_ = 0;
  double dt_ = 0.0, reference_speed_ = 0.0;  // [s], [m/s]
  // The run guard's limit on the whole ice's kinetic energy [J], from its dynamic mass summed as one process sums it
  // (rank 0's whole ice): the guard weighs the ice, not a rank's share of it.
  double energy_limit_ = 0.0;
  std::string signature_;
  std::optional<dynamics::World> whole_;  // rank 0: the whole ice, brought up to date when the outputs read it
  std::unique_ptr<domain::DistributedWorld> ice_;
  std::optional<run::Checkpoint> restart_;
  std::filesystem::path restart_results_;
  std::optional<io::ImageGrid> grid_geometry_;
  std::filesystem::path output_path_;  // rank 0's output folder, on every rank (VTK pieces)
};

}  // namespace polyfloe::mpi
