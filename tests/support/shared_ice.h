// What the tests of Worlds that share the ice (tests/unit/test_ghosts.cpp, tests/mpi/test_halo.cpp) share: the
// settings of their jostling packs, and the check that each World's own bodies are bitwise those of one World holding
// every body.
#pragma once

#include <gtest/gtest.h>

#include <cstring>

#include "dynamics/world.h"
#include "forcing/analytic_fields.h"
#include "world_checks.h"

namespace polyfloe::tsupport {

// Stored in space order (their indices change as they drift); with `drift`, a uniform current of (0.3, 0.1) m/s
// (semi-implicit drag: the predicted velocities matter).
inline dynamics::WorldSettings shared_ice_settings(contact::ForceModel model, bool drift) {
  dynamics::WorldSettings ws = no_drift();
  ws.contact.force_model = model;
  ws.store_in_space_order = true;
  if (drift) {
    ws.drift = forcing::DriftSettings{};
    ws.drift.ocean = forcing::make_field(forcing::FieldSpec::uniform({0.3, 0.1}));
  }
  return ws;
}

inline bool same_bits(const auto& x, const auto& y) { return std::memcmp(&x, &y, sizeof(x)) == 0; }

// Every body `w` owns (not a ghost) has the pose, velocity, force and torque of the body of its id in `one`, bit for
// bit (a fatal failure at the first that does not); returns how many it owns.
inline std::size_t expect_owned_as_in_one(const dynamics::World& w, const dynamics::World& one, int step) {
  std::size_t owned = 0;
  for (int i = 0; i < static_cast<int>(w.size()); ++i) {
    if (w.is_ghost(i)) continue;
    ++owned;
    const int j = one.index_of(w.id(i));
    EXPECT_GE(j, 0) << "body " << w.id(i);
    if (j < 0) return owned;
    auto same = [&](const auto& x, const auto& y, const char* what) {
      if (!same_bits(x, y)) ADD_FAILURE() << what << " of body " << w.id(i) << " differs at step " << step;
      return same_bits(x, y);
    };
    if (!same(w.positions()[i], one.positions()[j], "the position") || !same(w.yaws()[i], one.yaws()[j], "the yaw") ||
        !same(w.velocities()[i], one.velocities()[j], "the velocity") ||
        !same(w.angular_velocities()[i], one.angular_velocities()[j], "the angular velocity") ||
        !same(w.forces()[i], one.forces()[j], "the force") || !same(w.torques()[i], one.torques()[j], "the torque"))
      return owned;
  }
  return owned;
}

}  // namespace polyfloe::tsupport
