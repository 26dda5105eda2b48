// The order of the contact stage's slots (dynamics/slots.h SlotOrder) on its own: after any motion the slots are
// sorted by (key, id) exactly as a full sort would (ids here run against the indices, so a tie by index would fail), slot_of and body_at are inverse, and the intervals the sort
// reports cover every slot that changed body, each holding the same bodies as before; no changed key, no sort.
#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <set>
#include <vector>

#include "dynamics/slots.h"
#include "geometry/space_order.h"

using namespace polyfloe;
using dynamics::SlotKey;
using dynamics::SlotOrder;
using geometry::Vec2;

namespace {

constexpr double kCell = 4.0;  // [m]

// Body i's id: decreasing in i, so that the order by id is not the order by index.
dynamics::BodyId id_of(int i) { return static_cast<dynamics::BodyId>(3 * (10000 - i)); }

// Keys at `pos`, then sorted; checks the order and the intervals against the slots before.
std::vector<std::pair<int, int>> moved;  // what the last sort_and_check's sort reported

void sort_and_check(SlotOrder& order, const std::vector<Vec2>& pos, bool expect_change) {
  const int n = static_cast<int>(pos.size());
  const std::vector<SlotKey> before = order.slots();
  bool changed = false;
  for (int i = 0; i < n; ++i) changed = order.set_key(i, pos[static_cast<std::size_t>(i)]) || changed;
  ASSERT_EQ(changed, expect_change);
  moved = order.sort(changed);
  // The order a full sort gives.
  std::vector<SlotKey> want(static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i)
    want[static_cast<std::size_t>(i)] = {geometry::space_key(pos[static_cast<std::size_t>(i)], kCell), id_of(i), i};
  std::sort(want.begin(), want.end(),
            [](const SlotKey& a, const SlotKey& b) { return a.key != b.key ? a.key < b.key : a.id < b.id; });
  for (int k = 0; k < n; ++k) {
    ASSERT_EQ(order.body_at(k), want[static_cast<std::size_t>(k)].body) << "slot " << k;
    ASSERT_EQ(order.slot_of(order.body_at(k)), k);
  }
  // Intervals: increasing, disjoint, each the same bodies as before; outside them no slot changed body.
  std::vector<char> inside(static_cast<std::size_t>(n), 0);
  int last = -1;
  for (const auto& [first, end] : moved) {
    ASSERT_GT(first, last);
    ASSERT_LE(first, end);
    last = end;
    std::multiset<int> was, is;
    for (int k = first; k <= end; ++k) {
      was.insert(before[static_cast<std::size_t>(k)].body);
      is.insert(order.body_at(k));
      inside[static_cast<std::size_t>(k)] = 1;
    }
    ASSERT_EQ(was, is) << "interval [" << first << ", " << end << "]";
  }
  for (int k = 0; k < n; ++k) {
    if (!inside[static_cast<std::size_t>(k)]) {
      ASSERT_EQ(order.body_at(k), before[static_cast<std::size_t>(k)].body);
    }
  }
}

}  // namespace

TEST(SlotOrder, SlotsFollowTheBodiesAsTheyMoveInTheOrderAFullSortGives) {
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(0.0, 200.0), jitter(-1.5, 1.5);
  const int n = 500;
  SlotOrder order;
  order.set_cell(kCell);
  std::vector<Vec2> pos;
  for (int i = 0; i < n; ++i) {
    order.add(i, id_of(i));
    pos.emplace_back(u(rng), u(rng));
  }
  sort_and_check(order, pos, true);  // the first sort: every key new
  for (int step = 0; step < 40; ++step) {
    for (Vec2& p : pos) p += Vec2{jitter(rng), jitter(rng)};
    sort_and_check(order, pos, true);
    if (HasFatalFailure()) return;
  }
  sort_and_check(order, pos, false);  // nobody moved: no key changed
}

TEST(SlotOrder, ABodyCrossingTheFieldMovesOneIntervalAndAReversalSortsAllAtOnce) {
  const int n = 300;
  SlotOrder order;
  order.set_cell(kCell);
  std::vector<Vec2> pos;
  for (int i = 0; i < n; ++i) {
    order.add(i, id_of(i));
    pos.emplace_back(8.0 * (i % 30) + 1.0, 8.0 * (i / 30) + 1.0);  // a lattice, one body per cell
  }
  sort_and_check(order, pos, true);
  // One body from the first cell to the far corner: one interval, from its old slot to its new one.
  pos[0] = {8.0 * 29 + 5.0, 8.0 * 9 + 5.0};
  sort_and_check(order, pos, true);
  ASSERT_EQ(moved.size(), 1u);
  EXPECT_EQ(moved[0].first, 0);
  // Every body to its mirror image: past the insertion budget, one full sort, reported as one interval.
  for (Vec2& p : pos) p = Vec2{240.0, 80.0} - p;
  bool changed = false;
  for (int i = 0; i < n; ++i) changed = order.set_key(i, pos[static_cast<std::size_t>(i)]) || changed;
  const std::vector<std::pair<int, int>> all = order.sort(changed);
  ASSERT_EQ(all.size(), 1u);
  EXPECT_EQ(all[0], (std::pair<int, int>{0, n - 1}));
  for (int k = 1; k < n; ++k)
    EXPECT_LE(order.slots()[static_cast<std::size_t>(k - 1)].key, order.slots()[static_cast<std::size_t>(k)].key);
}
