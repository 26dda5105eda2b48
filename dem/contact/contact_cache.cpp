#include "contact/contact_cache.h"

#include <algorithm>

namespace polyfloe::contact {

PairKey make_key(std::uint64_t a, std::uint64_t b) { return a < b ? PairKey{a, b} : PairKey{b, a}; }

double ContactCache::previous(const PairKey& k) const {
  std::size_t hint = prev_.size();
  return previous(k, hint);
}

double ContactCache::previous(const PairKey& k, std::size_t& hint, bool* found) const {
  if (found) *found = true;
  if (hint < prev_.size() && prev_[hint].first == k) return prev_[hint++].second;
  prepare_lookups();
  if (found) *found = false;
  if (index_.empty()) return 0.0;
  const std::size_t mask = index_.size() - 1;
  for (std::size_t h = PairKeyHash{}(k) & mask;; h = (h + 1) & mask) {
    const std::int32_t i = index_[h];
    if (i < 0) return 0.0;
    if (prev_[static_cast<std::size_t>(i)].first == k) {
      hint = static_cast<std::size_t>(i) + 1;
      if (found) *found = true;
      return prev_[static_cast<std::size_t>(i)].second;
    }
  }
}

void ContactCache::rebuild_index() const {
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

void ContactCache::end_step() {
  cur_.resize(cur_count_);  // shrinks: no writes
  prev_.swap(cur_);
  cur_count_ = 0;
  index_stale_ = true;
  ++generation_;
}

std::vector<std::pair<PairKey, double>> ContactCache::entries() const {
  std::vector<std::pair<PairKey, double>> out(prev_.begin(), prev_.end());
  std::sort(out.begin(), out.end(), [](const auto& x, const auto& y) {
    return x.first.lo != y.first.lo ? x.first.lo < y.first.lo : x.first.hi < y.first.hi;
  });
  return out;
}

void ContactCache::restore(const std::vector<std::pair<PairKey, double>>& entries) {
  prev_ = entries;
  cur_.clear();
  cur_count_ = 0;
  index_stale_ = true;
  ++generation_;
}

}  // namespace polyfloe::contact
