// The planar World cut among MPI ranks (domain/distributed_world.h).
#include "domain/distributed_world.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>
#include <numeric>
#include <span>
#include <stdexcept>
#include <string>
#include <tuple>

#include "domain/collectives.h"
#include "dynamics/state_fields.h"
#include "geometry/space_order.h"

namespace polyfloe::domain {

namespace {

using Bytes = std::vector<unsigned char>;
using dynamics::BodyId;

template <class T>
void put(Bytes& out, const T& x) {
  const auto* p = reinterpret_cast<const unsigned char*>(&x);
  out.insert(out.end(), p, p + sizeof(T));
}
template <class T>
T get(const unsigned char*& in) {
  T x;
  std::memcpy(&x, in, sizeof(T));
  in += sizeof(T);
  return x;
}

// Appends the rows `rows` of every per-body field of a state, each field behind a byte that says whether the state
// has it (the drift model's fields may be empty).
class RowPacker : public dynamics::BodyFieldVisitor {
 public:
  RowPacker(std::span<const int> rows, Bytes& out) : rows_(rows), out_(out) {}
  template <class T>
  void bodies(const char*, const std::vector<T>& v) {
    put_rows(v);
  }
  template <class T>
  void bodies_or_none(const char*, const std::vector<T>& v) {
    put_rows(v);
  }

 private:
  template <class T>
  void put_rows(const std::vector<T>& v) {
    using Row = dynamics::StateRow<T>;
    put(out_, static_cast<std::uint8_t>(!v.empty()));
    if (v.empty()) return;
    typename Row::Scalar x[Row::width];
    for (const int k : rows_) {
      Row::pack(v[static_cast<std::size_t>(k)], x);
      for (const auto s : x) put(out_, s);
    }
  }
  std::span<const int> rows_;
  Bytes& out_;
};

// Appends `n` rows of every per-body field, read from `in`, to a state's fields.
class RowUnpacker : public dynamics::BodyFieldVisitor {
 public:
  RowUnpacker(std::size_t n, const unsigned char*& in) : n_(n), in_(in) {}
  template <class T>
  void bodies(const char*, std::vector<T>& v) {
    take(v);
  }
  template <class T>
  void bodies_or_none(const char*, std::vector<T>& v) {
    take(v);
  }

 private:
  template <class T>
  void take(std::vector<T>& v) {
    using Row = dynamics::StateRow<T>;
    if (!get<std::uint8_t>(in_)) return;
    typename Row::Scalar x[Row::width];
    for (std::size_t k = 0; k < n_; ++k) {
      for (auto& s : x) s = get<typename Row::Scalar>(in_);
      T row;
      Row::unpack(x, row);
      v.push_back(row);
    }
  }
  std::size_t n_;
  const unsigned char*& in_;
};

// One message: rows of `s` and contact histories.
void pack(const dynamics::WorldState& s, std::span<const int> rows,
          std::span<const contact::ContactCache::Entry* const> history, Bytes& out) {
  put(out, static_cast<std::uint64_t>(rows.size()));
  RowPacker packer(rows, out);
  visit_fields(packer, s);
  put(out, static_cast<std::uint64_t>(history.size()));
  for (const contact::ContactCache::Entry* e : history) {
    put(out, e->first.lo);
    put(out, e->first.hi);
    put(out, e->second.spring);
    put(out, e->second.normal_force);
  }
}

// A message's rows and histories appended to `s`.
void unpack(const Bytes& in, dynamics::WorldState& s) {
  if (in.empty()) return;
  const unsigned char* p = in.data();
  const auto n = get<std::uint64_t>(p);
  RowUnpacker unpacker(n, p);
  visit_fields(unpacker, s);
  const auto h = get<std::uint64_t>(p);
  for (std::uint64_t k = 0; k < h; ++k) {
    contact::ContactCache::Entry e;
    e.first.lo = get<std::uint64_t>(p);
    e.first.hi = get<std::uint64_t>(p);
    e.second.spring = get<double>(p);
    e.second.normal_force = get<double>(p);
    s.contact_history.push_back(e);
  }
}

// The box around a body of `shape` at (at, yaw) [m, rad].
geometry::Aabb box_of(const geometry::ConvexPolygon& shape, const geometry::Vec2& at, double yaw) {
  const double c = std::cos(yaw), s = std::sin(yaw);
  geometry::Aabb b{at, at};
  for (const geometry::Vec2& v : shape.vertices()) {
    const geometry::Vec2 p = at + geometry::rotate(v, c, s);
    b.lo = b.lo.cwiseMin(p);
    b.hi = b.hi.cwiseMax(p);
  }
  return b;
}

// A state with the scalars of `s` and no rows.
dynamics::WorldState scalars_of(const dynamics::WorldState& s) {
  dynamics::WorldState out;
  out.time = s.time;
  out.steps = s.steps;
  out.forces_ready = s.forces_ready;
  out.bonds_failed_last = s.bonds_failed_last;
  return out;
}

}  // namespace

DistributedWorld::DistributedWorld(MPI_Comm comm, const dynamics::WorldSettings& settings,
                                   std::vector<dynamics::BodyDesc> bodies, double margin, const bonds::BondSet* bonds)
    : comm_(comm), settings_(settings), bodies_(std::move(bodies)), partition_(comm) {
  if (bonds) bonds_.emplace(*bonds);
  double radius_sum = 0.0;  // as a World adding the bodies in this order sums them
  int dynamic = 0;
  for (std::size_t k = 0; k < bodies_.size(); ++k) {
    const dynamics::BodyDesc& d = bodies_[k];
    if (!d.shape) throw std::invalid_argument("body " + std::to_string(d.id) + " has no shape");
    if (!desc_of_.emplace(d.id, k).second) throw std::invalid_argument("duplicate body id " + std::to_string(d.id));
    if (d.motion == dynamics::Motion::dynamic) {
      radius_sum += d.shape->equivalent_radius();
      ++dynamic;
    }
  }
  if (settings_.space_order_cell <= 0.0 && dynamic > 0)
    settings_.space_order_cell = geometry::space_order_cell(radius_sum / dynamic);
  margin_ = margin > 0.0 ? margin : dynamic > 0 ? 0.5 * radius_sum / dynamic : 1.0;
  place(nullptr);
}

void DistributedWorld::place(const dynamics::WorldState* full) {
  // Where each body is (by its place in bodies_): the state's row, else as given.
  std::vector<geometry::Vec2> at(bodies_.size());
  std::vector<double> yaw(bodies_.size());
  std::vector<int> row(bodies_.size(), -1);
  for (std::size_t k = 0; k < bodies_.size(); ++k) {
    at[k] = bodies_[k].position;
    yaw[k] = bodies_[k].yaw;
  }
  if (full && full->bonds) bonds_->restore(*full->bonds);  // (checked by restore(): the ice has bonds)
  if (full)
    for (std::size_t r = 0; r < full->ids.size(); ++r) {
      const std::size_t k = desc_of_.at(full->ids[r]);
      at[k] = full->position[r];
      yaw[k] = full->yaw[r];
      row[k] = static_cast<int>(r);
    }
  // The partition of the floes (each rank offers a share: every rank knows every body), then each rank's own.
  std::vector<PartitionItem> items;
  for (std::size_t k = 0; k < bodies_.size(); ++k)
    if (static_cast<int>(k % static_cast<std::size_t>(ranks())) == rank()) items.push_back({bodies_[k].id, at[k], 1.0});
  partition_.balance(items);
  std::vector<BodyId> owned;
  std::vector<HaloItem> mine;
  for (std::size_t k = 0; k < bodies_.size(); ++k) {
    if (partition_.rank_of(at[k]) != rank()) continue;
    owned.push_back(bodies_[k].id);
    mine.push_back({bodies_[k].id, box_of(*bodies_[k].shape, at[k], yaw[k])});
  }
  const HaloLayout layout = halo_layout(comm_, mine, margin_);
  renew_due_ = false;
  start_load_window();  // (a new decomposition: its load is measured anew)
  rebalance_now_ = false;
  if (!full) {
    build(owned, layout, nullptr);
    return;
  }
  // This rank's rows of the state (its floes' and its ghosts') and the histories of the pairs it evaluates.
  std::vector<int> rows;
  std::unordered_map<BodyId, bool> own;
  for (const BodyId id : owned) {
    rows.push_back(row[desc_of_.at(id)]);
    own[id] = true;
  }
  for (const std::vector<BodyId>& ids : layout.recv)
    for (const BodyId id : ids) rows.push_back(row[desc_of_.at(id)]);
  std::vector<const contact::ContactCache::Entry*> history;
  for (const contact::ContactCache::Entry& e : full->contact_history)
    if (own.contains(e.first.lo)) history.push_back(&e);
  Bytes bytes;
  pack(*full, rows, history, bytes);
  dynamics::WorldState part = scalars_of(*full);
  unpack(bytes, part);
  build(owned, layout, &part);
}

void DistributedWorld::restore(const dynamics::WorldState& full) {
  auto bad = [](const std::string& what) { throw std::invalid_argument("world state: " + what); };
  if (full.ids.size() != bodies_.size())
    bad("it has " + std::to_string(full.ids.size()) + " bodies, the ice has " + std::to_string(bodies_.size()));
  if (const std::string problem = dynamics::body_row_problem(full, false); !problem.empty()) bad(problem);
  std::vector<char> seen(bodies_.size(), 0);
  for (const BodyId id : full.ids) {
    const auto it = desc_of_.find(id);
    if (it == desc_of_.end()) bad("it has a body of id " + std::to_string(id) + ", the ice has none");
    if (seen[it->second]++) bad("it lists the body of id " + std::to_string(id) + " twice");
  }
  for (const contact::ContactCache::Entry& e : full.contact_history)
    if (!desc_of_.contains(e.first.lo) || !desc_of_.contains(e.first.hi))
      bad("a contact history names a body the ice does not have (" + std::to_string(e.first.lo) + ", " +
          std::to_string(e.first.hi) + ")");
  if (full.bonds.has_value() != bonds_.has_value())
    bad(full.bonds ? "it has bonds, the ice has none" : "it has no bonds, the ice has");
  if (bonds_) {
    bonds::BondSet check = *bonds_;  // (its own checks: sizes, counts)
    check.restore(*full.bonds);
  }
  place(&full);
}

std::optional<dynamics::WorldState> DistributedWorld::gather(int root) const {
  const dynamics::World& w = *world_;
  const dynamics::WorldState s = w.state();
  std::vector<int> own_rows;
  for (std::size_t k = 0; k < s.ids.size(); ++k)
    if (!w.is_ghost(w.index_of(s.ids[k]))) own_rows.push_back(static_cast<int>(k));
  std::vector<const contact::ContactCache::Entry*> history;  // (a World stores those of the pairs it evaluates)
  for (const contact::ContactCache::Entry& e : s.contact_history) history.push_back(&e);
  Bytes mine;
  pack(s, own_rows, history, mine);
  const std::vector<Bytes> all = gather_to(comm_, root, mine);
  dynamics::WorldState full = scalars_of(s);
  if (bonds_) collect_bonds(root, &full);  // (collective)
  if (rank() != root) return std::nullopt;
  for (const Bytes& m : all) unpack(m, full);
  std::vector<int> from(full.ids.size());
  std::iota(from.begin(), from.end(), 0);
  std::sort(from.begin(), from.end(), [&](int x, int y) { return full.ids[x] < full.ids[y]; });
  dynamics::gather_body_rows(full, from);
  contact::ContactCache::sort_by_key(full.contact_history);
  return full;
}

DistributedWorld::~DistributedWorld() = default;

void DistributedWorld::build(const std::vector<BodyId>& owned, const HaloLayout& layout,
                             const dynamics::WorldState* state) {
  auto w = std::make_unique<dynamics::World>(settings_);
  w->set_threads(threads_);
  for (const BodyId id : owned) w->add_body(bodies_[desc_of_.at(id)]);
  for (const std::vector<BodyId>& ids : layout.recv)
    for (const BodyId id : ids) w->set_ghost(w->add_body(bodies_[desc_of_.at(id)]), true);
  std::optional<dynamics::WorldState> with_bonds;
  if (bonds_) {  // the faces of the elements held here, with their state
    std::vector<int> local_of(bodies_.size(), -1);
    for (int i = 0; i < static_cast<int>(w->size()); ++i) local_of[desc_of_.at(w->id(i))] = i;
    w->set_bonds(bonds_->subset(local_of));
    if (state) {
      with_bonds = *state;
      with_bonds->bonds = w->bonds()->state();
      state = &*with_bonds;
    }
  }
  if (halo_) {
    retired_.halo_bytes += halo_->bytes_sent();
    retired_.halo_messages += halo_->messages_sent();
    retired_.halo_seconds += halo_->seconds();
  }
  auto halo = std::make_unique<HaloExchange>(comm_, layout);
  w->set_exchange(halo.get());
  if (state) w->restore(*state);
  world_ = std::move(w);
  halo_ = std::move(halo);
  // Where the owned floes are now: how far they move is measured from here.
  pose_by_id_.clear();
  for (int i = 0; i < static_cast<int>(world_->size()); ++i)
    if (!world_->is_ghost(i)) pose_by_id_[world_->id(i)] = {world_->positions()[i], world_->yaws()[i]};
  reorders_seen_ = ~std::uint64_t{0};
}

double DistributedWorld::moved() const {
  const dynamics::World& w = *world_;
  const int n = static_cast<int>(w.size());
  if (w.body_reorders() != reorders_seen_) {  // indices changed: the poses by index anew
    pos_at_.assign(static_cast<std::size_t>(n), geometry::Vec2{0.0, 0.0});
    yaw_at_.assign(static_cast<std::size_t>(n), 0.0);
    for (int i = 0; i < n; ++i)
      if (!w.is_ghost(i)) std::tie(pos_at_[i], yaw_at_[i]) = pose_by_id_.at(w.id(i));
    reorders_seen_ = w.body_reorders();
  }
  double most = 0.0;
  for (int i = 0; i < n; ++i) {
    if (w.is_ghost(i)) continue;
    const double d = (w.positions()[i] - pos_at_[i]).norm() + std::abs(w.yaws()[i] - yaw_at_[i]) * w.reach(i);
    most = std::max(most, d);
  }
  return most;
}

void DistributedWorld::step(double dt) {
  // (renewed before the step rather than after the last: the World then keeps its last evaluation's contacts and
  // report for whoever reads them between steps)
  if (renew_due_) {
    renew();
    renew_due_ = false;
  }
  const auto t_step = std::chrono::steady_clock::now();
  const double waited = halo_->seconds();
  world_->step(dt);
  const double busy =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - t_step).count() - (halo_->seconds() - waited);
  busy_ += busy;
  busy_total_ += busy;
  ++busy_steps_;
  if (ranks() == 1) return;  // no halo to renew
  const auto t0 = std::chrono::steady_clock::now();
  const double mine = moved();
  double most = 0.0;
  MPI_Allreduce(&mine, &most, 1, MPI_DOUBLE, MPI_MAX, comm_);
  retired_.check_seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  if (most > 0.5 * margin_)
    throw CollectiveError("a floe moved " + std::to_string(most) + " m since the ranks last exchanged their floes (" +
                          std::to_string(renewals_) + " renewals, step " + std::to_string(world_->step_count()) +
                          "): more than half the halo's margin, " + std::to_string(margin_) +
                          " m, so contacts across ranks may have been missed. The time step is far too large.");
  renew_due_ = most > 0.25 * margin_;
  // (every rank has taken as many steps since the last measurement: the ranks meet in this collective together)
  if (!renew_due_ && busy_steps_ % kLoadCheck == 0)
    renew_due_ = rebalance_now_ = rebalance_due(measured_load(comm_, busy_));
}

bool DistributedWorld::rebalance_due(const Load& load) {
  if (load.uneven(kImbalance) && load.largest - load.mean > rebalance_cost_) return true;
  if (busy_steps_ >= kLoadWindow) {  // a window no longer: the load of long ago no longer counts, and the cost of
    start_load_window();             // the last rebalance counts half (one slow rebalance does not bar the next
    rebalance_cost_ *= 0.5;          // for good)
  }
  return false;
}

void DistributedWorld::start_load_window() {
  busy_ = 0.0;
  busy_steps_ = 0;
}

void DistributedWorld::count_sent(const std::vector<std::vector<unsigned char>>& out) {
  for (std::size_t q = 0; q < out.size(); ++q)
    if (static_cast<int>(q) != rank()) retired_.renewal_bytes += out[q].size();
}

DistributedWorld::Communication DistributedWorld::communication() const {
  Communication c = retired_;
  c.busy_seconds = busy_total_;
  c.halo_bytes += halo_->bytes_sent();
  c.halo_messages += halo_->messages_sent();
  c.halo_seconds += halo_->seconds();
  return c;
}

void DistributedWorld::renew() {
  const auto t0 = std::chrono::steady_clock::now();
  const dynamics::World& w = *world_;
  const dynamics::WorldState s = w.state();  // rows in id order, owned floes and ghosts
  std::vector<int> own_rows;
  std::vector<PartitionItem> items;
  for (std::size_t k = 0; k < s.ids.size(); ++k)
    if (!w.is_ghost(w.index_of(s.ids[k]))) {
      own_rows.push_back(static_cast<int>(k));
      items.push_back({s.ids[k], s.position[k], 1.0});
    }
  // Each floe to the rank of its region, with the histories of the pairs it evaluates (those of which it has the
  // lower id); the regions cut anew first where the ranks' measured loads call for it, each floe weighted by its
  // measured cost. (busy_steps_ is alike on every rank: the steps are collective.)
  const bool rebalance = rebalance_now_ || (busy_steps_ >= kLoadSample && rebalance_due(measured_load(comm_, busy_)));
  rebalance_now_ = false;
  std::vector<int> to;
  if (rebalance) {
    std::unordered_map<BodyId, std::size_t> item_of;
    for (std::size_t k = 0; k < items.size(); ++k) item_of[items[k].id] = k;
    std::vector<int> pairs(items.size(), 0);
    for (const contact::ContactCache::Entry& e : s.contact_history) {
      const auto it = item_of.find(e.first.lo);
      if (it != item_of.end()) ++pairs[it->second];
    }
    weigh_by_cost(items, pairs, busy_);
    start_load_window();
    to = partition_.balance(items);
    ++rebalances_;
  } else {
    for (const PartitionItem& it : items) to.push_back(partition_.rank_of(it.position));
  }
  const auto ranks_n = static_cast<std::size_t>(ranks());
  std::vector<std::vector<int>> rows_to(ranks_n);
  std::unordered_map<BodyId, int> dest;
  for (std::size_t j = 0; j < own_rows.size(); ++j) {
    rows_to[static_cast<std::size_t>(to[j])].push_back(own_rows[j]);
    dest[s.ids[static_cast<std::size_t>(own_rows[j])]] = to[j];
  }
  std::vector<std::vector<const contact::ContactCache::Entry*>> history_to(ranks_n);
  for (const contact::ContactCache::Entry& e : s.contact_history)
    history_to[static_cast<std::size_t>(dest.at(e.first.lo))].push_back(&e);
  std::vector<Bytes> out(ranks_n);
  for (std::size_t q = 0; q < ranks_n; ++q) pack(s, rows_to[q], history_to[q], out[q]);
  dynamics::WorldState owned = scalars_of(s);
  count_sent(out);
  const std::vector<Bytes> in = all_to_all(comm_, out);
  for (std::size_t q = 0; q < ranks_n; ++q) {
    const std::size_t before = owned.ids.size();
    unpack(in[q], owned);
    if (static_cast<int>(q) != rank()) migrated_ += owned.ids.size() - before;
  }
  // The ghosts for the floes now owned, and their rows from their owners.
  std::vector<HaloItem> mine;
  std::unordered_map<BodyId, int> row_of;
  for (std::size_t k = 0; k < owned.ids.size(); ++k) {
    const geometry::ConvexPolygon& shape = *bodies_[desc_of_.at(owned.ids[k])].shape;
    mine.push_back({owned.ids[k], box_of(shape, owned.position[k], owned.yaw[k])});
    row_of[owned.ids[k]] = static_cast<int>(k);
  }
  const HaloLayout layout = halo_layout(comm_, mine, margin_);
  for (std::size_t q = 0; q < ranks_n; ++q) {
    out[q].clear();
    std::vector<int> rows;
    for (const BodyId id : layout.send[q]) rows.push_back(row_of.at(id));
    pack(owned, rows, {}, out[q]);
  }
  dynamics::WorldState full = owned;
  count_sent(out);
  for (const Bytes& m : all_to_all(comm_, out)) unpack(m, full);
  if (bonds_) collect_bonds(-1, nullptr);  // every face's state, for the faces each rank now holds
  std::vector<BodyId> owned_ids = owned.ids;
  build(owned_ids, layout, &full);
  ++renewals_;
  const double took = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  retired_.renewal_seconds += took;
  if (rebalance) MPI_Allreduce(&took, &rebalance_cost_, 1, MPI_DOUBLE, MPI_MAX, comm_);
}

}  // namespace polyfloe::domain
