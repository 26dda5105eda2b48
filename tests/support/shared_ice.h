// What the tests of Worlds that share the ice (tests/unit/test_ghosts.cpp, tests/mpi/test_halo.cpp) share: the
// settings of their jostling packs, and the check that each World's own bodies are bitwise those of one World holding
// every body.
#pragma once

#include <gtest/gtest.h>

#include <cstring>
#include <string>
#include <utility>
#include <vector>

#include "dynamics/state_fields.h"
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

// Every field of a state as its name and its values' bytes (rows packed by their StateRow: no padding).
class StateBytes {
 public:
  std::vector<std::pair<std::string, std::vector<unsigned char>>> fields;
  template <class T>
  void attribute(const char* name, const T& x) {
    const std::vector<unsigned char> b = bytes(x);
    add(name) = b;
  }
  template <class T>
  void count(const char* name, const char*, const T& x, double) {
    attribute(name, x);
  }
  template <class T>
  void bodies(const char* name, const std::vector<T>& v) {
    rows(name, v);
  }
  template <class T>
  void bodies_or_none(const char* name, const std::vector<T>& v) {
    rows(name, v);
  }
  template <class T>
  void rows(const char* name, const std::vector<T>& v) {
    using Row = dynamics::StateRow<T>;
    std::vector<unsigned char>& out = add(name);
    typename Row::Scalar x[Row::width];
    for (const T& r : v) {
      Row::pack(r, x);
      const auto* p = reinterpret_cast<const unsigned char*>(x);
      out.insert(out.end(), p, p + sizeof x);
    }
  }
  template <class E>
  void history(const std::vector<E>& entries) {
    std::vector<unsigned char>& out = add("contact_history");
    for (const E& e : entries) {
      for (const auto& b : {bytes(e.first.lo), bytes(e.first.hi)}) out.insert(out.end(), b.begin(), b.end());
      const auto* p = reinterpret_cast<const unsigned char*>(&e.second);
      out.insert(out.end(), p, p + sizeof e.second);
    }
  }
  template <class F>
  void group(const char*, F&& f) {
    f();
  }
  template <class O, class F>
  void optional_group(const char* name, O& o, F&& f) {
    attribute(name, o.has_value());
    if (o) f(*o);
  }

 private:
  std::vector<unsigned char>& add(const char* name) {
    return fields.emplace_back(name, std::vector<unsigned char>{}).second;
  }
  template <class T>
  static std::vector<unsigned char> bytes(const T& x) {
    const auto* p = reinterpret_cast<const unsigned char*>(&x);
    return {p, p + sizeof x};
  }
};

// Every field of `a` bitwise that of `b` (a failure naming each field that is not).
inline void expect_same_state(const dynamics::WorldState& a, const dynamics::WorldState& b, const std::string& where) {
  StateBytes x, y;
  visit_fields(x, a);
  visit_fields(y, b);
  ASSERT_EQ(x.fields.size(), y.fields.size());
  for (std::size_t k = 0; k < x.fields.size(); ++k)
    EXPECT_TRUE(x.fields[k].second == y.fields[k].second)
        << where << ": the state's field " << x.fields[k].first << " differs (" << x.fields[k].second.size() << " and "
        << y.fields[k].second.size() << " bytes)";
}

}  // namespace polyfloe::tsupport
