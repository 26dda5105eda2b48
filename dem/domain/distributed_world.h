// The planar World cut among MPI ranks. Every rank is given the whole scene's bodies (the same list, in the same
// order); each owns the floes whose centroids lie in its region of Zoltan's recursive coordinate bisection
// (domain/partition.h) and holds ghosts of the floes of others that can touch its own (domain/halo.h). Each step
// exchanges the ghosts' poses and predicted velocities and the forces of the pairs whose floes have different
// owners, so that every floe moves, bit for bit, as it would in one World holding every body. As the floes drift the
// halo is renewed: each floe migrates to the rank of its region with its state and the histories of the contacts it
// evaluates (the regions cut anew first where the ranks' measured loads have drifted apart), and the ghosts are chosen
// anew.
//
// Output: gather() and gather_contacts() give one rank the whole ice (what one World holding every floe would
// hold), for the run's writers. Frozen ice: each rank holds the bonded faces whose elements it holds.
#pragma once

#include <mpi.h>

#include <cstdint>
#include <memory>
#include <optional>
#include <stdexcept>
#include <unordered_map>
#include <vector>

#include "domain/halo.h"
#include "domain/partition.h"
#include "dynamics/world.h"

namespace polyfloe::domain {

// An error thrown on every rank together (the ranks agreed on it in a collective): each rank may stop on it
// without leaving another waiting.
class CollectiveError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

class DistributedWorld {
 public:
  // Collective over `comm`. `settings` as for a World; its space_order_cell, where 0, is set from `bodies` as a World
  // that adds them in this order sets it (so that the ranks share it). The halo's margin [m]: 0 = 0.5 x the mean
  // equivalent radius of the dynamic bodies. Throws std::invalid_argument on a bad body (as World::add_body).
  // `bonds`: frozen ice, its elements numbered by their place in `bodies` (none: no bonds). Each rank's World holds
  // the faces whose two elements it holds (owned or ghost) and evaluates them all: a face with an element on each
  // of two ranks is evaluated on both, from the same poses and predicted velocities, so both keep its state alike
  // and each adds its forces to its own element in the faces' order, as one World does.
  DistributedWorld(MPI_Comm comm, const dynamics::WorldSettings& settings, std::vector<dynamics::BodyDesc> bodies,
                   double margin = 0.0, const bonds::BondSet* bonds = nullptr);
  ~DistributedWorld();
  DistributedWorld(const DistributedWorld&) = delete;
  DistributedWorld& operator=(const DistributedWorld&) = delete;

  // Collective: one step of dt [s]. The halo is renewed first where, after the last step, some floe had moved more
  // than a quarter of the margin since the last renewal. Throws std::runtime_error (on every rank) when a floe moved
  // more than half the margin within the steps since: pairs could then have been missed, and the time step is far
  // too large (a CollectiveError). One rank has no halo: nothing is tested or renewed.
  void step(double dt);

  // Collective: the forces and contacts of the present state, evaluated (as the first step evaluates them, where it
  // finds none: each rank's World then lists the contacts it evaluated, for a frame written before the first step).
  void compute_forces() { world_->compute_forces(0.0); }
  // Collective: the whole ice's state on rank `root` (every floe's rows in id order, every contact history in key
  // order: bit for bit what one World holding every floe gives as World::state()); none on the other ranks. What a
  // checkpoint stores.
  std::optional<dynamics::WorldState> gather(int root = 0) const;
  // Collective, every rank given the same whole state (as gather() gives it, or one World's state() of the same
  // bodies, from a run on any number of ranks): the regions cut anew for its poses, each rank's floes and ghosts
  // taking their rows and histories from it. Throws std::invalid_argument (on every rank) where the state does not
  // fit the bodies, naming what (bonds: as World::restore).
  void restore(const dynamics::WorldState& full);
  // A contact of the last evaluation, by the ids of its bodies (a < b; the record's indices are those of the rank
  // that evaluated it).
  struct Contact {
    dynamics::BodyId a = 0, b = 0;
    dynamics::ContactRecord record;
  };
  // Collective: the contacts of the last evaluation on rank `root`, each pair once (from the rank that evaluated
  // it), in order of the pairs' ids as one World's contacts() lists them; none on the other ranks.
  std::vector<Contact> gather_contacts(int root = 0) const;

  // This rank's World: its own floes and its ghosts (World::is_ghost).
  const dynamics::World& local() const { return *world_; }
  const HaloExchange& halo() const { return *halo_; }
  double margin() const { return margin_; }
  std::uint64_t renewals() const { return renewals_; }
  std::uint64_t rebalances() const { return rebalances_; }  // renewals that cut the regions anew
  // The load balance. Each rank measures the wall-clock time of its World's steps less the time in the step's
  // exchanges (its busy time: the work, not the waiting), summed over a window that starts at the last rebalance
  // (or restore()) and starts again after kLoadWindow steps. A renewal at least kLoadSample steps into the window
  // compares the ranks' busy times, and cuts the regions anew where the busiest exceeds kImbalance x the mean and
  // its excess over the mean exceeds what the last rebalance took (the slowest rank's renewal, halved at each new
  // window: a rebalance must pay for itself), each floe weighted by its measured cost (weigh_by_cost: its rank's
  // busy time shared by the contact pairs each floe evaluates). The ranks also compare their busy times whenever
  // the window's steps reach a multiple of kLoadCheck and no renewal is due, and renew where a rebalance is due,
  // so that a pack that does not drift is rebalanced too. The cuts depend on timing; the results do not (every
  // decomposition steps the floes bitwise alike).
  static constexpr double kImbalance = 1.1;
  static constexpr std::uint64_t kLoadSample = 20, kLoadCheck = 100, kLoadWindow = 1000;
  std::uint64_t migrated() const { return migrated_; }  // floes this rank took over from others, in all renewals
  // What this rank spent on communication since its construction.
  struct Communication {
    std::uint64_t halo_bytes = 0, halo_messages = 0;  // sent by the step's exchanges (HaloExchange)
    double halo_seconds = 0.0;                        // in the step's exchanges, waiting included [s]
    std::uint64_t renewal_bytes = 0;                  // sent by the renewals (floes migrating, ghosts' rows)
    double renewal_seconds = 0.0;                     // in the renewals, the rebuilt World included [s]
    double check_seconds = 0.0;                       // in the step's test for a renewal (one allreduce) [s]
    double busy_seconds = 0.0;  // in the World's steps, less the step's exchanges: the rank's work [s]
  };
  Communication communication() const;
  int rank() const { return partition_.rank(); }
  // Worker threads of each rank's World (OpenMP; see World::set_threads).
  void set_threads(int threads) {
    threads_ = threads;
    world_->set_threads(threads);
  }
  int ranks() const { return partition_.ranks(); }

 private:
  // The regions cut for the floes' poses (the state's, else the bodies' as given), and this rank's World built for
  // its share (its rows from the state).
  void place(const dynamics::WorldState* full);
  // A World of `owned` and `ghosts` (ids) with `state` (rows for all of them; none: as the bodies were given).
  void build(const std::vector<dynamics::BodyId>& owned, const HaloLayout& layout, const dynamics::WorldState* state);
  void renew();
  // The whole ice's bond state from the ranks that own each face's lower-id element: on every rank into bonds_
  // (root < 0), or into `full` on rank `root`.
  void collect_bonds(int root, dynamics::WorldState* full) const;
  void count_sent(const std::vector<std::vector<unsigned char>>& out);  // a renewal's messages to the other ranks
  // Whether the ranks' measured `load` calls for a rebalance (the header's load balance; the same on every rank); if
  // not, forgets a window of kLoadWindow steps or more.
  bool rebalance_due(const Load& load);
  void start_load_window();  // the load's window empty
  // The farthest any vertex of an owned floe has moved since the last renewal [m] (on this rank).
  double moved() const;

  MPI_Comm comm_;
  dynamics::WorldSettings settings_;
  std::vector<dynamics::BodyDesc> bodies_;
  std::unordered_map<dynamics::BodyId, std::size_t> desc_of_;
  double margin_ = 0.0;
  Partition partition_;
  mutable std::optional<bonds::BondSet> bonds_;  // every face, elements numbered as bodies_; its state as of the
                                                 // last renewal or restore
  std::unique_ptr<dynamics::World> world_;
  std::unique_ptr<HaloExchange> halo_;
  std::uint64_t renewals_ = 0, migrated_ = 0, rebalances_ = 0;
  Communication retired_;  // the counts of the halos that renewals replaced, and of the renewals
  int threads_ = 1;
  bool renew_due_ = false;
  double busy_ = 0.0;             // busy seconds in the load's window [s]
  double busy_total_ = 0.0;       // and since the construction [s]
  std::uint64_t busy_steps_ = 0;  // steps in it
  double rebalance_cost_ = 0.0;   // what the last rebalance took, on the slowest rank [s] (halved each window)
  bool rebalance_now_ = false;    // the last check found a rebalance due (the renewal it asked for does it)
  // The owned floes' poses at the last renewal, by index of the World (re-read by id after it re-stores its bodies).
  mutable std::vector<geometry::Vec2> pos_at_;
  mutable std::vector<double> yaw_at_;
  mutable std::unordered_map<dynamics::BodyId, std::pair<geometry::Vec2, double>> pose_by_id_;
  mutable std::uint64_t reorders_seen_ = 0;
};

}  // namespace polyfloe::domain
