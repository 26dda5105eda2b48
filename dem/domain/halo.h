// The halo of a rank: which of its floes other ranks hold as ghosts, which ghosts it holds and who owns them, and
// the step's exchange over MPI (dynamics::StepExchange) that keeps the ghosts current and carries the contact forces
// of the pairs whose floes have different owners. With it each rank's World gives its own floes, bit for bit, what
// one World holding every floe would (dynamics/world.h, "owned bodies and ghosts").
#pragma once

#include <mpi.h>

#include <cstdint>
#include <span>
#include <unordered_map>
#include <vector>

#include "dynamics/step_exchange.h"
#include "dynamics/world.h"
#include "geometry/vec2.h"

namespace polyfloe::domain {

// A floe this rank owns, with a box around it [m].
struct HaloItem {
  dynamics::BodyId id = 0;
  geometry::Aabb box;
};

struct HaloLayout {
  std::vector<std::vector<dynamics::BodyId>>
      send;  // by rank: this rank's floes that rank holds as ghosts (increasing id)
  std::vector<std::vector<dynamics::BodyId>>
      recv;  // by rank: the ghosts this rank holds that rank owns (increasing id)
};

// Collective over `comm`: the halo of every rank's `owned` floes, their boxes grown by `margin` / 2 [m] (margin > 0):
// rank q holds a floe of another rank as a ghost where the floe's grown box overlaps q's reach, boxes that cover
// q's own grown floes. Two floes whose boxes overlap, each having moved (any vertex) less than margin / 2 since, are
// then both held by the owner of each: every pair an owner evaluates or receives is a candidate pair of both Worlds.
// A rank's reach is one box around its grown floes, except for the bodies larger than kLarge x its median floe's size (walls, a giant
// floe: at most kMaxLarge of them, the largest), each its own box; one box around all would reach as far as a wall
// does and take every floe along it.
HaloLayout halo_layout(MPI_Comm comm, std::span<const HaloItem> owned, double margin);
inline constexpr double kLarge = 8.0;
inline constexpr std::size_t kMaxLarge = 64;

// The step's exchange of one rank's World under a layout (its ghosts the layout's recv, flagged with
// World::set_ghost): poses and predicted velocities to the ranks that hold this rank's floes as ghosts, and the
// contact forces of the pairs it evaluated to the owners of their higher-id floes; point to point, between the
// ranks that share floes only. Throws std::runtime_error when a floe the layout names is not in the World.
class HaloExchange : public dynamics::StepExchange {
 public:
  HaloExchange(MPI_Comm comm, HaloLayout layout);
  void poses(dynamics::World& w) override;
  void predictions(dynamics::World& w) override;
  void pair_forces(dynamics::World& w) override;

  const HaloLayout& layout() const { return layout_; }
  // What this rank sent since its construction: bytes and messages (the step's communication volume).
  std::uint64_t bytes_sent() const { return bytes_; }
  std::uint64_t messages_sent() const { return messages_; }
  // Wall-clock seconds in the exchanges since its construction [s]: packing, sending, waiting for the neighbours
  // (load imbalance shows here) and unpacking.
  double seconds() const { return seconds_; }

 private:
  // Three doubles per floe, from this rank's floes (`pack`) to the ghosts of the others (`unpack`).
  template <class Pack, class Unpack>
  void forward(dynamics::World& w, int tag, Pack&& pack, Unpack&& unpack);
  int index(const dynamics::World& w, dynamics::BodyId id) const;

  MPI_Comm comm_;
  HaloLayout layout_;
  std::unordered_map<dynamics::BodyId, int> ghost_owner_;
  std::vector<std::vector<double>> out_, in_;  // by rank
  std::vector<std::vector<dynamics::PairForce>> forces_out_;
  std::vector<dynamics::PairForce> forces_in_;
  std::vector<MPI_Request> requests_;
  std::uint64_t bytes_ = 0, messages_ = 0;
  double seconds_ = 0.0;
};

}  // namespace polyfloe::domain
