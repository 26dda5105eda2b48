// The partition of the ice among MPI ranks: Zoltan's recursive coordinate bisection (RCB) of every rank's floes,
// weighted by each floe's measured cost, and the queries the halo exchange asks of its cuts: the rank whose region
// holds a point, and the ranks whose regions a box reaches (a floe larger than a region reaches several). Zoltan
// (Debian's libtrilinos-zoltan-dev) is private to partition.cpp; this header names MPI only.
#pragma once

#include <mpi.h>

#include <cstdint>
#include <memory>
#include <span>
#include <vector>

#include "geometry/vec2.h"

namespace polyfloe::domain {

// One floe a rank offers to the partition: its global id, centroid and cost (any unit: only ratios count).
struct PartitionItem {
  std::uint64_t id = 0;
  geometry::Vec2 position{0.0, 0.0};  // [m]
  double weight = 1.0;
};

class Partition {
 public:
  // Collective over `comm` (MPI initialised); no cuts until the first balance().
  explicit Partition(MPI_Comm comm);
  ~Partition();
  Partition(const Partition&) = delete;
  Partition& operator=(const Partition&) = delete;

  int rank() const { return rank_; }
  int ranks() const { return ranks_; }

  // Collective: cuts the plane into ranks() regions of about equal total weight by recursive coordinate bisection
  // over every rank's `items`, and returns the rank whose region holds each of this rank's items' centroid (rank_of,
  // in the order given). The cuts are kept for the queries below. The result depends only on the items of all ranks together and on how they
  // are spread among the ranks, never on timing. Throws std::runtime_error naming Zoltan's error.
  std::vector<int> balance(std::span<const PartitionItem> items);
  bool has_cuts() const { return has_cuts_; }

  // The rank whose region holds `p` (after balance()).
  int rank_of(const geometry::Vec2& p) const;
  // The ranks whose regions `box` reaches, increasing (after balance()): at least the rank of its centre.
  void ranks_of(const geometry::Aabb& box, std::vector<int>& out) const;

 private:
  struct Zoltan;
  MPI_Comm comm_;
  int rank_ = 0, ranks_ = 1;
  bool has_cuts_ = false;
  std::unique_ptr<Zoltan> zoltan_;
  std::vector<PartitionItem> items_;  // what the callbacks hand Zoltan during balance()
};

// Each floe's cost, for balance(): this rank's measured busy time `busy` [s] (at least 1 ns), as microseconds,
// shared among its `items` in proportion to 1 + the contact pairs each evaluates (`pairs`, in the items' order), a
// pair's narrow phase and law costing about what a floe's own stages do (bench_step: 0.2-0.5 us per floe-step
// either way).
void weigh_by_cost(std::span<PartitionItem> items, std::span<const int> pairs, double busy);

// The ranks' measured load (collective over `comm`): the busiest rank's busy seconds and the mean over the ranks,
// the same bits on every rank (summed in rank order, not by a reduction).
struct Load {
  double largest = 0.0, mean = 0.0;  // [s]
  // Whether the busiest rank works more than `factor` x the mean (never without a measurement).
  bool uneven(double factor) const { return mean > 0.0 && largest > factor * mean; }
};
Load measured_load(MPI_Comm comm, double busy);

}  // namespace polyfloe::domain
