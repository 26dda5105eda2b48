// The halo of a rank and the step's exchange over MPI (domain/halo.h).
#include "domain/halo.h"

#include "domain/collectives.h"

#include <algorithm>
#include <array>
#include <limits>
#include <stdexcept>
#include <string>

namespace polyfloe::domain {

namespace {

enum Tag : int { kPoses = 101, kPredictions = 102, kForces = 103 };

int comm_rank(MPI_Comm comm) {
  int r = 0;
  MPI_Comm_rank(comm, &r);
  return r;
}
int comm_size(MPI_Comm comm) {
  int r = 1;
  MPI_Comm_size(comm, &r);
  return r;
}

}  // namespace

HaloLayout halo_layout(MPI_Comm comm, std::span<const HaloItem> owned, double margin) {
  if (!(margin > 0.0)) throw std::invalid_argument("halo_layout: the margin must be positive");
  const int rank = comm_rank(comm), ranks = comm_size(comm);
  const geometry::Vec2 g{0.5 * margin, 0.5 * margin};
  // The box around this rank's grown floes, as (lo.x, lo.y, -hi.x, -hi.y): none (+inf) without floes.
  constexpr double inf = std::numeric_limits<double>::infinity();
  std::array<double, 4> reach{inf, inf, inf, inf};
  for (const HaloItem& it : owned) {
    reach[0] = std::min(reach[0], it.box.lo.x() - g.x());
    reach[1] = std::min(reach[1], it.box.lo.y() - g.y());
    reach[2] = std::min(reach[2], -(it.box.hi.x() + g.x()));
    reach[3] = std::min(reach[3], -(it.box.hi.y() + g.y()));
  }
  std::vector<double> all(4 * static_cast<std::size_t>(ranks));
  MPI_Allgather(reach.data(), 4, MPI_DOUBLE, all.data(), 4, MPI_DOUBLE, comm);
  std::vector<HaloItem> by_id(owned.begin(), owned.end());
  std::sort(by_id.begin(), by_id.end(), [](const HaloItem& a, const HaloItem& b) { return a.id < b.id; });
  HaloLayout layout;
  layout.send.resize(static_cast<std::size_t>(ranks));
  layout.recv.resize(static_cast<std::size_t>(ranks));
  for (int q = 0; q < ranks; ++q) {
    if (q == rank) continue;
    const double* e = all.data() + 4 * q;
    const geometry::Aabb theirs{{e[0], e[1]}, {-e[2], -e[3]}};
    for (const HaloItem& it : by_id)
      if (geometry::Aabb{it.box.lo - g, it.box.hi + g}.overlaps(theirs)) layout.send[q].push_back(it.id);
  }
  // Each rank learns which ghosts it holds from the ranks that send them.
  layout.recv = all_to_all(comm, layout.send);
  return layout;
}

HaloExchange::HaloExchange(MPI_Comm comm, HaloLayout layout) : comm_(comm), layout_(std::move(layout)) {
  const std::size_t ranks = static_cast<std::size_t>(comm_size(comm));
  if (layout_.send.size() != ranks || layout_.recv.size() != ranks)
    throw std::invalid_argument("HaloExchange: the layout is not one of this communicator's");
  for (std::size_t q = 0; q < ranks; ++q)
    for (const dynamics::BodyId id : layout_.recv[q]) ghost_owner_[id] = static_cast<int>(q);
  out_.resize(ranks);
  in_.resize(ranks);
  forces_out_.resize(ranks);
}

int HaloExchange::index(const dynamics::World& w, dynamics::BodyId id) const {
  const int i = w.index_of(id);
  if (i < 0) throw std::runtime_error("the halo names body " + std::to_string(id) + ", which this rank's World lacks");
  return i;
}

template <class Pack, class Unpack>
void HaloExchange::forward(dynamics::World& w, int tag, Pack&& pack, Unpack&& unpack) {
  const int ranks = static_cast<int>(layout_.send.size());
  requests_.clear();
  for (int q = 0; q < ranks; ++q) {
    const std::vector<dynamics::BodyId>& ids = layout_.recv[q];
    if (ids.empty()) continue;
    in_[q].resize(3 * ids.size());
    MPI_Irecv(in_[q].data(), static_cast<int>(in_[q].size()), MPI_DOUBLE, q, tag, comm_, &requests_.emplace_back());
  }
  for (int q = 0; q < ranks; ++q) {
    const std::vector<dynamics::BodyId>& ids = layout_.send[q];
    if (ids.empty()) continue;
    out_[q].resize(3 * ids.size());
    for (std::size_t k = 0; k < ids.size(); ++k) pack(index(w, ids[k]), out_[q].data() + 3 * k);
    MPI_Isend(out_[q].data(), static_cast<int>(out_[q].size()), MPI_DOUBLE, q, tag, comm_, &requests_.emplace_back());
    bytes_ += out_[q].size() * sizeof(double);
    ++messages_;
  }
  MPI_Waitall(static_cast<int>(requests_.size()), requests_.data(), MPI_STATUSES_IGNORE);
  for (int q = 0; q < ranks; ++q) {
    const std::vector<dynamics::BodyId>& ids = layout_.recv[q];
    for (std::size_t k = 0; k < ids.size(); ++k) unpack(index(w, ids[k]), in_[q].data() + 3 * k);
  }
}

void HaloExchange::poses(dynamics::World& w) {
  forward(
      w, kPoses,
      [&](int i, double* v) {
        v[0] = w.positions()[i].x();
        v[1] = w.positions()[i].y();
        v[2] = w.yaws()[i];
      },
      [&](int i, const double* v) {
        w.set_ghost_pose(i, {v[0], v[1]}, v[2]);
      });
}

void HaloExchange::predictions(dynamics::World& w) {
  forward(
      w, kPredictions,
      [&](int i, double* v) {
        v[0] = w.predicted_velocity(i).x();
        v[1] = w.predicted_velocity(i).y();
        v[2] = w.predicted_omega(i);
      },
      [&](int i, const double* v) {
        w.set_ghost_prediction(i, {v[0], v[1]}, v[2]);
      });
}

void HaloExchange::pair_forces(dynamics::World& w) {
  // To the owners of this rank's ghosts (each of them, also with nothing to send: it waits for a message), from the
  // ranks that hold this rank's floes as ghosts.
  const int ranks = static_cast<int>(layout_.send.size());
  for (auto& f : forces_out_) f.clear();
  for (const dynamics::PairForce& f : w.outgoing_pair_forces()) forces_out_[ghost_owner_.at(f.b)].push_back(f);
  requests_.clear();
  for (int q = 0; q < ranks; ++q) {
    if (layout_.recv[q].empty()) continue;
    const int bytes = static_cast<int>(forces_out_[q].size() * sizeof(dynamics::PairForce));
    MPI_Isend(forces_out_[q].data(), bytes, MPI_BYTE, q, kForces, comm_, &requests_.emplace_back());
    bytes_ += static_cast<std::uint64_t>(bytes);
    ++messages_;
  }
  forces_in_.clear();
  for (int q = 0; q < ranks; ++q) {
    if (layout_.send[q].empty()) continue;
    MPI_Status status;
    MPI_Probe(q, kForces, comm_, &status);
    int bytes = 0;
    MPI_Get_count(&status, MPI_BYTE, &bytes);
    const std::size_t at = forces_in_.size();
    forces_in_.resize(at + static_cast<std::size_t>(bytes) / sizeof(dynamics::PairForce));
    MPI_Recv(forces_in_.data() + at, bytes, MPI_BYTE, q, kForces, comm_, MPI_STATUS_IGNORE);
  }
  MPI_Waitall(static_cast<int>(requests_.size()), requests_.data(), MPI_STATUSES_IGNORE);
  w.take_pair_forces(forces_in_);
}

}  // namespace polyfloe::domain
