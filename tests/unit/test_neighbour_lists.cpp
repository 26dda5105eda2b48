// The planar World's neighbour lists alone (dynamics/neighbour_lists.h): the candidate pairs they give are the pairs
// a fresh scan of the boxes gives, in slot order, while bodies move, rotate and change slots; the lists are
// rebuilt exactly when a body has moved more than half the skin.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <set>
#include <utility>
#include <vector>

#include "contact/narrow_phase_planar.h"
#include "dynamics/neighbour_lists.h"

namespace {

using polyfloe::dynamics::NeighbourLists;
using polyfloe::dynamics::SlotKey;
using polyfloe::dynamics::SlotStatic;
using polyfloe::dynamics::SlotView;
using polyfloe::geometry::Aabb;
using polyfloe::geometry::Vec2;
using Pairs = std::set<std::pair<int, int>>;

// Squares of half side 1 m on a jittered lattice (spacing 2.3 m: many near misses), the slots in body order.
struct Field {
  int n = 0;
  std::vector<Vec2> pos;
  std::vector<double> yaw, reach;
  std::vector<SlotKey> slots;
  std::vector<int> body_slot;
  std::vector<SlotStatic> statics;
  std::vector<Aabb> boxes;
  std::vector<std::uint8_t> dynamic;       // by body
  std::vector<std::uint8_t> slot_dynamic;  // by slot
  std::vector<Vec2> world_xy;

  explicit Field(int side, std::mt19937& rng) : n(side * side) {
    std::uniform_real_distribution<double> jitter(-0.3, 0.3);
    for (int i = 0; i < n; ++i) {
      pos.emplace_back(2.3 * (i % side) + jitter(rng), 2.3 * (i / side) + jitter(rng));
      yaw.push_back(jitter(rng));
      reach.push_back(std::sqrt(2.0));
      slots.push_back({0, static_cast<polyfloe::dynamics::BodyId>(i + 1), i});
      body_slot.push_back(i);
      SlotStatic s;
      s.mass = s.radius = s.equivalent_radius = 1.0;
      s.id = static_cast<polyfloe::dynamics::BodyId>(i + 1);
      s.body = i;
      s.vert_begin = 4 * i;
      s.vert_count = 4;
      statics.push_back(s);
      dynamic.push_back(i % 7 == 3 ? 0 : 1);  // some walls: a pair of two is never a candidate
    }
    world_xy.resize(4 * static_cast<std::size_t>(n));
    boxes.resize(static_cast<std::size_t>(n));
    slot_dynamic.resize(static_cast<std::size_t>(n));
    update();
  }
  // World-frame vertices (slot order) and boxes from the poses.
  void update() {
    const Vec2 corners[4] = {{-1, -1}, {1, -1}, {1, 1}, {-1, 1}};
    for (int k = 0; k < n; ++k) {
      const int i = slots[k].body;
      statics[k].body = i;
      statics[k].id = static_cast<polyfloe::dynamics::BodyId>(i + 1);
      statics[k].vert_begin = 4 * k;
      slot_dynamic[k] = dynamic[i];
      const double c = std::cos(yaw[i]), s = std::sin(yaw[i]);
      Aabb box{{1e300, 1e300}, {-1e300, -1e300}};
      for (int v = 0; v < 4; ++v) {
        const Vec2 w = pos[i] + Vec2{c * corners[v].x() - s * corners[v].y(), s * corners[v].x() + c * corners[v].y()};
        world_xy[4 * k + v] = w;
        box.lo = box.lo.cwiseMin(w);
        box.hi = box.hi.cwiseMax(w);
      }
      boxes[k] = box;
    }
  }
  SlotView view() const { return {slots, body_slot, statics, boxes, slot_dynamic, world_xy, pos, yaw, reach}; }
  // Every slot pair whose boxes overlap, one of them dynamic.
  Pairs box_pairs() const {
    Pairs out;
    for (int a = 0; a < n; ++a)
      for (int b = a + 1; b < n; ++b)
        if ((dynamic[slots[a].body] || dynamic[slots[b].body]) && boxes[a].overlaps(boxes[b])) out.insert({a, b});
    return out;
  }
  bool touching(int a, int b) const {
    polyfloe::contact::PlanarContact g;
    return polyfloe::contact::planar_overlap({world_xy.data() + 4 * a, 4}, {world_xy.data() + 4 * b, 4}, g);
  }
};

// The candidate pairs as a set, checked sorted by (a, b) with a < b and each list entry valid.
Pairs candidates(NeighbourLists& lists, const Field& f, const polyfloe::contact::ContactLaw& law, bool exact) {
  std::vector<polyfloe::contact::CandidatePair> pairs;
  lists.candidate_pairs(f.view(), law, exact, 1, pairs);
  Pairs out;
  for (std::size_t u = 0; u < pairs.size(); ++u) {
    EXPECT_LT(pairs[u].a, pairs[u].b);
    EXPECT_GE(pairs[u].entry, 0);
    if (u > 0) {
      EXPECT_TRUE(std::make_pair(pairs[u - 1].a, pairs[u - 1].b) < std::make_pair(pairs[u].a, pairs[u].b));
    }
    out.insert({pairs[u].a, pairs[u].b});
  }
  return out;
}

TEST(NeighbourLists, GiveTheBoxPairsOfAFreshScanWhileBodiesMove) {
  std::mt19937 rng(7);
  Field f(12, rng);
  const polyfloe::contact::ContactLaw law{polyfloe::contact::ContactLawSettings{}};
  NeighbourLists lists(0.0);
  lists.set_skin(0.4);
  std::normal_distribution<double> step(0.0, 0.02);  // [m], [rad] per step: a build every few steps
  std::uint64_t builds_seen = 0;
  for (int s = 0; s < 60; ++s) {
    // Half the steps as the World's kick does it (every body's within() and the verdict), half without.
    if (s % 2 == 0 && lists.built_for(f.pos.size())) {
      bool outrun = false;
      for (int i = 0; i < f.n; ++i) outrun = !lists.within(i, f.pos[i], f.yaw[i], f.reach[i]) || outrun;
      lists.set_kick_verdict(outrun);
    }
    const std::uint64_t before = lists.builds();
    ASSERT_EQ(candidates(lists, f, law, false), f.box_pairs()) << "step " << s;
    EXPECT_EQ(lists.fresh(), lists.builds() != before);
    builds_seen += lists.builds() - before;
    for (int i = 0; i < f.n; ++i) {
      if (!f.dynamic[i]) continue;
      f.pos[i] += Vec2{step(rng), step(rng)};
      f.yaw[i] += step(rng);
    }
    f.update();
  }
  // Rebuilt only when needed: at most once per step, and far fewer than that at these speeds.
  EXPECT_GE(builds_seen, 2u);
  EXPECT_LE(builds_seen, 30u);
}

TEST(NeighbourLists, SkipOnlyPairsThatCannotTouch) {
  // With the exact narrow phase's distances, a pair may leave the candidates only if its polygons do not overlap.
  std::mt19937 rng(11);
  Field f(10, rng);
  const polyfloe::contact::ContactLaw law{polyfloe::contact::ContactLawSettings{}};
  NeighbourLists lists(0.0);
  lists.set_skin(0.5);
  std::normal_distribution<double> step(0.0, 0.03);
  std::size_t skipped = 0;
  for (int s = 0; s < 40; ++s) {
    const Pairs got = candidates(lists, f, law, true), boxes = f.box_pairs();
    for (const auto& p : got) EXPECT_TRUE(boxes.count(p)) << p.first << " " << p.second;
    for (const auto& p : boxes)
      if (!got.count(p)) {
        ++skipped;
        EXPECT_FALSE(f.touching(p.first, p.second)) << "step " << s << ": " << p.first << " " << p.second;
      }
    for (int i = 0; i < f.n; ++i)
      if (f.dynamic[i]) f.pos[i] += Vec2{step(rng), step(rng)};
    f.update();
  }
  EXPECT_GT(skipped, 0u);  // the filter does something on this field
}

TEST(NeighbourLists, KeepTheSlotOrderWhenSlotsChangeBodies) {
  std::mt19937 rng(3);
  Field f(8, rng);
  const polyfloe::contact::ContactLaw law{polyfloe::contact::ContactLawSettings{}};
  NeighbourLists lists(0.0);
  lists.set_skin(1.0);
  candidates(lists, f, law, false);
  ASSERT_EQ(lists.builds(), 1u);
  // Swap bodies between slots, as a re-sort of the slots does, without moving any body: the lists stand.
  for (int k = 0; k + 1 < f.n; k += 5) {
    std::swap(f.slots[k], f.slots[k + 1]);
    f.body_slot[f.slots[k].body] = k;
    f.body_slot[f.slots[k + 1].body] = k + 1;
  }
  f.update();
  lists.note_slots_moved();
  EXPECT_EQ(candidates(lists, f, law, false), f.box_pairs());
  EXPECT_EQ(lists.builds(), 1u);
  // Forgotten lists are built at the next call.
  lists.invalidate();
  EXPECT_FALSE(lists.built_for(f.pos.size()));
  EXPECT_EQ(candidates(lists, f, law, false), f.box_pairs());
  EXPECT_EQ(lists.builds(), 2u);
}

TEST(NeighbourLists, RebuildExactlyWhenABodyOutrunsHalfTheSkin) {
  std::mt19937 rng(5);
  Field f(6, rng);
  const polyfloe::contact::ContactLaw law{polyfloe::contact::ContactLawSettings{}};
  NeighbourLists lists(0.0);
  lists.set_skin(0.4);
  candidates(lists, f, law, false);
  ASSERT_EQ(lists.builds(), 1u);
  f.pos[0] += Vec2{0.19, 0.0};  // within half the skin (0.2 m)
  f.update();
  candidates(lists, f, law, false);
  EXPECT_EQ(lists.builds(), 1u);
  f.pos[0] += Vec2{0.02, 0.0};  // 0.21 m since the build
  f.update();
  EXPECT_EQ(candidates(lists, f, law, false), f.box_pairs());
  EXPECT_EQ(lists.builds(), 2u);
  f.yaw[0] += 0.15;  // a vertex at sqrt(2) m moves up to 0.21 m
  f.update();
  candidates(lists, f, law, false);
  EXPECT_EQ(lists.builds(), 3u);
  f.pos[1] = Vec2{std::nan(""), 0.0};  // a non-finite pose counts as outrun
  candidates(lists, f, law, false);
  EXPECT_EQ(lists.builds(), 4u);
}

}  // namespace
