// The state of a world as a list of named fields, for the code that stores or checks all of them: checkpoints
// (run/checkpoint.cpp writes and reads them by this list), the restores' size checks and the restart's finiteness
// check. Each world's state lists its fields once, in a visit_fields(v, state) next to its struct
// (dynamics/world.h, dynamics/spatial_world.h); a visitor is any object with these members (T the row type):
//
//   v.attribute(name, x)                x: double, bool, int or std::uint64_t, one value of the state
//   v.count(name, what, x, max)         x: std::uint64_t, a count in [0, max] (`what` names it in messages)
//   v.bodies(name, rows)                one row per body; the first, `ids`, fixes the number of bodies
//   v.bodies_or_none(name, rows)        one row per body, or none at all
//   v.rows(name, rows)                  rows of their own number (the bonds' faces and points)
//   v.history(entries)                  the contact history: std::vector<std::pair<contact::PairKey, Value>>
//   v.group(name, fields)               fields() visits the fields of a named group
//   v.optional_group(name, value, f)    f(*value) for a std::optional group that a state may not have
//
// A row type T has a StateRow<T>: how many scalars of which type make one row, and how to pack and unpack them.
#pragma once

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include <Eigen/Geometry>

#include "dynamics/body.h"
#include "dynamics/rows.h"
#include "forcing/drift.h"
#include "geometry/polyhedron.h"
#include "geometry/vec2.h"

namespace polyfloe::dynamics {

// Wall-clock seconds spent in each stage of step(), summed over steps. In the planar World `shapes` is the slot
// sort and one pass over the bodies: world-frame shapes, the velocity prediction the velocity-dependent forces are
// evaluated at, and between full drift evaluations the linear model's drift loads; `forcing` is the full drift
// evaluations. In the SpatialWorld `integrate` holds the kicks and the move with its world-frame vertices,
// `forcing` gravity and buoyancy.
struct StepProfile {
  double integrate = 0.0, shapes = 0.0, broad = 0.0, narrow_and_law = 0.0, forcing = 0.0, bonds = 0.0;
  std::uint64_t steps = 0;
  std::uint64_t candidates = 0, contacts = 0;  // broad-phase pairs and contacts, summed over the evaluations
  std::uint64_t reused = 0;  // contacts whose overlap was built from the topology kept from the step before
};

// One row of a state array: `width` values of type Scalar.
template <class T>
struct StateRow {
  static_assert(std::is_arithmetic_v<T>, "a state row is a number, a vector, a quaternion or a drift load");
  using Scalar = T;
  static constexpr int width = 1;
  static void pack(const T& v, Scalar* out) { out[0] = v; }
  static void unpack(const Scalar* in, T& v) { v = in[0]; }
};

template <>
struct StateRow<geometry::Vec2> {
  using Scalar = double;
  static constexpr int width = 2;
  static void pack(const geometry::Vec2& v, double* out) {
    out[0] = v.x();
    out[1] = v.y();
  }
  static void unpack(const double* in, geometry::Vec2& v) { v = {in[0], in[1]}; }
};

template <>
struct StateRow<geometry::Vec3> {
  using Scalar = double;
  static constexpr int width = 3;
  static void pack(const geometry::Vec3& v, double* out) {
    for (int k = 0; k < 3; ++k) out[k] = v[k];
  }
  static void unpack(const double* in, geometry::Vec3& v) { v = {in[0], in[1], in[2]}; }
};

template <>
struct StateRow<Eigen::Quaterniond> {  // (w, x, y, z)
  using Scalar = double;
  static constexpr int width = 4;
  static void pack(const Eigen::Quaterniond& q, double* out) {
    out[0] = q.w();
    out[1] = q.x();
    out[2] = q.y();
    out[3] = q.z();
  }
  static void unpack(const double* in, Eigen::Quaterniond& q) { q = Eigen::Quaterniond(in[0], in[1], in[2], in[3]); }
};

template <>
struct StateRow<forcing::DriftLoad> {  // force x, y, torque, dxx, dxy, dyy, dxw, dyw, dww, m f
  using Scalar = double;
  static constexpr int width = 10;
  static void pack(const forcing::DriftLoad& d, double* out) {
    const double v[10] = {d.force.x(), d.force.y(), d.torque, d.dxx, d.dxy, d.dyy, d.dxw, d.dyw, d.dww, d.mf};
    for (int k = 0; k < 10; ++k) out[k] = v[k];
  }
  static void unpack(const double* in, forcing::DriftLoad& d) {
    d.force = {in[0], in[1]};
    d.torque = in[2];
    d.dxx = in[3];
    d.dxy = in[4];
    d.dyy = in[5];
    d.dxw = in[6];
    d.dyw = in[7];
    d.dww = in[8];
    d.mf = in[9];
  }
};

// Rows as one flat array of their scalars (row after row), and back: how a state array is stored.
template <class T>
std::vector<typename StateRow<T>::Scalar> pack_rows(const std::vector<T>& rows) {
  std::vector<typename StateRow<T>::Scalar> flat(rows.size() * StateRow<T>::width);
  for (std::size_t i = 0; i < rows.size(); ++i) StateRow<T>::pack(rows[i], flat.data() + i * StateRow<T>::width);
  return flat;
}
template <class T>
std::vector<T> unpack_rows(const std::vector<typename StateRow<T>::Scalar>& flat) {
  std::vector<T> rows(flat.size() / StateRow<T>::width);
  for (std::size_t i = 0; i < rows.size(); ++i) StateRow<T>::unpack(flat.data() + i * StateRow<T>::width, rows[i]);
  return rows;
}

// Whether every value of a row is finite.
template <class T>
bool finite_row(const T& row) {
  typename StateRow<T>::Scalar v[StateRow<T>::width];
  StateRow<T>::pack(row, v);
  for (const auto x : v)
    if constexpr (std::is_floating_point_v<typename StateRow<T>::Scalar>)
      if (!std::isfinite(x)) return false;
  return true;
}

// A visitor of the per-body fields only: the others are passed over (the groups entered). Its subclass gives
// bodies() and bodies_or_none().
struct BodyFieldVisitor {
  template <class T>
  void attribute(const char*, const T&) {}
  template <class T>
  void count(const char*, const char*, const T&, double) {}
  template <class T>
  void rows(const char*, const std::vector<T>&) {}
  template <class E>
  void history(const std::vector<E>&) {}
  template <class F>
  void group(const char*, F&& fields) {
    fields();
  }
  template <class T, class F>
  void optional_group(const char*, const T&, F&&) {}
};

// Checks of a state's per-body arrays, by its field list: every one has a row per body (`bodies_or_none` ones may
// be empty) and, with `finite`, only finite values. `problem` is the first failure ("velocity has 1 entries for 2
// bodies", "position of body 7 is not finite"), empty when none.
class BodyRowCheck : public BodyFieldVisitor {
 public:
  explicit BodyRowCheck(bool finite) : finite_(finite) {}
  const std::string& problem() const { return problem_; }

  template <class T>
  void bodies(const char* name, const std::vector<T>& rows) {
    if (ids_ == nullptr) {  // the first per-body field: the ids
      if constexpr (std::is_same_v<T, std::uint64_t>)
        ids_ = &rows;
      else if (problem_.empty())
        problem_ = std::string("the state's first per-body field, ") + name + ", is not the body ids";
      return;
    }
    check(name, rows, false);
  }
  template <class T>
  void bodies_or_none(const char* name, const std::vector<T>& rows) {
    check(name, rows, true);
  }

 private:
  template <class T>
  void check(const char* name, const std::vector<T>& rows, bool may_be_empty) {
    if (!problem_.empty() || ids_ == nullptr) return;
    const std::size_t n = ids_->size();
    if (rows.size() != n && !(may_be_empty && rows.empty())) {
      problem_ =
          std::string(name) + " has " + std::to_string(rows.size()) + " entries for " + std::to_string(n) + " bodies";
      return;
    }
    if (!finite_) return;
    for (std::size_t i = 0; i < rows.size(); ++i)
      if (!finite_row(rows[i])) {
        problem_ = std::string(name) + " of body " + std::to_string((*ids_)[i]) + " is not finite";
        return;
      }
  }
  bool finite_;
  const std::vector<std::uint64_t>* ids_ = nullptr;
  std::string problem_;
};

// BodyRowCheck over `state` (a WorldState or SpatialWorldState; its visit_fields found by argument lookup).
template <class State>
std::string body_row_problem(const State& state, bool finite) {
  BodyRowCheck check(finite);
  visit_fields(check, state);
  return check.problem();
}

// Reorders every per-body field of a state (the `bodies` ones, and the `bodies_or_none` ones that are not empty):
// row k becomes row from[k] of before. The planar World's state() lists its bodies in id order with it, and its
// restore() takes a state's rows into the order the World stores its bodies in. Every field must have a row per body.
class BodyRowGather : public BodyFieldVisitor {
 public:
  explicit BodyRowGather(std::span<const int> from) : from_(from) {}

  template <class T>
  void bodies(const char*, std::vector<T>& rows) {
    gather(rows);
  }
  template <class T>
  void bodies_or_none(const char*, std::vector<T>& rows) {
    if (!rows.empty()) gather(rows);
  }

 private:
  template <class T>
  void gather(std::vector<T>& rows) {
    gather_rows(rows, from_);
  }
  std::span<const int> from_;
};

template <class State>
void gather_body_rows(State& state, std::span<const int> from) {
  BodyRowGather gather(from);
  visit_fields(gather, state);
}

}  // namespace polyfloe::dynamics

// A world's members that its state holds as plain copies, bound once: `bind(f)` calls f(&State::field, member) for
// each of them (each world's state_members), so that state() copies them out and restore() in from one list. The
// fields that are not plain copies (the contact history, the drift model, the bonds) each world moves itself.
template <class State, class Bind>
void copy_members_out(State& s, Bind&& bind) {
  bind([&s](auto field, const auto& member) { s.*field = member; });
}
template <class State, class Bind>
void copy_members_in(const State& s, Bind&& bind) {
  bind([&s](auto field, auto& member) { member = s.*field; });
}
