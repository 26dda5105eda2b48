// The contact sum: the deterministic reduction of the planar contact stage. Each candidate pair is evaluated apart
// (on any thread) into a PairResult; the sum adds them into per-slot forces and torques, stores each touching
// pair's history in the contact cache and keeps the counts and extremes the step reports, all in the order one
// loop over the pairs would: the same bits on any number of threads.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "contact/broad_phase.h"
#include "contact/contact_cache.h"
#include "contact/contact_law.h"
#include "dynamics/neighbour_lists.h"
#include "dynamics/slots.h"
#include "dynamics/step_report.h"

namespace polyfloe::dynamics {

// What a contact record keeps of the narrow phase's measurement (contact::PlanarContact less the terms only the
// force evaluation reads).
struct ContactGeometry {
  Vec2 normal{1.0, 0.0};  // unit normal from a to b
  Vec2 point{0.0, 0.0};   // contact point: the overlap's centroid (exact) or the witness midpoint (gjk_epa) [m]
  double depth = 0.0;     // [m]
  double area = 0.0;      // overlap area [m^2] (0 from gjk_epa)
};

// One candidate pair's evaluation (the contact stage's parallel part), added up afterwards in pair order.
struct PairResult {
  bool hit = false;
  bool fallback = false;  // the 2-D GJK-EPA failed on it: measured exactly (beside `hit`: no growth in size)
  bool reused = false;    // its overlap was built from the kept topology (OverlapTopology::reused)
  int a = 0, b = 0;       // slots, ordered by id
  ContactGeometry g;
  contact::ContactForce cf;
  Vec2 f{0.0, 0.0};  // on b
  double tau_b = 0.0, tau_a = 0.0;
  double v2 = 0.0, q2 = 0.0;  // impact speed^2 and v^2 (k_n/m*)^4 (the shortest contact has the largest)
  double energy = 0.0;        // [J]
};

class ContactSum {
 public:
  // What the sum reads: the candidate pairs (sorted by their lower slot a) with their results and hit flags (the
  // results' `hit`, packed: 1 evaluated here, 2 a force evaluated by another World, which adds only its force), the
  // slots' records, and the overlap limit as a fraction of the smaller equivalent radius (DeepestOverlap).
  struct Input {
    std::span<const contact::CandidatePair> pairs;
    std::span<const PairResult> results;
    std::span<const std::uint8_t> hit;
    std::span<const SlotStatic> statics;
    double overlap_limit = 0.5;
  };
  // The counts and extremes of one sum.
  struct Totals {
    std::size_t hits = 0;        // touching pairs
    std::uint64_t failures = 0;  // pairs the 2-D GJK-EPA failed on
    std::uint64_t reused = 0;    // overlaps built from the kept topology
    DeepestOverlap deepest;      // against overlap_limit
    ContactResolution shortest;  // the largest q2's duration and impact speed
  };

  // Sums the pairs into slot_force() and slot_torque() over all the slots, on `threads`; stores each touching
  // pair's spring and normal force in `cache` (in pair order, under the generation after the current one) and tells
  // `lists` where, for the pairs that came from a list entry.
  const Totals& sum(const Input& in, int threads, NeighbourLists& lists, contact::ContactCache& cache);

  const Vec2& slot_force(int slot) const { return slot_force_[static_cast<std::size_t>(slot)]; }  // [N]
  double slot_torque(int slot) const { return slot_torque_[static_cast<std::size_t>(slot)]; }     // [N m]

 private:
  // A block of consecutive slots: its pairs (those whose lower slot is in the block, from first_pair on), the ones
  // of them whose upper slot lies in a later block, and the block's share of the counts and extremes.
  struct Block {
    int first_slot = 0, end_slot = 0;  // its slots: [first_slot, end_slot)
    std::size_t first_pair = 0, end_pair = 0, first_store = 0, hits = 0;
    std::vector<std::size_t> spilled;
    std::uint64_t failures = 0, reused = 0;
    double worst_q2 = 0.0, worst_v2 = 0.0;
    int worst_a = -1, worst_b = -1;
    DeepestOverlap deepest;
  };
  void sum_block(const Input& in, int c, std::span<contact::ContactCache::Entry> stores, std::uint64_t next_gen,
                 NeighbourLists& lists);
  void merge_blocks(std::size_t hits);

  std::vector<Block> blocks_;
  std::vector<Vec2> slot_force_;
  std::vector<double> slot_torque_;
  Totals totals_;
};

}  // namespace polyfloe::dynamics
