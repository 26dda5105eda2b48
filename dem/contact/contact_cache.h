// The contact history: values a contact law keeps per touching pair from one step to the next (LAMMPS's
// size_history), keyed by the stable ids of the two bodies (lower id first). No fixed slots per body: any number
// of contacts per floe. Entries of pairs that stopped touching are dropped at the end of the step in which they
// were not refreshed. The value type declares what is kept: PlanarHistory for the planar world, the 3-D spring for
// the spatial one. A new pair gets a value-initialised Value (zeros for numbers and aggregates of them; an Eigen
// vector's is not: look at `found`).
#pragma once

#include <algorithm>
#include <cstdint>
#include <span>
#include <utility>
#include <vector>

namespace polyfloe::contact {

struct PairKey {
  std::uint64_t lo = 0, hi = 0;
  bool operator==(const PairKey&) const = default;
};
PairKey make_key(std::uint64_t a, std::uint64_t b);

struct PairKeyHash {
  std::size_t operator()(const PairKey& k) const noexcept {
    std::uint64_t h = k.lo * 0x9E3779B97F4A7C15ull ^ (k.hi + 0x632BE59BD9B4E019ull + (k.lo << 6) + (k.lo >> 2));
    h ^= h >> 31;
    return static_cast<std::size_t>(h * 0xBF58476D1CE4E5B9ull);
  }
};

// What the planar contact law keeps per pair.
struct PlanarHistory {
  double spring = 0.0;  // tangential spring s [m] (Coulomb-capped)
  // The pair's normal force at the end of the last step [N] (the foundation model's damping solves for the
  // end-of-step approach rate with it); NaN where not known (a checkpoint written before it was kept).
  double normal_force = 0.0;
  bool operator==(const PlanarHistory&) const = default;
};

template <class Value>
class HistoryStore {
 public:
  using Entry = std::pair<PairKey, Value>;
  // Value stored for this pair by the previous step, or Value{} for a new contact. The index these look pairs up
  // by is rebuilt on the first lookup after a step (end_step, restore): not safe from several threads at once
  // unless prepare_lookups() was called since.
  Value previous(const PairKey& k) const {
    std::size_t hint = prev_.size();
    return previous(k, hint);
  }
  // The same, first trying the entry at `hint` and leaving `hint` just past the entry found: pairs come in nearly
  // the same order every step, so a loop that passes one hint along reads the store in order, without hashing.
  // `found` (optional): whether the pair was stored by the previous step (in contact then).
  Value previous(const PairKey& k, std::size_t& hint, bool* found = nullptr) const {
    if (found) *found = true;
    if (hint < prev_.size() && prev_[hint].first == k) return prev_[hint++].second;
    const std::int32_t i = find(k);
    if (found) *found = i >= 0;
    if (i < 0) return Value{};
    hint = static_cast<std::size_t>(i) + 1;
    return prev_[static_cast<std::size_t>(i)].second;
  }
  void prepare_lookups() const {
    if (index_stale_) rebuild_index();
  }
  // The value of the previous step's i-th store (the i-th place of its store_slots, or its i-th store()): for a
  // caller that kept where it stored each pair, with the generation() it stored them under, and needs no lookup.
  const Value& stored(std::size_t i) const { return prev_[i].second; }
  // Counts the steps (end_step) and restores: the previous step's stores are those made while it was one less.
  std::uint64_t generation() const { return generation_; }
  // Record this step's value; the pair survives into the next step. Each pair is stored at most once a step.
  void store(const PairKey& k, const Value& v) {
    if (cur_count_ < cur_.size())
      cur_[cur_count_] = {k, v};
    else
      cur_.emplace_back(k, v);
    ++cur_count_;
  }
  // Or, for a parallel loop: room for this step's `count` stores, each then written at its own place (the order of
  // the places is the order of the stores). Replaces whatever was stored this step; the room is not cleared.
  std::span<Entry> store_slots(std::size_t count) {
    if (cur_.size() < count) cur_.resize(count);
    cur_count_ = count;
    return {cur_.data(), count};
  }
  // Called once per step after all stores: this step's entries become the previous ones.
  void end_step() {
    cur_.resize(cur_count_);  // shrinks: no writes
    prev_.swap(cur_);
    cur_count_ = 0;
    index_stale_ = true;
    ++generation_;
  }
  std::size_t size() const { return prev_.size(); }
  // Entries in a deterministic order (by key: for checkpoints and tests).
  std::vector<Entry> entries() const {
    std::vector<Entry> out(prev_.begin(), prev_.end());
    sort_by_key(out);
    return out;
  }
  // Entries in the order entries() lists them: by key (lo, then hi).
  static void sort_by_key(std::vector<Entry>& v) {
    std::sort(v.begin(), v.end(), [](const Entry& x, const Entry& y) {
      return x.first.lo != y.first.lo ? x.first.lo < y.first.lo : x.first.hi < y.first.hi;
    });
  }
  void restore(const std::vector<Entry>& entries) {
    prev_ = entries;
    cur_.clear();
    cur_count_ = 0;
    index_stale_ = true;
    ++generation_;
  }

 private:
  // Position of k in prev_, or -1.
  std::int32_t find(const PairKey& k) const {
    prepare_lookups();
    if (index_.empty()) return -1;
    const std::size_t mask = index_.size() - 1;
    for (std::size_t h = PairKeyHash{}(k)&mask;; h = (h + 1) & mask) {
      const std::int32_t i = index_[h];
      if (i < 0 || prev_[static_cast<std::size_t>(i)].first == k) return i;
    }
  }
  void rebuild_index() const {
    index_stale_ = false;
    std::size_t cap = 16;
    while (cap < 2 * prev_.size()) cap *= 2;
    index_.assign(cap, -1);
    const std::size_t mask = cap - 1;
    for (std::size_t i = 0; i < prev_.size(); ++i) {
      std::size_t h = PairKeyHash{}(prev_[i].first) & mask;
      while (index_[h] >= 0) h = (h + 1) & mask;
      index_[h] = static_cast<std::int32_t>(i);
    }
  }
  // This step's stores, appended in order (no hashing on the hot path), and last step's entries with an
  // open-addressing index (linear probing, power-of-two size, at most half full), built when first needed. No
  // allocation once warm.
  // cur_ keeps the storage of the step before last as room (no clearing, no allocation): its first cur_count_
  // entries are this step's.
  std::vector<Entry> cur_, prev_;
  std::size_t cur_count_ = 0;
  mutable std::vector<std::int32_t> index_;  // position in prev_, -1 = empty
  mutable bool index_stale_ = false;
  std::uint64_t generation_ = 0;
};

// The planar world's contact history.
using ContactCache = HistoryStore<PlanarHistory>;

}  // namespace polyfloe::contact
