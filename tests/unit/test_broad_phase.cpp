// GridBroadPhase against brute force: for every set of boxes, the candidate pairs must be exactly the pairs (i < j)
// whose boxes overlap (closed intervals, touching counts) and of which at least one body is dynamic, each once.
// Sets: power-law sizes 5-100 m, some non-dynamic boxes, automatic and fixed cell sizes (tiny, typical, huge), boxes
// spread over a huge area (the cell-count cap), identical boxes, zero-size boxes, boxes on cell boundaries; non-finite
// boxes (a body that blew up) enter no cell.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <utility>
#include <vector>

#include "contact/broad_phase.h"

using namespace polyfloe;
using geometry::Aabb;
using geometry::Vec2;

namespace {

using PairList = std::vector<std::pair<int, int>>;

PairList brute_pairs(const std::vector<Aabb>& boxes, const std::vector<std::uint8_t>& dyn) {
  PairList out;
  const int n = static_cast<int>(boxes.size());
  for (int i = 0; i < n; ++i)
    for (int j = i + 1; j < n; ++j)
      if ((dyn[i] || dyn[j]) && boxes[i].overlaps(boxes[j])) out.emplace_back(i, j);
  return out;
}

// Runs the grid and checks: a < b in every pair, no duplicates, and the sorted set equals brute force.
void expect_same_pairs(contact::GridBroadPhase& grid, const std::vector<Aabb>& boxes,
                       const std::vector<std::uint8_t>& dyn, const char* what) {
  std::vector<contact::CandidatePair> got;
  grid.find_pairs(boxes, dyn, got);
  PairList g;
  for (const auto& p : got) {
    EXPECT_LT(p.a, p.b) << what;
    g.emplace_back(p.a, p.b);
  }
  std::sort(g.begin(), g.end());
  const auto dup = std::adjacent_find(g.begin(), g.end());
  EXPECT_TRUE(dup == g.end()) << what << ": pair (" << dup->first << ", " << dup->second << ") reported twice";
  const PairList want = brute_pairs(boxes, dyn);  // already sorted
  EXPECT_EQ(g.size(), want.size()) << what;
  EXPECT_TRUE(g == want) << what;
}

// Box sizes from a power law p(s) ~ s^-2 on [5, 100] m (inverse CDF), centres uniform in a square of side `extent`.
std::vector<Aabb> power_law_boxes(std::mt19937_64& rng, int n, double extent) {
  std::uniform_real_distribution<double> u(0.0, 1.0);
  const double s0 = 5.0, s1 = 100.0;
  std::vector<Aabb> boxes;
  for (int i = 0; i < n; ++i) {
    const double size = 1.0 / (1.0 / s0 - u(rng) * (1.0 / s0 - 1.0 / s1));
    const double aspect = 0.3 + 0.7 * u(rng);
    const Vec2 c{extent * u(rng), extent * u(rng)};
    const Vec2 h{0.5 * size, 0.5 * size * aspect};
    boxes.push_back({c - h, c + h});
  }
  return boxes;
}

std::vector<std::uint8_t> mostly_dynamic(std::mt19937_64& rng, int n, double fraction_static) {
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::vector<std::uint8_t> dyn(static_cast<std::size_t>(n));
  for (auto& d : dyn) d = u(rng) < fraction_static ? 0 : 1;
  return dyn;
}

}  // namespace

TEST(BroadPhase, PowerLawSizesAutomaticAndFixedCells) {
  std::mt19937_64 rng(1);
  for (int trial = 0; trial < 20; ++trial) {
    const int n = 50 + 40 * trial;
    const auto boxes = power_law_boxes(rng, n, 12.0 * std::sqrt(static_cast<double>(n)) * 3.0);
    const auto dyn = mostly_dynamic(rng, n, 0.15);
    for (double cell : {0.0, 1.0, 7.5, 40.0, 250.0, 1.0e5}) {
      contact::GridBroadPhase grid(cell);
      expect_same_pairs(grid, boxes, dyn, "power law");
      // Reusing the grid (warm buffers) gives the same answer.
      expect_same_pairs(grid, boxes, dyn, "power law, second call");
      EXPECT_GT(grid.cell_size(), 0.0);
      EXPECT_LE(static_cast<double>(grid.cell_count()), 4.0 * n + 1024.0);
    }
  }
}

TEST(BroadPhase, DenseClusterGivesExactlyTheBruteForcePairsWithAutomaticAndFixedCells) {
  std::mt19937_64 rng(2);
  const int n = 400;
  const auto boxes = power_law_boxes(rng, n, 100.0);  // heavily overlapping
  const auto dyn = mostly_dynamic(rng, n, 0.3);
  for (double cell : {0.0, 3.0, 20.0}) {
    contact::GridBroadPhase grid(cell);
    expect_same_pairs(grid, boxes, dyn, "dense");
  }
  EXPECT_GT(brute_pairs(boxes, dyn).size(), 3000u);  // the set really is dense
}

TEST(BroadPhase, HugeAreaCapsTheCellCountByEnlargingTheCellAndKeepsEveryPair) {
  std::mt19937_64 rng(3);
  // A few clusters of floes kilometres apart, plus a long wall: the automatic cell would give ~1e10 cells.
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::vector<Aabb> boxes;
  for (int cluster = 0; cluster < 4; ++cluster) {
    const Vec2 origin{cluster * 2.0e6, (cluster % 2) * 1.5e6};
    for (const Aabb& b : power_law_boxes(rng, 60, 200.0)) boxes.push_back({b.lo + origin, b.hi + origin});
  }
  boxes.push_back({{-10.0, -20.0}, {6.1e6, 0.0}});  // a wall along the whole span
  const int n = static_cast<int>(boxes.size());
  auto dyn = mostly_dynamic(rng, n, 0.1);
  dyn.back() = 0;
  for (double cell : {0.0, 0.01, 5.0}) {
    contact::GridBroadPhase grid(cell);
    expect_same_pairs(grid, boxes, dyn, "huge area");
    EXPECT_LE(static_cast<double>(grid.cell_count()), 4.0 * n + 1024.0) << "cell " << cell;
    // ~2000 cells over 6e6 m x 1.5e6 m: cells of ~7e4 m, far above any requested or automatic size.
    EXPECT_GT(grid.cell_size(), 1.0e4) << "the cap must have enlarged the cell (requested " << cell << ")";
  }
}

TEST(BroadPhase, IdenticalZeroSizeAndTouchingBoxes) {
  std::vector<Aabb> boxes;
  // Five identical boxes.
  for (int i = 0; i < 5; ++i) boxes.push_back({{0.0, 0.0}, {10.0, 10.0}});
  // Zero-size boxes (points): inside the identical ones, on their corner, on their edge, far away, and two
  // coincident points.
  boxes.push_back({{5.0, 5.0}, {5.0, 5.0}});
  boxes.push_back({{10.0, 10.0}, {10.0, 10.0}});
  boxes.push_back({{10.0, 3.0}, {10.0, 3.0}});
  boxes.push_back({{100.0, 100.0}, {100.0, 100.0}});
  boxes.push_back({{100.0, 100.0}, {100.0, 100.0}});
  // Degenerate segments (zero width or height) crossing the identical boxes.
  boxes.push_back({{-5.0, 4.0}, {15.0, 4.0}});
  boxes.push_back({{7.0, -5.0}, {7.0, 15.0}});
  // Boxes that only touch: edge to edge, corner to corner, and exactly on multiples of the fixed cell sizes.
  boxes.push_back({{10.0, 0.0}, {20.0, 10.0}});
  boxes.push_back({{20.0, 10.0}, {30.0, 20.0}});
  boxes.push_back({{-10.0, -10.0}, {0.0, 0.0}});
  boxes.push_back({{30.0, 20.0}, {40.0, 40.0}});
  const int n = static_cast<int>(boxes.size());
  std::vector<std::uint8_t> all_dynamic(static_cast<std::size_t>(n), 1);
  std::vector<std::uint8_t> mixed(static_cast<std::size_t>(n), 1);
  mixed[1] = mixed[2] = mixed[5] = mixed[13] = 0;
  for (double cell : {0.0, 1.0, 2.5, 10.0, 20.0, 1000.0}) {
    contact::GridBroadPhase grid(cell);
    expect_same_pairs(grid, boxes, all_dynamic, "degenerate, all dynamic");
    expect_same_pairs(grid, boxes, mixed, "degenerate, mixed");
  }
  // Spot checks against hand values: the 5 identical boxes give all 10 pairs among them, and the far coincident
  // points (8, 9) are a pair.
  const PairList want = brute_pairs(boxes, all_dynamic);
  for (int i = 0; i < 5; ++i)
    for (int j = i + 1; j < 5; ++j) EXPECT_TRUE(std::count(want.begin(), want.end(), std::make_pair(i, j)) == 1);
  EXPECT_TRUE(std::count(want.begin(), want.end(), std::make_pair(8, 9)) == 1);
}

TEST(BroadPhase, NonDynamicPairsExcludedAndEdgeCases) {
  // Two overlapping walls and one floe touching both: only the floe's two pairs.
  std::vector<Aabb> boxes{{{0.0, 0.0}, {100.0, 1.0}}, {{0.0, 0.0}, {1.0, 100.0}}, {{0.5, 0.5}, {3.0, 3.0}}};
  std::vector<std::uint8_t> dyn{0, 0, 1};
  contact::GridBroadPhase grid;
  std::vector<contact::CandidatePair> pairs;
  grid.find_pairs(boxes, dyn, pairs);
  ASSERT_EQ(pairs.size(), 2u);
  std::sort(pairs.begin(), pairs.end(), [](const auto& x, const auto& y) { return x.a < y.a; });
  EXPECT_EQ(pairs[0].a, 0);
  EXPECT_EQ(pairs[0].b, 2);
  EXPECT_EQ(pairs[1].a, 1);
  EXPECT_EQ(pairs[1].b, 2);
  // No dynamic body at all, a single body, no bodies: nothing, and stale output is cleared.
  dyn[2] = 0;
  grid.find_pairs(boxes, dyn, pairs);
  EXPECT_TRUE(pairs.empty());
  pairs.push_back({0, 1});
  grid.find_pairs(std::span<const Aabb>(boxes.data(), 1), std::span<const std::uint8_t>(dyn.data(), 1), pairs);
  EXPECT_TRUE(pairs.empty());
  pairs.push_back({0, 1});
  grid.find_pairs({}, {}, pairs);
  EXPECT_TRUE(pairs.empty());
  // Boxes far from the origin (1e7 m): same answer as brute force.
  std::mt19937_64 rng(5);
  auto far = power_law_boxes(rng, 300, 600.0);
  for (Aabb& b : far) {
    b.lo += Vec2{1.0e7, -3.0e7};
    b.hi += Vec2{1.0e7, -3.0e7};
  }
  const auto fdyn = mostly_dynamic(rng, 300, 0.2);
  for (double cell : {0.0, 12.0}) {
    contact::GridBroadPhase g2(cell);
    expect_same_pairs(g2, far, fdyn, "far from origin");
  }
}

TEST(BroadPhase, NonFiniteBoxesEnterNoCellAndTheOthersKeepTheirPairs) {
  std::mt19937_64 rng(9);
  const int n = 400;
  auto boxes = power_law_boxes(rng, n, 600.0);
  const auto dyn = mostly_dynamic(rng, n, 0.1);
  const double nan = std::numeric_limits<double>::quiet_NaN(), inf = std::numeric_limits<double>::infinity();
  boxes[3] = {Vec2{nan, 0.0}, Vec2{nan, 1.0}};     // a body whose state became NaN
  boxes[50] = {Vec2{-inf, -inf}, Vec2{inf, inf}};  // or infinite
  boxes[51].hi.y() = nan;
  std::vector<contact::CandidatePair> got;
  contact::GridBroadPhase grid;
  grid.find_pairs(boxes, dyn, got);  // used to loop for ever on a NaN box
  PairList g;
  for (const auto& p : got) g.emplace_back(p.a, p.b);
  std::sort(g.begin(), g.end());
  PairList want;
  for (const auto& p : brute_pairs(boxes, dyn))
    if (p.first != 3 && p.first != 50 && p.first != 51 && p.second != 3 && p.second != 50 && p.second != 51)
      want.push_back(p);
  EXPECT_FALSE(want.empty());
  EXPECT_EQ(g, want);
}

// Found by fuzzing restarts (tests/fuzz/regressions/fuzz_checkpoint/broad-phase-cell-of-zero-at-far-positions):
// boxes so far from the origin that their extent rounds to zero gave a cell size of 0, which the grid's growth
// loop never enlarged. Far, huge and overflowing spans now give a grid of a few cells with every pair found.
TEST(BroadPhase, BoxesFarFromTheOriginOrSpanningTheRangeOfDoubles) {
  for (const double far : {1e300, 1e17, -1e200}) {
    SCOPED_TRACE(far);
    const std::vector<Aabb> boxes{
        {Vec2{far, far}, Vec2{far, far}}, {Vec2{far, far}, Vec2{far, far}}, {Vec2{0.0, 0.0}, Vec2{1.0, 1.0}}};
    const std::vector<std::uint8_t> dyn{1, 1, 1};
    std::vector<contact::CandidatePair> got;
    contact::GridBroadPhase grid;
    grid.find_pairs(boxes, dyn, got);
    PairList g;
    for (const auto& p : got) g.emplace_back(p.a, p.b);
    std::sort(g.begin(), g.end());
    EXPECT_EQ(g, brute_pairs(boxes, dyn));
  }
  const double big = 1e308;
  const std::vector<Aabb> spread{{Vec2{-big, -big}, Vec2{-big, -big}},
                                 {Vec2{big, big}, Vec2{big, big}},
                                 {Vec2{0.0, 0.0}, Vec2{1.0, 1.0}},
                                 {Vec2{0.5, 0.5}, Vec2{2.0, 2.0}}};
  const std::vector<std::uint8_t> dyn{1, 1, 1, 1};
  std::vector<contact::CandidatePair> got;
  contact::GridBroadPhase grid;
  grid.find_pairs(spread, dyn, got);  // the span overflows to infinity
  PairList g;
  for (const auto& p : got) g.emplace_back(p.a, p.b);
  std::sort(g.begin(), g.end());
  EXPECT_EQ(g, brute_pairs(spread, dyn));
}
