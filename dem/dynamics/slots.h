// The contact stage's slots: the planar World's bodies sorted by position (cells numbered tile by tile, as the
// broad phase numbers its cells; ties by index), so that bodies close in space are close in memory whatever order
// they were added in. Slots are private to the step; these are the records it keeps per slot.
#pragma once

#include <cstdint>

#include "dynamics/body.h"

namespace polyfloe::dynamics {

// A slot's sort key: the body's cell and the body.
struct SlotKey {
  std::uint64_t key = 0;
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
};

// The state of a slot's body, gathered every force evaluation.
struct SlotState {
  Vec2 pos{0.0, 0.0}, vel{0.0, 0.0};  // [m], [m/s] (velocity as evaluated)
  double omega = 0.0;                 // [rad/s]
};

}  // namespace polyfloe::dynamics
