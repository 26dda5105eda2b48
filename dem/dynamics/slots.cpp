// The order of the contact stage's slots (dynamics/slots.h).
#include "dynamics/slots.h"

#include <algorithm>

namespace polyfloe::dynamics {

namespace {

bool slot_less(const SlotKey& a, const SlotKey& b) { return a.key != b.key ? a.key < b.key : a.id < b.id; }

}  // namespace

const std::vector<std::pair<int, int>>& SlotOrder::sort(bool keys_changed) {
  const int n = static_cast<int>(slots_.size());
  moved_.clear();
  if (!keys_changed) return moved_;  // sorted by (key, id) as before: nothing moves (most steps)
  // Insertion sort from the last order. Each move permutes the slots of an interval among themselves; overlapping
  // intervals are merged, so that each recorded interval holds the same bodies as before.
  std::size_t moves = 0;
  const std::size_t budget = 8 * static_cast<std::size_t>(n) + 64;
  for (int k = 1; k < n && moves <= budget; ++k) {
    if (!slot_less(slots_[k], slots_[k - 1])) continue;
    const SlotKey x = slots_[k];
    int j = k;
    for (; j > 0 && slot_less(x, slots_[j - 1]); --j) slots_[j] = slots_[j - 1];
    slots_[j] = x;
    moves += static_cast<std::size_t>(k - j);
    int first = j;
    while (!moved_.empty() && moved_.back().second >= first) {
      first = std::min(first, moved_.back().first);
      moved_.pop_back();
    }
    moved_.emplace_back(first, k);
  }
  if (moves > budget) {
    std::sort(slots_.begin(), slots_.end(), slot_less);
    moved_.assign(1, {0, n - 1});
  }
  for (const auto& [first, last] : moved_)
    for (int k = first; k <= last; ++k) body_slot_[static_cast<std::size_t>(slots_[k].body)] = k;
  return moved_;
}

}  // namespace polyfloe::dynamics
