// The planar contact stage: the broad phase's candidate pairs, each measured by the narrow phase and given its force
// by the contact law (apart, on any thread), then added up into per-slot forces and torques in pair order
// (ContactSum), so that the result has the same bits on any number of threads. It reads the bodies through a
// PlanarContactInput view and writes nothing of the World (as the drift stage reads DriftBodies and the bond stage
// an ElementState); the World adds its slot sums to the bodies.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "bonds/bond_set.h"
#include "contact/broad_phase.h"
#include "contact/contact_cache.h"
#include "contact/contact_law.h"
#include "dynamics/contact_sum.h"
#include "dynamics/neighbour_lists.h"
#include "dynamics/slots.h"

namespace polyfloe::dynamics {

// How a pair of level floes is measured.
enum class PlanarNarrowPhase {
  exact,    // the overlap polygon (contact/narrow_phase_planar.h): area, centroid, chord normal, depth = area/chord
  gjk_epa,  // the paper's method in the plane (contact/narrow_phase_gjk2d.h): the minimum translation's depth and
            // normal at the witness midpoint, for comparison; a failed query is measured by the exact method
};

// One active contact of the last step (for output and diagnostics).
struct ContactRecord {
  int a = 0, b = 0;  // body indices, ordered so that id(a) < id(b); the normal points from a to b
  ContactGeometry geometry;
  double normal_force = 0.0;      // [N], on b along +normal
  double tangential_force = 0.0;  // [N], on b along k x normal
  bool sliding = false;
  Vec2 force{0.0, 0.0};  // total contact force on b [N] (force_model gradient: the normal part follows
                         // the depth gradient, close to but not exactly along the normal)
  double energy = 0.0;   // elastic energy stored in the contact [J] (2/5 k_n d^2.5; foundation: kappa I)
  Vec2 force_on_b() const { return force; }
};

// A contact force evaluated by the World that owns a pair's lower-id body a, for the World that owns its other body
// b (a domain decomposition's: World::set_ghost): what b's sum adds, in its place among b's other contacts.
struct PairForce {
  BodyId a = 0, b = 0;  // ids, a < b
  Vec2 f{0.0, 0.0};     // on b [N]
  double tau_b = 0.0;   // on b [N m]
};

// What one contact evaluation reads of the bodies: the slots' records and state (slot order; the velocities as
// evaluated, the step's prediction), their world-frame vertices, and by body the inverse masses the foundation
// model's damping step reads.
struct PlanarContactInput {
  std::span<const SlotStatic> statics;
  std::span<const SlotState> states;
  std::span<const Vec2> world_xy;  // counter-clockwise, from statics[k].vert_begin
  // The foundation force model's edge lines of those polygons (contact::EdgeLines about each one's first vertex),
  // beside world_xy; empty: computed per pair.
  std::span<const double> edge_nx{}, edge_ny{}, edge_offset{};
  std::span<const double> inv_mass, inv_inertia;  // [1/kg], [1/(kg m^2)], 0 unless dynamic
  const bonds::BondSet* bonds = nullptr;          // pairs joined by an intact face skip the contact law
  PlanarNarrowPhase narrow_phase = PlanarNarrowPhase::exact;
  double dt = 0.0;             // the step [s]
  double overlap_limit = 0.5;  // the deepest overlap's limit, a fraction of the smaller equivalent radius
  int threads = 1;
};

class PlanarContactStage {
 public:
  // The broad phase: the pairs of slots whose boxes overlap now and that could touch, from `lists` (built where
  // they must be), sorted by slot.
  void find_pairs(const SlotView& view, const contact::ContactLaw& law, PlanarNarrowPhase narrow_phase, int threads,
                  NeighbourLists& lists);

  // The narrow phase and the contact law on every pair of the last find_pairs(), in parallel (each listed pair's
  // kept overlap topology is updated in `lists`; last step's histories are read from `cache`). A pair whose
  // lower-id body is a ghost is left to the World that owns that body (no contact until take_incoming()).
  void evaluate(const PlanarContactInput& in, const contact::ContactLaw& law, NeighbourLists& lists,
                const contact::ContactCache& cache);
  // Of the last evaluate(): the forces of the touching pairs whose higher-id body is a ghost, for the Worlds that
  // own those bodies, appended to `out` (in pair order).
  void outgoing(std::span<const SlotStatic> statics, std::vector<PairForce>& out) const;
  // The forces other Worlds evaluated for this World's bodies: each must be a candidate pair here, its lower-id
  // body a ghost and the other one not (std::logic_error otherwise: the ghosts do not cover the pairs).
  void take_incoming(std::span<const SlotStatic> statics, std::span<const PairForce> in);
  // The sum of the last evaluate() (ContactSum::sum: per-slot forces and torques, each touching pair's history
  // stored in `cache`): the counts and extremes of the sum, of the pairs evaluated here.
  const ContactSum::Totals& sum(const PlanarContactInput& in, NeighbourLists& lists, contact::ContactCache& cache);

  std::size_t candidates() const { return pairs_.size(); }                  // of the last find_pairs()
  const Vec2& slot_force(int slot) const { return sum_.slot_force(slot); }  // [N], of the last evaluate()
  double slot_torque(int slot) const { return sum_.slot_torque(slot); }     // [N m]
  // The last evaluation's touching pairs as records, in order of their ids (`statics` as it read them).
  void list_contacts(std::span<const SlotStatic> statics, std::vector<ContactRecord>& out) const;

  // Each thread's place in the contact history (ContactCache::previous with a hint), a cache line apart.
  struct alignas(64) CacheHint {
    std::size_t at = 0;
  };

 private:
  std::vector<contact::CandidatePair> pairs_;
  std::vector<PairResult> results_;
  std::vector<std::uint8_t> hit_;  // results_[p].hit, packed (2: a force from elsewhere): the sum's first pass reads it
  std::vector<PairForce> incoming_;  // scratch: take_incoming()'s, sorted by ids
  ContactSum sum_;
  std::vector<CacheHint> hints_;
  // The contact cache's generation the last sum stored under: where it is still the cache's and the lists stand,
  // each pair's history is found through its list entry; otherwise (after a build or a restore of the cache) by
  // key, for one evaluation.
  std::uint64_t history_gen_ = ~std::uint64_t{0};
};

}  // namespace polyfloe::dynamics
