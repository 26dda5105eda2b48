// `polyfloe run` under mpirun (mpi/distributed_run.h).
#include "mpi/distributed_run.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <iostream>
#include <string>
#include <unordered_map>

#include "domain/collectives.h"
#include "forcing/field.h"
#include "io/progress.h"
#include "io/vtk_writer.h"
#include "formats/atomic_file.h"
#include "run/guard.h"
#include "run/run_outputs.h"
#include "run/velocity_grid.h"
#include "scene/scene_reader.h"

namespace polyfloe::mpi {

int agree(MPI_Comm comm, int code) {
  int most = 0;
  MPI_Allreduce(&code, &most, 1, MPI_INT, MPI_MAX, comm);
  return most;
}

bool launched_by_mpirun() {
  return std::getenv("OMPI_COMM_WORLD_SIZE") != nullptr || std::getenv("PMI_SIZE") != nullptr ||
         std::getenv("PMIX_RANK") != nullptr;
}

Session::Session(int& argc, char**& argv) {
  if (!launched_by_mpirun()) return;
  MPI_Init(&argc, &argv);
  active_ = true;
  int rank = 0;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  if (rank != 0) {
    std::cout.setstate(std::ios::failbit);
    std::cerr.setstate(std::ios::failbit);
  }
}

Session::~Session() {
  if (active_) MPI_Finalize();
}

namespace {

// Rank 0 ran `f` (the others nothing); every rank learns whether it threw: rank 0 rethrows it, the others throw
// PeerStopped.
template <class F>
void on_root_agreed(MPI_Comm comm, int rank, F&& f) {
  std::exception_ptr failed;
  if (rank == 0) {
    try {
      f();
    } catch (...) {
      failed = std::current_exception();
    }
  }
  int stop = failed ? 1 : 0;
  MPI_Bcast(&stop, 1, MPI_INT, 0, comm);
  if (failed) std::rethrow_exception(failed);
  if (stop) throw PeerStopped();
}

// Collective: rank `root`'s `text` on every rank.
std::string broadcast(MPI_Comm comm, int root, std::string text) {
  int length = static_cast<int>(text.size());
  MPI_Bcast(&length, 1, MPI_INT, root, comm);
  text.resize(static_cast<std::size_t>(length));
  MPI_Bcast(text.data(), length, MPI_CHAR, root, comm);
  return text;
}

// Collective: the message of the lowest rank whose `mine` is not empty, on every rank; empty where none has one.
std::string first_message(MPI_Comm comm, int rank, int ranks, std::string mine) {
  int who = mine.empty() ? ranks : rank, first = 0;
  MPI_Allreduce(&who, &first, 1, MPI_INT, MPI_MIN, comm);
  return first == ranks ? std::string() : broadcast(comm, first, std::move(mine));
}

// An error this rank met alone, in the middle of a collective step: reported here, and the job aborted (the other
// ranks wait in the step's exchanges).
[[noreturn]] void abort_alone(MPI_Comm comm, int rank, const std::exception& e) {
  if (dynamic_cast<const forcing::FieldError*>(&e))
    std::fprintf(stderr,
                 "\npolyfloe: a forcing field does not cover the run (rank %d): %s\nThe frames written so far are "
                 "complete.\n",
                 rank, e.what());
  else
    std::fprintf(stderr, "\npolyfloe: error (rank %d): %s\n", rank, e.what());
  std::fflush(stderr);
  MPI_Abort(comm, run::kExitFailure);
  std::abort();  // (MPI_Abort does not return)
}

// What each rank spent its run on (polyfloe run --profile under mpirun), printed by rank 0.
void print_rank_profile(MPI_Comm comm, const domain::DistributedWorld& ice, std::uint64_t steps, double wall) {
  struct Row {
    double owned, ghosts, busy_s, halo_bytes, halo_messages, halo_s, renewal_bytes, renewal_s, check_s, renewals,
        rebalances, migrated;
  };
  const dynamics::World& w = ice.local();
  double ghosts = 0.0;
  for (int i = 0; i < static_cast<int>(w.size()); ++i) ghosts += w.is_ghost(i) ? 1.0 : 0.0;
  const domain::DistributedWorld::Communication c = ice.communication();
  const Row mine{static_cast<double>(w.size()) - ghosts,
                 ghosts,
                 c.busy_seconds,
                 static_cast<double>(c.halo_bytes),
                 static_cast<double>(c.halo_messages),
                 c.halo_seconds,
                 static_cast<double>(c.renewal_bytes),
                 c.renewal_seconds,
                 c.check_seconds,
                 static_cast<double>(ice.renewals()),
                 static_cast<double>(ice.rebalances()),
                 static_cast<double>(ice.migrated())};
  const std::vector<std::vector<Row>> all = domain::gather_to(comm, 0, std::vector<Row>{mine});
  if (all.empty()) return;
  const double per = 1.0 / static_cast<double>(std::max<std::uint64_t>(steps, 1));
  std::fprintf(stderr,
               "profile: %.3f s wall for %llu steps; per rank (at the end; busy time and exchanges per step, waiting "
               "included):\n",
               wall, static_cast<unsigned long long>(steps));
  for (std::size_t r = 0; r < all.size(); ++r) {
    const Row& x = all[r].front();
    std::fprintf(stderr,
                 "  rank %zu: %.0f bodies + %.0f ghosts; busy %.3f ms; %.0f bytes in %.1f messages, %.3f ms; %.0f "
                 "renewals (%.0f rebalanced, %.0f floes taken over, %.0f bytes, %.3f s), renewal test %.3f s\n",
                 r, x.owned, x.ghosts, 1e3 * x.busy_s * per, x.halo_bytes * per, x.halo_messages * per,
                 1e3 * x.halo_s * per, x.renewals, x.rebalances, x.migrated, x.renewal_bytes, x.renewal_s, x.check_s);
  }
}

}  // namespace

DistributedRun::DistributedRun(MPI_Comm comm, const scene::Scene& scene, dynamics::World world,
                               std::vector<dynamics::BodyDesc> descs, const run::RunOptions& options,
                               std::optional<run::Checkpoint> restart, const std::filesystem::path& restart_file)
    : comm_(comm), scene_(scene), options_(options), descs_size_(descs.size()) {
  MPI_Comm_rank(comm_, &rank_);
  MPI_Comm_size(comm_, &ranks_);
  if (scene_.output.vtk && scene_.output.vtk_pieces) options_.vtk_piece_writers = ranks_;  // a piece each
  world.set_threads(options_.threads);
  dt_ = scene::time_step(scene_, world);
  reference_speed_ = scene::reference_speed(scene_);
  const scene::VelocityGridSettings& grid = scene_.output.velocity_grid;
  if (grid.enabled && (scene_.output.vtk || scene_.output.hdf5))
    grid_geometry_ = run::velocity_grid_geometry(grid, world);  // (the same on every rank: refused on every one)
  const dynamics::WorldSettings settings = world.settings();
  std::optional<bonds::BondSet> bonds;  // frozen ice, its elements numbered by their place in descs
  if (world.bonds()) {
    std::unordered_map<dynamics::BodyId, int> desc_of;
    for (std::size_t k = 0; k < descs.size(); ++k) desc_of[descs[k].id] = static_cast<int>(k);
    std::vector<int> to(world.size());
    for (std::size_t i = 0; i < world.size(); ++i) to[i] = desc_of.at(world.id(static_cast<int>(i)));
    bonds.emplace(*world.bonds());
    bonds->renumber(to);
  }
  if (rank_ == 0) {
    signature_ = run::body_signature(world);
    whole_.emplace(std::move(world));
  }
  double mass = rank_ == 0 ? whole_->dynamic_mass() : 0.0;
  MPI_Bcast(&mass, 1, MPI_DOUBLE, 0, comm_);
  energy_limit_ = run::runaway_energy_limit(mass, reference_speed_);
  on_root_agreed(comm_, rank_, [&] {
    if (restart)
      restart_results_ = run::take_checkpoint(scene_, *whole_, *restart, restart_file, options_.output_dir,
                                              grid_geometry_.has_value());
  });
  ice_ = std::make_unique<domain::DistributedWorld>(comm_, settings, std::move(descs), 0.0, bonds ? &*bonds : nullptr);
  ice_->set_threads(options_.threads);
  if (restart) ice_->restore(restart->world);  // (checked on rank 0: fits on every rank)
  restart_ = std::move(restart);
}

DistributedRun::~DistributedRun() = default;

void DistributedRun::stop_unstable(run::BasicRunOutputs<dynamics::World>* outputs, std::string unstable) {
  unstable = first_message(comm_, rank_, ranks_, unstable);  // the lowest rank that found the step unstable says why
  try {                                                      // and the state goes to checkpoints/
    gather();
    if (rank_ == 0) unstable += outputs->save_unstable(*whole_);
  } catch (const PeerStopped&) {
  } catch (const std::exception& e) {  // a state one World refuses (not finite): as when a save fails
    unstable += std::string(" (the state could not be saved: ") + e.what() + ")";
  }
  throw run::InstabilityError(unstable);
}

double DistributedRun::ice_energy(double mine) const {
  std::vector<double> shares(static_cast<std::size_t>(ranks_));
  MPI_Allgather(&mine, 1, MPI_DOUBLE, shares.data(), 1, MPI_DOUBLE, comm_);
  double energy = 0.0;
  for (const double e : shares) energy += e;
  return energy;
}

std::string DistributedRun::runaway_energy(double energy) const {
  struct Worst {
    double energy;
    dynamics::BodyId id;
  };
  const auto [e, id] = run::most_energetic(ice_->local());
  const std::vector<std::vector<Worst>> all = domain::all_gather(comm_, std::vector<Worst>{{e, id}});
  Worst worst{-1.0, 0};
  for (const std::vector<Worst>& w : all)
    if (w[0].energy > worst.energy || (w[0].energy == worst.energy && w[0].id < worst.id)) worst = w[0];
  return run::runaway_energy(ice_->local(), energy, energy_limit_, worst.id, worst.energy, dt_);
}

void DistributedRun::write_pieces(run::BasicRunOutputs<dynamics::World>* outputs, int frame) {
  on_root_agreed(comm_, rank_, [&] { outputs->begin_vtk_pieces(*whole_); });
  std::string failed;
  try {
    io::write_vtk_piece(output_path_, ice_->local(), frame, rank_, scene_.output.contacts,
                        scene_.world.drift.water_density);
  } catch (const std::exception& e) {
    failed = "rank " + std::to_string(rank_) + ": " + e.what();
  }
  failed = first_message(comm_, rank_, ranks_, failed);
  if (!failed.empty()) throw io::IoError(failed);
}

void DistributedRun::gather() {
  std::optional<dynamics::WorldState> state;
  std::exception_ptr failed;  // (rank 0's part of a gather may throw after its collectives)
  try {
    state = ice_->gather(0);
  } catch (...) {
    failed = std::current_exception();
  }
  std::vector<domain::DistributedWorld::Contact> contacts = ice_->gather_contacts(0);
  on_root_agreed(comm_, rank_, [&] {
    if (failed) std::rethrow_exception(failed);
    whole_->restore(*state);
    std::vector<dynamics::ContactRecord> records;
    records.reserve(contacts.size());
    for (domain::DistributedWorld::Contact& c : contacts) {
      c.record.a = whole_->index_of(c.a);
      c.record.b = whole_->index_of(c.b);
      records.push_back(c.record);
    }
    whole_->show_contacts(std::move(records));
  });
}

run::RunSummary DistributedRun::run() {
  const auto wall0 = std::chrono::steady_clock::now();
  std::unique_ptr<run::BasicRunOutputs<dynamics::World>> outputs;
  std::unique_ptr<io::Progress> progress;
  // (the ranks' World is rebuilt when they exchange floes: read anew each time)
  auto local = [this]() -> const dynamics::World& { return ice_->local(); };
  const std::uint64_t first_step = local().step_count();
  run::RunSummary s;
  s.start_time = local().time();
  on_root_agreed(comm_, rank_, [&] {
    outputs = std::make_unique<run::BasicRunOutputs<dynamics::World>>(scene_, *whole_, options_, dt_, signature_,
                                                                      grid_geometry_, restart_, restart_results_);
    progress = std::make_unique<io::Progress>(scene_.time.duration, options_.interactive, stderr, first_step);
  });
  output_path_ = broadcast(comm_, 0, rank_ == 0 ? outputs->path().string() : std::string());
  if (!restart_) {  // the forces at t = 0 (what the first step would evaluate), and the first frame's pieces
    try {
      ice_->compute_forces();
    } catch (const domain::CollectiveError&) {
      throw;
    } catch (const std::exception& e) {  // (met by one rank alone, e.g. a floe outside a wind field: as in a step)
      abort_alone(comm_, rank_, e);
    }
    if (options_.vtk_piece_writers > 0) write_pieces(outputs.get(), 0);
  }
  // a fresh run: the first frame from the whole ice, forces at t = 0
  on_root_agreed(comm_, rank_, [&] { outputs->start(*whole_, restart_); });

  // Each step: rank 0 says the step to take (its outputs' schedule), every rank steps its share, the ranks agree
  // on the guard's verdict and on whether the outputs read the ice after it, which is then gathered for them.
  struct Next {
    double dt;
    int end;
  };
  for (;;) {
    Next next{0.0, 0};
    if (rank_ == 0) {
      next = {outputs->step(local().time()), outputs->at_end(local().time()) ? 1 : 0};
      progress->update(local().time(), local().step_count());
    }
    MPI_Bcast(&next, sizeof next, MPI_BYTE, 0, comm_);
    if (next.end) break;
    try {
      ice_->step(next.dt);
    } catch (const domain::CollectiveError&) {
      throw;
    } catch (const std::exception& e) {
      abort_alone(comm_, rank_, e);
    }
    // The run guard's checks, in one process's order: each rank's share, and the ice's energy as a whole.
    const run::ShareCheck check = run::check_share(local(), local().report(), dt_, reference_speed_);
    const double energy = ice_energy(check.energy);
    // (the third: 1 + the VTK frame due in pieces, if one is)
    int mine[4] = {check.motion.empty() ? 0 : 1, rank_ == 0 && outputs->wants_world(local().time()) ? 1 : 0,
                   rank_ == 0 ? outputs->vtk_pieces_due(local().time()) + 1 : 0, check.overlap.empty() ? 0 : 1},
        all[4];
    MPI_Allreduce(mine, all, 4, MPI_INT, MPI_MAX, comm_);
    if (all[0]) stop_unstable(outputs.get(), check.motion);
    if (energy > energy_limit_) stop_unstable(outputs.get(), runaway_energy(energy));
    if (all[3]) stop_unstable(outputs.get(), check.overlap);
    if (all[2] > 0) write_pieces(outputs.get(), all[2] - 1);
    if (!all[1]) continue;
    gather();
    on_root_agreed(comm_, rank_, [&] { outputs->after_step(*whole_); });
  }
  on_root_agreed(comm_, rank_, [&] {
    progress->finish(local().time(), local().step_count());
    outputs->finish();
    if (const run::ChannelMonitor* channel = outputs->channel()) {
      s.channel_area_passed = channel->area_passed();
      s.channel_jam_time = channel->jam_time();
    }
    s.frames = outputs->frames();
    s.output_dir = outputs->path();
  });
  s.steps = local().step_count() - first_step;
  s.simulated = local().time();
  s.wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall0).count();
  s.dt = dt_;
  if (options_.profile) print_rank_profile(comm_, *ice_, s.steps, s.wall);
  return s;
}

}  // namespace polyfloe::mpi
