// Tangential-spring history per contact, keyed by the stable ids of the two bodies (lower id first).
// No fixed slots per body: any number of contacts per floe. Entries of pairs that stopped touching are dropped
// at the end of the step in which they were not refreshed.
#pragma once

#include <cstdint>
#include <span>
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

class ContactCache {
 public:
  // Spring value stored for this pair by the previous step, or 0 for a new contact. The index these look pairs up
  // by is rebuilt on the first lookup after a step (end_step, restore): not safe from several threads at once
  // unless prepare_lookups() was called since.
  double previous(const PairKey& k) const;
  // The same, first trying the entry at `hint` and leaving `hint` just past the entry found: pairs come in nearly
  // the same order every step, so a loop that passes one hint along reads the store in order, without hashing.
  // `found` (optional): whether the pair was stored by the previous step (in contact then).
  double previous(const PairKey& k, std::size_t& hint, bool* found = nullptr) const;
  void prepare_lookups() const {
    if (index_stale_) rebuild_index();
  }
  // The value of the previous step's i-th store (the i-th place of its store_slots, or its i-th store()): for a
  // caller that kept where it stored each pair, with the generation() it stored them under, and needs no lookup.
  double stored(std::size_t i) const { return prev_[i].second; }
  // Counts the steps (end_step) and restores: the previous step's stores are those made while it was one less.
  std::uint64_t generation() const { return generation_; }
  // Record this step's value; the pair survives into the next step. Each pair is stored at most once a step.
  void store(const PairKey& k, double spring) {
    if (cur_count_ < cur_.size()) cur_[cur_count_] = {k, spring};
    else cur_.emplace_back(k, spring);
    ++cur_count_;
  }
  // Or, for a parallel loop: room for this step's `count` stores, each then written at its own place (the order of
  // the places is the order of the stores). Replaces whatever was stored this step; the room is not cleared.
  std::span<std::pair<PairKey, double>> store_slots(std::size_t count) {
    if (cur_.size() < count) cur_.resize(count);
    cur_count_ = count;
    return {cur_.data(), count};
  }
  // Called once per step after all stores: this step's entries become the previous ones.
  void end_step();
  std::size_t size() const { return prev_.size(); }
  // Entries in a deterministic order (for checkpoints and tests).
  std::vector<std::pair<PairKey, double>> entries() const;
  void restore(const std::vector<std::pair<PairKey, double>>& entries);

 private:
  void rebuild_index() const;
  // This step's stores, appended in order (no hashing on the hot path), and last step's entries with an
  // open-addressing index (linear probing, power-of-two size, at most half full), built when first needed. No
  // allocation once warm.
  // cur_ keeps the storage of the step before last as room (no clearing, no allocation): its first cur_count_
  // entries are this step's.
  std::vector<std::pair<PairKey, double>> cur_, prev_;
  std::size_t cur_count_ = 0;
  mutable std::vector<std::int32_t> index_;  // position in prev_, -1 = empty
  mutable bool index_stale_ = false;
  std::uint64_t generation_ = 0;
};

}  // namespace polyfloe::contact
