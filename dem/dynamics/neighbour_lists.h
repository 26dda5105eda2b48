// The planar World's broad phase: neighbour lists ("Verlet lists") over the grid of contact/broad_phase.h.
//
// The lists hold the pairs of slots whose boxes, grown by half the skin on every side, overlapped at the last build,
// each pair once, in its lower slot's list; they stay valid while no vertex has moved more than half the skin since
// (then every pair whose boxes overlap now is among them). Each listed pair also carries what the contact stage
// keeps for it from one evaluation to the next: its distance at the build (from below), the topology of its overlap
// at its last contact, its contact-law coefficients, and where its contact history was stored.
//
// candidate_pairs() answers, from the lists, the slot pairs whose boxes overlap now and that could touch, sorted
// by slot: a function of the current state alone, whenever the lists were built, so that a restarted run and any
// number of threads take the same contacts in the same order.
#pragma once

#include <cmath>
#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include "contact/broad_phase.h"
#include "contact/contact_law.h"
#include "contact/narrow_phase_planar.h"
#include "dynamics/slots.h"
#include "geometry/vec2.h"

namespace polyfloe::dynamics {

// What the lists read of the World's step (views; by slot unless said).
struct SlotView {
  std::span<const SlotKey> slots;         // slot -> body
  std::span<const int> body_slot;         // by body: body -> slot
  std::span<const SlotStatic> statics;    // packed body data
  std::span<const geometry::Aabb> boxes;  // world-frame bounding boxes
  std::span<const std::uint8_t> dynamic;  // whether the slot's body is dynamic
  std::span<const Vec2> world_xy;         // world-frame vertices (SlotStatic::vert_begin, vert_count)
  std::span<const Vec2> position;         // by body [m]
  std::span<const double> yaw;            // by body [rad]
  std::span<const double> reach;          // by body: circumradius about the centroid [m]
};

class NeighbourLists {
 public:
  // `cell`: the grid's cell size [m] (0 = automatic; contact::GridBroadPhase).
  explicit NeighbourLists(double cell) : grid_(cell) {}

  // The skin [m]: a speed knob only (the pairs found, their order and so every result are the same for any value).
  void set_skin(double skin) { skin_ = skin; }
  double skin() const { return skin_; }

  // Forget the lists (bodies added): the next candidate_pairs() builds them.
  void invalidate() {
    pos_.clear();
    kick_verdict_.reset();
  }
  // Whether lists were built for n bodies.
  bool built_for(std::size_t n) const { return pos_.size() == n; }
  // Body i at pose (position, yaw) with circumradius `reach`: notes how far its vertices may have moved since the
  // build, and returns whether that is within half the skin. A rotation by dθ moves a vertex at r by
  // 2 r sin(dθ/2) <= r |dθ|. For lists built_for() the bodies present.
  bool within(std::size_t i, const Vec2& position, double yaw, double reach) {
    const double moved = (position - pos_[i]).norm() + std::abs(yaw - yaw_[i]) * reach;
    moved_[i] = moved;
    return moved <= 0.5 * skin_;  // NaN counts as too far
  }
  // The verdict of a pass over every body's within() at the current poses (the integrator's, which has the bodies
  // at hand), for the next candidate_pairs() to take once instead of a pass of its own; forgotten when the poses
  // change from outside.
  void set_kick_verdict(bool outrun) { kick_verdict_ = outrun; }
  void forget_kick_verdict() { kick_verdict_.reset(); }
  // Some slot changed bodies (the slots were re-sorted): the pairs may come out of order until the next build.
  void note_slots_moved() { slots_moved_ = true; }

  // The candidate pairs now, into `pairs` (slot pairs (a, b), a < b, sorted by a, then b; `entry` their list
  // entry), building the lists first where a body has outrun the skin. `exact`: the pairs' distances at the build
  // may skip pairs (the exact narrow phase's); `law` gives each listed pair's coefficients. `threads` >= 1.
  void candidate_pairs(const SlotView& v, const contact::ContactLaw& law, bool exact, int threads,
                       std::vector<contact::CandidatePair>& pairs);

  // Whether the lists were built in the last candidate_pairs() (their entries have no history yet).
  bool fresh() const { return fresh_; }
  // A listed pair's kept overlap topology (contact::planar_overlap reads and updates it) and its coefficients.
  contact::OverlapTopology& topology(int entry) { return topology_[static_cast<std::size_t>(entry)]; }
  const contact::PairCoefficients& coefficients(int entry) const {
    return coefficients_[static_cast<std::size_t>(entry)];
  }
  // Where a listed pair's contact history was stored among the contact cache's stores, and under which of its
  // generations (ContactCache::stored): while the lists stand, a pair finds last step's history without a lookup.
  void set_store(int entry, std::uint32_t store, std::uint64_t generation) {
    store_[static_cast<std::size_t>(entry)] = store;
    store_generation_[static_cast<std::size_t>(entry)] = generation;
  }
  std::uint32_t store(int entry) const { return store_[static_cast<std::size_t>(entry)]; }
  std::uint64_t store_generation(int entry) const { return store_generation_[static_cast<std::size_t>(entry)]; }

  // How often the lists were built (a diagnostic of the skin).
  std::uint64_t builds() const { return builds_; }

 private:
  // Whether some body has outrun the skin since the build (the kick's verdict where there is one).
  bool outrun(const SlotView& v, int threads);
  void build(const SlotView& v, const contact::ContactLaw& law, bool exact, int threads,
             std::vector<contact::CandidatePair>& pairs);
  // The grid's pairs of `boxes` (by slot) into `pairs`: on one thread, or the scan split between threads.
  void grid_pairs(std::span<const geometry::Aabb> boxes, std::span<const std::uint8_t> dynamic, int threads,
                  std::vector<contact::CandidatePair>& pairs);
  // `pairs` = the first `chunks` lists of chunks_, in order.
  void join_chunks(int chunks, std::vector<contact::CandidatePair>& pairs);

  contact::GridBroadPhase grid_;
  double skin_ = 0.0;      // [m]
  std::vector<Vec2> pos_;  // poses at the last build, by body (empty: no lists)
  std::vector<double> yaw_;
  std::vector<double> moved_;  // by body: how far its vertices may have moved since the build [m]
  std::optional<bool> kick_verdict_;
  bool slots_moved_ = true;  // some slot changed bodies since the build
  bool fresh_ = true;
  // The lists by the build's slots (CSR; each pair once, in its lower slot's list), and the build's slot -> body
  // and body -> slot.
  std::vector<int> off_, adj_, body_, slot_;
  // Per listed pair: its distance at the build from below, less a margin [m]; its overlap's topology at its last
  // contact (unknown after a build); its contact-law coefficients (a function of the two bodies' radii and masses
  // alone, so computed once per build, in the same arithmetic as per contact); where its history was stored.
  std::vector<double> gap_;
  std::vector<contact::OverlapTopology> topology_;
  std::vector<contact::PairCoefficients> coefficients_;
  std::vector<std::uint32_t> store_;
  std::vector<std::uint64_t> store_generation_;
  std::vector<geometry::Aabb> grown_;                        // scratch: the boxes grown by half the skin
  std::vector<std::vector<contact::CandidatePair>> chunks_;  // scratch: the scans of the threads
  std::uint64_t builds_ = 0;
};

}  // namespace polyfloe::dynamics
