// The halo of a rank and the step's exchange over MPI (domain/halo.h).
#include "domain/halo.h"

#include "domain/collectives.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <limits>
#include <numeric>
#include <stdexcept>
#include <string>

namespace polyfloe::domain {

namespace {

using Clock = std::chrono::steady_clock;
double since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

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
  auto grown = [&](const geometry::Aabb& b) { return geometry::Aabb{b.lo - g, b.hi + g}; };
  // What this rank's grown floes cover, as boxes for the others: the bodies far larger than its typical floe (more
  // than kLarge x the median size: walls, a giant floe; the kMaxLarge largest) each by its own box, the rest by one
  // box around them. (One box around all would reach as far as a wall does, and take every floe along it.)
  std::vector<double> size(owned.size());
  for (std::size_t k = 0; k < owned.size(); ++k) {
    const geometry::Vec2 e = owned[k].box.hi - owned[k].box.lo;
    size[k] = std::max(e.x(), e.y());
  }
  std::vector<double> sorted = size;
  std::nth_element(sorted.begin(), sorted.begin() + static_cast<std::ptrdiff_t>(sorted.size() / 2), sorted.end());
  const double large = sorted.empty() ? 0.0 : kLarge * sorted[sorted.size() / 2];
  std::vector<std::size_t> by_size(owned.size());
  std::iota(by_size.begin(), by_size.end(), std::size_t{0});
  std::sort(by_size.begin(), by_size.end(), [&](std::size_t x, std::size_t y) { return size[x] > size[y]; });
  constexpr double inf = std::numeric_limits<double>::infinity();
  std::vector<geometry::Aabb> reach{{{inf, inf}, {-inf, -inf}}};  // the box around the rest first (none: empty)
  for (std::size_t j = 0; j < by_size.size(); ++j) {
    const geometry::Aabb b = grown(owned[by_size[j]].box);
    if (j < kMaxLarge && size[by_size[j]] > large) {
      reach.push_back(b);
    } else {
      reach[0].lo = reach[0].lo.cwiseMin(b.lo);
      reach[0].hi = reach[0].hi.cwiseMax(b.hi);
    }
  }
  std::vector<std::array<double, 4>> flat;  // (as plain numbers for MPI)
  for (const geometry::Aabb& b : reach) flat.push_back({b.lo.x(), b.lo.y(), b.hi.x(), b.hi.y()});
  std::vector<std::vector<geometry::Aabb>> all;
  for (const std::vector<std::array<double, 4>>& boxes : all_gather(comm, flat)) {
    all.emplace_back();
    for (const std::array<double, 4>& e : boxes) all.back().push_back({{e[0], e[1]}, {e[2], e[3]}});
  }
  std::vector<HaloItem> by_id(owned.begin(), owned.end());
  std::sort(by_id.begin(), by_id.end(), [](const HaloItem& a, const HaloItem& b) { return a.id < b.id; });
  HaloLayout layout;
  layout.send.resize(static_cast<std::size_t>(ranks));
  layout.recv.resize(static_cast<std::size_t>(ranks));
  for (int q = 0; q < ranks; ++q) {
    if (q == rank) continue;
    const std::vector<geometry::Aabb>& theirs = all[static_cast<std::size_t>(q)];
    for (const HaloItem& it : by_id) {
      const geometry::Aabb b = grown(it.box);
      if (std::any_of(theirs.begin(), theirs.end(), [&](const geometry::Aabb& t) { return b.overlaps(t); }))
        layout.send[q].push_back(it.id);
    }
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
  const Clock::time_point t0 = Clock::now();
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
  seconds_ += since(t0);
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
  const Clock::time_point t0 = Clock::now();
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
  seconds_ += since(t0);
}

}  // namespace polyfloe::domain
