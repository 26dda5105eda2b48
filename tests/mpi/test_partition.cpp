// The partition of the ice among MPI ranks (domain/partition.h), run by CTest under mpirun at 1, 2, 3 and 4 ranks:
//   - 1,000 floes on a jittered lattice, dealt round-robin: after balance() every rank's share of the weight is within 10 % of
//     the mean (Zoltan's tolerance is 5 %, plus a floe's granularity), each floe's rank is the rank that
//     rank_of() gives for its centroid, and the regions hold whole columns or rows of space (a box around a floe
//     reaches its rank);
//   - a cost that grows along x: the weights are balanced, not the counts; a measured busy time shared by the
//     floes' contact pairs, and the ranks' load compared;
//   - the same items twice: the same ranks; all floes starting on rank 0 (the other ranks empty): every rank gets some;
//   - a box over the whole field reaches every rank, a box as long as the field (a floe larger than a region) reaches
//     more than one where there are several, and no floes at all leaves no cuts (rank 0 answers).
#include <gtest/gtest.h>
#include <mpi.h>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <vector>

#include "domain/partition.h"
#include "mpi_test_main.h"

using namespace polyfloe;
using domain::Partition;
using domain::PartitionItem;
using geometry::Vec2;

namespace {

int rank() { return polyfloe::tsupport::mpi_rank(); }
int ranks() { return polyfloe::tsupport::mpi_ranks(); }

constexpr int kColumns = 40, kRows = 25;  // the lattice of floes, 10 m apart

// The lattice floes this rank holds: floe k goes to rank k % ranks (or all to rank 0), weight w(k).
template <class Weight>
std::vector<PartitionItem> lattice_items(bool all_on_rank_zero, Weight w) {
  std::vector<PartitionItem> items;
  for (int k = 0; k < kColumns * kRows; ++k) {
    const int holder = all_on_rank_zero ? 0 : k % ranks();
    if (holder != rank()) continue;
    // (jittered by up to 1 m, as floes are: ties on a cut are rare, and whole columns never tie)
    const Vec2 jitter{std::fmod(0.618034 * k, 1.0) - 0.5, std::fmod(0.414214 * k, 1.0) - 0.5};
    items.push_back({static_cast<std::uint64_t>(k) + (std::uint64_t{1} << 40),  // ids past 32 bits
                     Vec2{10.0 * (k % kColumns) + 5.0, 10.0 * (k / kColumns) + 5.0} + 2.0 * jitter, w(k)});
  }
  return items;
}

// The weight each rank gets from every rank's items and their destinations.
std::vector<double> weight_per_rank(const std::vector<PartitionItem>& items, const std::vector<int>& to) {
  std::vector<double> mine(static_cast<std::size_t>(ranks()), 0.0), all(mine.size(), 0.0);
  for (std::size_t k = 0; k < items.size(); ++k) mine[static_cast<std::size_t>(to[k])] += items[k].weight;
  MPI_Allreduce(mine.data(), all.data(), ranks(), MPI_DOUBLE, MPI_SUM, MPI_COMM_WORLD);
  return all;
}

void expect_balanced(const std::vector<double>& w) {
  const double mean = std::accumulate(w.begin(), w.end(), 0.0) / static_cast<double>(w.size());
  for (std::size_t r = 0; r < w.size(); ++r) EXPECT_NEAR(w[r], mean, 0.10 * mean) << "rank " << r << " of " << w.size();
}

}  // namespace

TEST(Partition, LatticeFloesAreSharedEvenlyAndEachFloesRankHoldsItsCentroid) {
  Partition p(MPI_COMM_WORLD);
  const auto items = lattice_items(false, [](int) { return 1.0; });
  const std::vector<int> to = p.balance(items);
  ASSERT_EQ(to.size(), items.size());
  ASSERT_TRUE(p.has_cuts());
  expect_balanced(weight_per_rank(items, to));
  std::vector<int> reached;
  for (std::size_t k = 0; k < items.size(); ++k) {
    ASSERT_GE(to[k], 0);
    ASSERT_LT(to[k], ranks());
    EXPECT_EQ(p.rank_of(items[k].position), to[k]) << "floe " << items[k].id;
    p.ranks_of({items[k].position - Vec2{4.0, 4.0}, items[k].position + Vec2{4.0, 4.0}}, reached);
    EXPECT_TRUE(std::binary_search(reached.begin(), reached.end(), to[k])) << "floe " << items[k].id;
  }
}

TEST(Partition, ACostGrowingAlongXIsBalancedByWeightNotByCount) {
  Partition p(MPI_COMM_WORLD);
  const auto items = lattice_items(false, [](int k) { return 1.0 + 0.25 * (k % kColumns); });
  const std::vector<int> to = p.balance(items);
  expect_balanced(weight_per_rank(items, to));
}

TEST(Partition, TheSameItemsGiveTheSameRanksAndFloesAllOnOneRankReachEveryRank) {
  Partition p(MPI_COMM_WORLD), q(MPI_COMM_WORLD);
  const auto items = lattice_items(false, [](int k) { return 1.0 + (k % 7); });
  EXPECT_EQ(p.balance(items), q.balance(items));
  Partition r(MPI_COMM_WORLD);
  const auto all_on_zero = lattice_items(true, [](int) { return 1.0; });
  const std::vector<int> to = r.balance(all_on_zero);
  const std::vector<double> w = weight_per_rank(all_on_zero, to);
  expect_balanced(w);
  for (std::size_t k = 0; k < w.size(); ++k) EXPECT_GT(w[k], 0.0) << "rank " << k;
}

TEST(Partition, BoxesReachTheRanksTheyCrossAndNoFloesMeansNoCuts) {
  Partition p(MPI_COMM_WORLD);
  p.balance(lattice_items(false, [](int) { return 1.0; }));
  std::vector<int> reached;
  p.ranks_of({Vec2{-1.0, -1.0}, Vec2{10.0 * kColumns + 1.0, 10.0 * kRows + 1.0}}, reached);
  std::vector<int> every(static_cast<std::size_t>(ranks()));
  std::iota(every.begin(), every.end(), 0);
  EXPECT_EQ(reached, every);
  // A floe as long as the field, across its middle: larger than any region where there are several.
  p.ranks_of({Vec2{0.0, 120.0}, Vec2{10.0 * kColumns, 130.0}}, reached);
  if (ranks() > 1) {
    EXPECT_GT(reached.size(), 1u);
  }
  EXPECT_TRUE(std::is_sorted(reached.begin(), reached.end()));

  Partition none(MPI_COMM_WORLD);
  const std::vector<int> to = none.balance({});
  EXPECT_TRUE(to.empty());
  EXPECT_FALSE(none.has_cuts());
  EXPECT_EQ(none.rank_of(Vec2{5.0, 5.0}), 0);
  none.ranks_of({Vec2{0.0, 0.0}, Vec2{1.0, 1.0}}, reached);
  EXPECT_EQ(reached, std::vector<int>{0});
}

namespace {

TEST(Partition, MeasuredCostIsSharedByContactPairsAndTheLoadComparedAcrossRanks) {
  // A rank busy 2 ms with three floes evaluating 0, 1 and 3 contact pairs: shares 1:2:4 of 2,000 us.
  std::vector<PartitionItem> items(3);
  const std::vector<int> pairs{0, 1, 3};
  domain::weigh_by_cost(items, pairs, 2e-3);
  EXPECT_NEAR(items[0].weight, 2000.0 / 7.0, 1e-9);
  EXPECT_NEAR(items[1].weight, 4000.0 / 7.0, 1e-9);
  EXPECT_NEAR(items[2].weight, 8000.0 / 7.0, 1e-9);
  domain::weigh_by_cost(items, pairs, 0.0);  // a rank that measured nothing: 1 ns, shared alike
  EXPECT_NEAR(items[0].weight, 1e-3 / 7.0, 1e-15);
  EXPECT_NEAR(items[2].weight, 4e-3 / 7.0, 1e-15);
  EXPECT_THROW(domain::weigh_by_cost(items, std::vector<int>{1}, 1.0), std::logic_error);
  // Rank r busy (r + 1) s: the busiest works ranks s, the mean is (ranks + 1) / 2 s.
  const domain::Load load = domain::measured_load(MPI_COMM_WORLD, rank() + 1.0);
  EXPECT_EQ(load.largest, static_cast<double>(ranks()));
  EXPECT_DOUBLE_EQ(load.mean, 0.5 * (ranks() + 1));
  EXPECT_EQ(load.uneven(1.1), ranks() > 1);
  EXPECT_FALSE(domain::Load{}.uneven(1.1));  // nothing measured: never uneven
}

}  // namespace
