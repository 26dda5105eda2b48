// The contact stage's slots: the planar World's bodies sorted by position (cells numbered tile by tile, as the
// broad phase numbers its cells; ties by id, so that the order does not depend on where the bodies are stored), so that bodies close in space are close in memory whatever order
// they were added in. Slots are private to the step; these are the records it keeps per slot.
#pragma once

#include <cstddef>
#include <cstdint>
#include <utility>
#include <vector>

#include "dynamics/body.h"
#include "geometry/space_order.h"

namespace polyfloe::dynamics {

// A slot's sort key: the body's cell and its id; and the body (its index).
struct SlotKey {
  std::uint64_t key = 0;
  BodyId id = 0;
  int body = 0;
};

// A packed copy of the body data the pair loop reads; rewritten where the order changes.
struct SlotStatic {
  double mass = 0.0;               // [kg], +inf unless dynamic
  double radius = 0.0;             // [m], +inf unless dynamic
  double equivalent_radius = 0.0;  // sqrt(area / pi), also for walls [m]
  BodyId id = 0;
  int body = 0;        // body index
  int vert_begin = 0;  // into the World's world-frame vertices
  int vert_count = 0;
  std::uint8_t ghost = 0;  // a copy of a body another World owns (World::set_ghost): its pairs with lower ids are
                           // evaluated there
};

// The state of a slot's body, gathered every force evaluation.
struct SlotState {
  Vec2 pos{0.0, 0.0}, vel{0.0, 0.0};  // [m], [m/s] (velocity as evaluated)
  double omega = 0.0;                 // [rad/s]
};

// The order of the slots: which body each slot holds, sorted by (key, id), the key a body's cell at its position
// (geometry::space_key: cells of cell() numbered tile by tile). The order is a function of the current positions
// and the ids alone, not of the bodies' indices (restarts reproduce it); it is re-sorted by insertion from the last order, O(N) while floes keep their
// neighbours.
class SlotOrder {
 public:
  std::size_t size() const { return slots_.size(); }
  double cell() const { return cell_; }  // [m]
  void set_cell(double cell) { cell_ = cell; }

  // A new body takes the last slot, its key unset (above every key: the next sort places it).
  void add(int body, BodyId id) {
    slots_.push_back({~std::uint64_t{0}, id, body});
    body_slot_.push_back(static_cast<int>(slots_.size()) - 1);
  }
  // Body i's key at `position`; whether it changed.
  bool set_key(int i, const Vec2& position) {
    SlotKey& slot = slots_[static_cast<std::size_t>(body_slot_[static_cast<std::size_t>(i)])];
    const std::uint64_t key = geometry::space_key(position, cell_);
    const bool changed = key != slot.key;
    slot.key = key;
    return changed;
  }
  // The World stored its bodies in slot order (body k is the one slot k held): slot k holds body k.
  void bodies_in_slot_order() {
    for (std::size_t k = 0; k < slots_.size(); ++k) {
      slots_[k].body = static_cast<int>(k);
      body_slot_[k] = static_cast<int>(k);
    }
  }
  int slot_of(int body) const { return body_slot_[static_cast<std::size_t>(body)]; }
  int body_at(int slot) const { return slots_[static_cast<std::size_t>(slot)].body; }
  const std::vector<SlotKey>& slots() const { return slots_; }       // slot -> body
  const std::vector<int>& body_slots() const { return body_slot_; }  // body -> slot

  // Sorts the slots by (key, id) where `keys_changed` (set_key said so for some body since the last sort), and
  // returns the intervals of slots [first, last] it permuted, each holding the same bodies as before (overlapping
  // moves merged), in increasing order; slot_of() follows. Past a budget of moves (bodies crossing many others, or
  // the first sort) a full sort, reported as one interval: the order is the same either way.
  const std::vector<std::pair<int, int>>& sort(bool keys_changed);

 private:
  double cell_ = 1.0;                       // [m]
  std::vector<SlotKey> slots_;              // slot -> body, sorted by (key, id)
  std::vector<int> body_slot_;              // body -> slot
  std::vector<std::pair<int, int>> moved_;  // what the last sort permuted
};

}  // namespace polyfloe::dynamics
