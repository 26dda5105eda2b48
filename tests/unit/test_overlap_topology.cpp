// Kept overlap topologies (contact::OverlapTopology): planar_overlap given the topology of an earlier step builds the
// overlap from it instead of clipping, and must give the same bits as a fresh call whatever topology it is given -
// the current one, a stale one, a wrong one, garbage - or else the World's results would depend on what it kept
// (restarts, thread counts). And it must actually be used: a test that reuse happens for persisting contacts.
#include <gtest/gtest.h>

#include <cstdio>
#include <cstring>
#include <numbers>
#include <random>
#include <string>
#include <vector>

#include "contact/narrow_phase_planar.h"
#include "test_support.h"

using namespace polyfloe;
using contact::OverlapTopology;
using contact::PlanarContact;
using geometry::Vec2;

namespace {

bool same_topology(const OverlapTopology& x, const OverlapTopology& y) {
  return x.a_first == y.a_first && x.a_last == y.a_last && x.b_first == y.b_first && x.b_last == y.b_last;
}

// Calls planar_overlap with and without `kept` (for both gradient settings) and reports the first difference.
// `reused`: whether the kept topology passed its check (the call says so; it then comes back unchanged).
std::string compare(const std::vector<Vec2>& a, const std::vector<Vec2>& b, OverlapTopology& kept, bool* reused) {
  for (const bool gradient : {false, true}) {
    PlanarContact fresh, again;
    OverlapTopology fresh_topology, t = kept;
    const bool hit_fresh = contact::planar_overlap(a, b, fresh, gradient, &fresh_topology);
    const bool hit_again = contact::planar_overlap(a, b, again, gradient, &t);
    PlanarContact plain;
    const bool hit_plain = contact::planar_overlap(a, b, plain, gradient);
    if (hit_fresh != hit_again || hit_fresh != hit_plain) return "contact or not differs";
    if (hit_fresh && std::memcmp(&fresh, &again, sizeof fresh) != 0) {
      return "kept topology changed the result: area " + std::to_string(fresh.area) + " vs " +
             std::to_string(again.area) + ", depth " + std::to_string(fresh.depth) + " vs " +
             std::to_string(again.depth);
    }
    if (hit_fresh && std::memcmp(&fresh, &plain, sizeof fresh) != 0) return "the topology argument changed the result";
    if (!same_topology(t, fresh_topology)) return "the returned topology depends on the one passed in";
    if (hit_fresh && t.reused && !(kept.known() && same_topology(kept, t)))
      return "reported as reused with another topology";
    if (!hit_fresh && t.reused) {
      // Answered by the kept separating edge: all of the other polygon outside that edge's line.
      if (t.a_apart != kept.a_apart || t.b_apart != kept.b_apart) return "reported as apart by another edge";
      auto separates = [](const std::vector<Vec2>& q, int j, const std::vector<Vec2>& p) {
        const int n = static_cast<int>(q.size());
        const Vec2 q0 = q[static_cast<std::size_t>((j + n - 1) % n)], q1 = q[static_cast<std::size_t>(j)];
        for (const Vec2& x : p)
          if (!(geometry::cross(q1 - q0, x - q0) < 0.0)) return false;
        return true;
      };
      if (!(kept.b_apart >= 0 ? separates(b, kept.b_apart, a) : kept.a_apart >= 0 && separates(a, kept.a_apart, b)))
        return "the kept separating edge does not separate";
    }
    if (reused && !gradient) *reused = t.reused;
    if (gradient) kept = t;
  }
  return "";
}

std::vector<Vec2> moved(const std::vector<Vec2>& v, const Vec2& shift, double turn) {
  Vec2 c{0.0, 0.0};
  for (const Vec2& p : v) c += p;
  c /= static_cast<double>(v.size());
  const double cs = std::cos(turn), sn = std::sin(turn);
  std::vector<Vec2> out;
  for (const Vec2& p : v) out.push_back(c + shift + geometry::rotate(p - c, cs, sn));
  return out;
}

}  // namespace

// Pairs of random floes (4-20 corners, 5-100 m, 5 km from the origin) pressed into each other and then moved a
// step at a time (B by up to 2 mm and 2e-4 rad a step, 60 steps): every step's call with the topology kept from the
// step before gives the same bits as a fresh call, and most persisting contacts reuse it.
TEST(OverlapTopology, KeptTopologyGivesTheSameBitsAndIsReused) {
  std::mt19937_64 rng(2024);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  long calls = 0, known = 0, reused_count = 0;
  for (int pair = 0; pair < 400; ++pair) {
    const int na = 4 + static_cast<int>(u(rng) * 17), nb = 4 + static_cast<int>(u(rng) * 17);
    const double ra = 2.5 + 47.5 * u(rng), rb = 2.5 + 47.5 * u(rng);
    const Vec2 where{5000.0 * (2.0 * u(rng) - 1.0), 5000.0 * (2.0 * u(rng) - 1.0)};
    const auto a = tsupport::transform(tsupport::random_convex(rng, na, ra, ra * (0.5 + 0.5 * u(rng))),
                                       2.0 * std::numbers::pi * u(rng), where);
    const auto b0 = tsupport::random_convex(rng, nb, rb, rb * (0.5 + 0.5 * u(rng)));
    // B placed so that it just reaches into A along a random direction.
    const double ang = 2.0 * std::numbers::pi * u(rng);
    const Vec2 dir{std::cos(ang), std::sin(ang)};
    auto b = tsupport::transform(b0, 2.0 * std::numbers::pi * u(rng), where + (ra + rb) * dir);
    for (int k = 0; k < 200; ++k) {  // walk in until the boxes' overlap is a few percent
      PlanarContact g;
      if (contact::planar_overlap(a, b, g) && g.depth > 0.01 * std::min(ra, rb)) break;
      b = moved(b, -0.01 * std::min(ra, rb) * dir, 0.0);
    }
    OverlapTopology kept;
    for (int step = 0; step < 60; ++step) {
      const double s = 2e-3 * u(rng), th = 2.0 * std::numbers::pi * u(rng);
      b = moved(b, s * Vec2{std::cos(th), std::sin(th)}, 2e-4 * (2.0 * u(rng) - 1.0));
      bool reused = false;
      const bool had_topology = kept.known();
      known += had_topology;
      const std::string err = compare(a, b, kept, &reused);
      ASSERT_TRUE(err.empty()) << "pair " << pair << " step " << step << ": " << err;
      ++calls;
      reused_count += reused && had_topology;  // the overlap's topology, not a separating edge
    }
  }
  // The walk keeps most pairs touching; of the calls with a known topology nearly all reuse it (the rest saw a
  // crossing move to the next edge, or a vertex pass the other floe's edge).
  EXPECT_GT(known, calls / 2);
  EXPECT_GT(reused_count, 9 * known / 10) << reused_count << " of " << known;
  std::printf("%ld calls, %ld with a known topology, %ld reused it\n", calls, known, reused_count);
}

// Near misses moved a step at a time (B 0.1 % of its size apart, then jostled by up to 0.2 mm and 2e-5 rad a step,
// 30 steps): every call gives the fresh call's answer, and most are answered by the separating edge kept from the
// step before.
TEST(OverlapTopology, PairsApartKeepTheirSeparatingEdge) {
  std::mt19937_64 rng(99);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  long apart = 0, reused = 0;
  for (int pair = 0; pair < 300; ++pair) {
    const double ra = 2.5 + 47.5 * u(rng), rb = 2.5 + 47.5 * u(rng);
    const Vec2 where{5000.0 * (2.0 * u(rng) - 1.0), 5000.0 * (2.0 * u(rng) - 1.0)};
    const auto a = tsupport::transform(tsupport::random_convex(rng, 12, ra, ra * (0.5 + 0.5 * u(rng))),
                                       2.0 * std::numbers::pi * u(rng), where);
    const double ang = 2.0 * std::numbers::pi * u(rng);
    const Vec2 dir{std::cos(ang), std::sin(ang)};
    auto b = tsupport::transform(tsupport::random_convex(rng, 12, rb, rb * (0.5 + 0.5 * u(rng))),
                                 2.0 * std::numbers::pi * u(rng), where + (ra + rb) * dir);
    PlanarContact g;
    while (!contact::planar_overlap(a, b, g)) b = moved(b, -0.002 * rb * dir, 0.0);  // walk in until they touch,
    b = moved(b, 0.003 * rb * dir, 0.0);                                             // then back out a little
    OverlapTopology kept;
    for (int step = 0; step < 30; ++step) {
      const double s = 2e-4 * u(rng), th = 2.0 * std::numbers::pi * u(rng);
      b = moved(b, s * Vec2{std::cos(th), std::sin(th)}, 2e-5 * (2.0 * u(rng) - 1.0));
      bool was_reused = false;
      const OverlapTopology before = kept;
      const std::string err = compare(a, b, kept, &was_reused);
      ASSERT_TRUE(err.empty()) << "pair " << pair << " step " << step << ": " << err;
      if (!contact::planar_overlap(a, b, g)) {
        ++apart;
        reused += was_reused && (before.a_apart >= 0 || before.b_apart >= 0);
      }
    }
  }
  // Every pair's first call finds its edge; later ones reuse it unless the motion changed which edge separates.
  EXPECT_GT(apart, 300 * 30 / 2);
  EXPECT_GT(reused, 9 * apart / 10) << reused << " of " << apart;
  std::printf("%ld calls apart, %ld answered by the kept separating edge\n", apart, reused);
}

// Whatever topology is passed - every combination of edge indices, and out-of-range ones - the result is the fresh
// call's, and the topology returned is the fresh call's. Small polygons (5 and 4 corners) in many placements, and
// odd and even corner counts up to 12 in fewer (the chain test takes two edges at a time and the last of an odd
// count alone, so a chain vertex must be caught outside any one edge).
TEST(OverlapTopology, AnyTopologyPassedInGivesTheFreshResult) {
  std::mt19937_64 rng(77);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  struct Sizes {
    int na, nb, pairs;
  };
  for (const Sizes sz : {Sizes{5, 4, 40}, Sizes{7, 12, 3}, Sizes{12, 9, 3}, Sizes{3, 6, 10}}) {
    for (int pair = 0; pair < sz.pairs; ++pair) {
      const int na = sz.na, nb = sz.nb;
      const auto a = tsupport::transform(tsupport::random_convex(rng, na, 10.0, 7.0), 6.0 * u(rng), {100.0, -40.0});
      const auto b = tsupport::transform(tsupport::random_convex(rng, nb, 6.0, 5.0), 6.0 * u(rng),
                                         Vec2{100.0, -40.0} + Vec2{12.0 * u(rng) - 6.0, 12.0 * u(rng) - 6.0});
      for (int i1 = 0; i1 <= na; ++i1)
        for (int i2 = 0; i2 <= na; ++i2)
          for (int j1 = 0; j1 <= nb; ++j1)
            for (int j2 = 0; j2 <= nb; ++j2) {
              for (const int apart : {-1, 0, 1}) {
                OverlapTopology t{static_cast<std::int8_t>(i1),
                                  static_cast<std::int8_t>(i2),
                                  static_cast<std::int8_t>(j1),
                                  static_cast<std::int8_t>(j2),
                                  static_cast<std::int8_t>(apart == 0 ? i1 : -1),
                                  static_cast<std::int8_t>(apart == 1 ? j1 : -1)};
                const std::string err = compare(a, b, t, nullptr);
                ASSERT_TRUE(err.empty()) << "pair " << pair << " topology " << i1 << i2 << j1 << j2 << apart << ": "
                                         << err;
              }
            }
    }
  }
}

// Overlaps of other shapes have no topology to keep: containment, and the eight crossings of a square and the same
// square turned by 45 degrees. The usual corner-into-edge contact has one, with the right edges.
TEST(OverlapTopology, OnlyTwoCrossingOverlapsHaveATopology) {
  const std::vector<Vec2> square{{-1, -1}, {1, -1}, {1, 1}, {-1, 1}};
  const double r = std::sqrt(2.0);
  const std::vector<Vec2> diamond{{r, 0}, {0, r}, {-r, 0}, {0, -r}};
  const std::vector<Vec2> small{{-0.1, -0.1}, {0.1, -0.1}, {0.1, 0.1}, {-0.1, 0.1}};
  PlanarContact g;
  OverlapTopology t{0, 0, 0, 0};
  ASSERT_TRUE(contact::planar_overlap(square, diamond, g, false, &t));
  EXPECT_FALSE(t.known());
  t = {0, 1, 2, 3};
  ASSERT_TRUE(contact::planar_overlap(square, small, g, false, &t));
  EXPECT_FALSE(t.known());
  // The diamond's corner (0, -r) pushed up into the square's top edge from above: B = diamond + (0, 1 + r - 0.1).
  std::vector<Vec2> above;
  for (const Vec2& p : diamond) above.push_back(p + Vec2{0.0, 1.0 + r - 0.1});
  ASSERT_TRUE(contact::planar_overlap(square, above, g, false, &t));
  ASSERT_TRUE(t.known());
  // A's boundary inside B: a piece of the top edge (edge 2, (1,1) -> (-1,1)), no vertex; B's: its bottom corner
  // (vertex 3), between its edges 3 ((-r,0) -> (0,-r)) and 0 ((0,-r) -> (r,0)).
  EXPECT_EQ(t.a_first, 2);
  EXPECT_EQ(t.a_last, 2);
  EXPECT_EQ(t.b_first, 3);
  EXPECT_EQ(t.b_last, 0);
  OverlapTopology kept = t;
  EXPECT_TRUE(compare(square, above, kept, nullptr).empty());
  // Separated: unknown.
  std::vector<Vec2> apart;
  for (const Vec2& p : diamond) apart.push_back(p + Vec2{0.0, 5.0});
  EXPECT_FALSE(contact::planar_overlap(square, apart, g, false, &t));
  EXPECT_FALSE(t.known());
}
