#include "contact/contact_cache.h"

#include <algorithm>

namespace polyfloe::contact {

PairKey make_key(std::uint64_t a, std::uint64_t b) { return a < b ? PairKey{a, b} : PairKey{b, a}; }

double ContactCache::previous(const PairKey& k) const {
  const auto it = prev_.find(k);
  return it == prev_.end() ? 0.0 : it->second;
}

void ContactCache::store(const PairKey& k, double spring) { cur_[k] = spring; }

void ContactCache::end_step() {
  prev_.swap(cur_);
  cur_.clear();
}

std::vector<std::pair<PairKey, double>> ContactCache::entries() const {
  std::vector<std::pair<PairKey, double>> out(prev_.begin(), prev_.end());
  std::sort(out.begin(), out.end(), [](const auto& x, const auto& y) {
    return x.first.lo != y.first.lo ? x.first.lo < y.first.lo : x.first.hi < y.first.hi;
  });
  return out;
}

void ContactCache::restore(const std::vector<std::pair<PairKey, double>>& entries) {
  prev_.clear();
  cur_.clear();
  for (const auto& [k, v] : entries) prev_[k] = v;
}

}  // namespace polyfloe::contact
