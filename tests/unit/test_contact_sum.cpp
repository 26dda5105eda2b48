// The contact sum (dynamics/contact_sum.h) on its own: random pair results over random slots summed on 1, 2, 3 and
// 7 threads give the bits of one plain loop over the pairs in pair order — the slots' forces and torques, the
// contact history stored, the counts, the deepest overlap and the shortest contact.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <random>
#include <vector>

#include "dynamics/contact_sum.h"

using namespace polyfloe;
using dynamics::ContactSum;
using dynamics::PairResult;
using geometry::Vec2;

namespace {

struct Case {
  std::vector<dynamics::SlotStatic> statics;
  std::vector<contact::CandidatePair> pairs;
  std::vector<PairResult> results;
  std::vector<std::uint8_t> hit;
};

Case random_case(int slots, int pair_count, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::uniform_int_distribution<int> slot(0, slots - 1);
  Case c;
  for (int k = 0; k < slots; ++k) {
    dynamics::SlotStatic s;
    s.id = static_cast<dynamics::BodyId>(5000 - 7 * k);
    s.body = (k * 37) % slots;
    s.equivalent_radius = 2.0 + u(rng);
    c.statics.push_back(s);
  }
  for (int p = 0; p < pair_count; ++p) {
    int a = slot(rng), b = slot(rng);
    if (a == b) continue;
    if (a > b) std::swap(a, b);
    c.pairs.push_back({a, b, -1});
  }
  std::sort(c.pairs.begin(), c.pairs.end(),
            [](const auto& x, const auto& y) { return x.a != y.a ? x.a < y.a : x.b < y.b; });
  for (const contact::CandidatePair& p : c.pairs) {
    PairResult r;
    r.hit = u(rng) > -0.4;  // 70 %
    r.fallback = u(rng) > 0.9;
    r.reused = r.hit && u(rng) > 0.0;
    // ordered by id: the lower id first (ids fall with the slot)
    r.a = p.b;
    r.b = p.a;
    r.f = {1e3 * u(rng), 1e3 * u(rng)};
    r.tau_a = 1e4 * u(rng);
    r.tau_b = 1e4 * u(rng);
    r.g.depth = 0.5 * (1.0 + u(rng));
    r.v2 = 1.0 + u(rng);
    r.q2 = std::exp(10.0 * u(rng));
    r.cf.spring = 1e-3 * u(rng);
    r.cf.normal = 1e3 * (1.0 + u(rng));
    c.results.push_back(r);
    c.hit.push_back(r.hit ? 1 : 0);
  }
  return c;
}

}  // namespace

TEST(ContactSum, AnyThreadCountGivesThePlainLoopsBitsInPairOrder) {
  const Case c = random_case(300, 1500, 17);
  const int n = static_cast<int>(c.statics.size());
  // The plain loop: every hit pair in pair order.
  std::vector<Vec2> force(static_cast<std::size_t>(n), Vec2{0.0, 0.0});
  std::vector<double> torque(static_cast<std::size_t>(n), 0.0);
  std::vector<contact::ContactCache::Entry> stored;
  std::size_t hits = 0;
  std::uint64_t failures = 0, reused = 0;
  dynamics::DeepestOverlap deepest;
  double worst_q2 = 0.0;
  int worst_a = -1;
  for (std::size_t p = 0; p < c.pairs.size(); ++p) {
    const PairResult& r = c.results[p];
    failures += r.fallback;
    if (!r.hit) continue;
    ++hits;
    reused += r.reused;
    const dynamics::SlotStatic &A = c.statics[r.a], &B = c.statics[r.b];
    force[r.b] += r.f;
    torque[r.b] += r.tau_b;
    force[r.a] -= r.f;
    torque[r.a] += r.tau_a;
    stored.push_back({{A.id, B.id}, {r.cf.spring, r.cf.normal}});
    deepest.consider(r.g.depth, 0.5 * std::min(A.equivalent_radius, B.equivalent_radius), A.body, B.body);
    if (r.q2 > worst_q2) {
      worst_q2 = r.q2;
      worst_a = A.body;
    }
  }
  ASSERT_GT(hits, 500u);
  std::vector<contact::ContactCache::Entry> by_key = stored;
  std::sort(by_key.begin(), by_key.end(), [](const auto& x, const auto& y) {
    return x.first.lo != y.first.lo ? x.first.lo < y.first.lo : x.first.hi < y.first.hi;
  });
  for (int threads : {1, 2, 3, 7}) {
    ContactSum sum;
    dynamics::NeighbourLists lists(0.0);
    contact::ContactCache cache;
    const ContactSum::Totals& t = sum.sum({c.pairs, c.results, c.hit, c.statics, 0.5}, threads, lists, cache);
    for (int k = 0; k < n; ++k) {
      ASSERT_EQ(std::memcmp(&sum.slot_force(k), &force[k], sizeof(Vec2)), 0) << "slot " << k << ", threads " << threads;
      const double tk = sum.slot_torque(k);
      ASSERT_EQ(std::memcmp(&tk, &torque[k], sizeof(double)), 0) << "slot " << k << ", threads " << threads;
    }
    EXPECT_EQ(t.hits, hits);
    EXPECT_EQ(t.failures, failures);
    EXPECT_EQ(t.reused, reused);
    EXPECT_EQ(t.deepest.ratio, deepest.ratio);
    EXPECT_EQ(t.deepest.a, deepest.a);
    EXPECT_EQ(t.deepest.b, deepest.b);
    EXPECT_EQ(t.shortest.a, worst_a);
    EXPECT_EQ(t.shortest.duration, 3.2181 * std::pow(worst_q2, -0.1));
    // The history: each hit pair's spring and normal force (listed by key).
    EXPECT_EQ(cache.entries(), by_key);
  }
}

TEST(ContactSum, NoHitsReportNoContact) {
  Case c = random_case(50, 200, 3);
  for (auto& h : c.hit) h = 0;
  for (auto& r : c.results) r.hit = false;
  ContactSum sum;
  dynamics::NeighbourLists lists(0.0);
  contact::ContactCache cache;
  const ContactSum::Totals& t = sum.sum({c.pairs, c.results, c.hit, c.statics, 0.5}, 2, lists, cache);
  EXPECT_EQ(t.hits, 0u);
  EXPECT_EQ(t.deepest.a, -1);
  EXPECT_EQ(t.shortest.a, -1);
  EXPECT_TRUE(std::isinf(t.shortest.duration));
  for (int k = 0; k < 50; ++k) EXPECT_EQ(sum.slot_force(k), (Vec2{0.0, 0.0}));
}
