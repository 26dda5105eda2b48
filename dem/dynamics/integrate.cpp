// Stage: velocity-Verlet kicks and moves, and the world-frame shapes that follow the bodies. (Velocity Verlet's
// "drift", the position update, is called the move here: drift is what wind and currents do to the ice.)
#include <algorithm>
#include <cmath>
#include <cstdint>

#include "dynamics/parallel.h"
#include "geometry/space_order.h"
#include "dynamics/world.h"
#include "dynamics/rows.h"

namespace polyfloe::dynamics {

// The first half kick and the move, in one pass over the bodies. Where drag and Coriolis are treated
// semi-implicitly (bodies whose drift load has a damping matrix), drag enters only the final kick (kick_implicit),
// over the whole step; the first half kick applies the other forces and Coriolis at the start-of-step velocity.
// The same pass writes each body's slot key at its new position (sort_slots' first part).
bool World::kick_and_move(double dt) {
  const double half_dt = 0.5 * dt;
  const int n = static_cast<int>(size());
  bool changed = false;
  // And how far each body's vertices may have moved since the neighbour lists were built (their test, done here
  // while the body is at hand: the contact stage then needs no pass of its own).
  const bool lists = lists_.built_for(size());
  bool outrun = false;
  POLYFLOE_OMP_FOR_ANY(threads_, changed, outrun)
  for (int ii = 0; ii < n; ++ii) {
    const std::size_t i = static_cast<std::size_t>(ii);
    if (bodies_.ghost[i]) continue;  // moved by its owner (set_ghost_pose)
    Vec2 f = bodies_.force[i];
    double t = bodies_.torque[i];
    if (drift_.damped(i)) {
      // Other forces, and Coriolis at v_n: the first half of its trapezoidal rule.
      const forcing::DriftLoad& d = drift_.load(i);
      f -= d.force + d.mf * geometry::perp_left(bodies_.vel[i]);
      t -= d.torque;
    }
    bodies_.vel[i] += (half_dt * bodies_.inv_mass[i]) * f;
    bodies_.omega[i] += half_dt * bodies_.inv_inertia[i] * t;
    if (bodies_.motion[i] != Motion::fixed) {
      bodies_.pos[i] += dt * bodies_.vel[i];
      bodies_.yaw[i] += dt * bodies_.omega[i];
    }
    changed = order_.set_key(ii, bodies_.pos[i]) || changed;
    if (lists) outrun = !lists_.within(i, bodies_.pos[i], bodies_.yaw[i], bodies_.reach[i]) || outrun;
  }
  lists_.set_kick_verdict(!lists || outrun);
  return changed;
}

void World::kick_implicit(double dt) {
  const double half_dt = 0.5 * dt;
  const int n = static_cast<int>(size());
  // By blocks of bodies, each adding its bodies' motion to its share of the run guard's summary as it goes.
  const int blocks = (n + kSummaryBlock - 1) / kSummaryBlock;
  motion_blocks_.resize(static_cast<std::size_t>(blocks));
  POLYFLOE_OMP_FOR(threads_)
  for (int blk = 0; blk < blocks; ++blk) {
    MotionSummary sum;
    for (int ii = blk * kSummaryBlock, end = std::min(n, ii + kSummaryBlock); ii < end; ++ii) {
      const std::size_t i = static_cast<std::size_t>(ii);
      if (bodies_.ghost[i]) continue;                // integrated by its owner
      const forcing::DriftLoad& d = drift_.load(i);  // and its linear model, set by compute_forces()
      if (!bodies_.is_dynamic[i] || !d.has_damping()) {
        bodies_.vel[i] += (half_dt * bodies_.inv_mass[i]) * bodies_.force[i];
        bodies_.omega[i] += half_dt * bodies_.inv_inertia[i] * bodies_.torque[i];
      } else {
        // Drag linear in v with each sample's speed factor frozen at the prediction v*: F_d(v) = b - D v;
        // Coriolis F_c(v) = -C v. With F_o the other forces at the end of the step and v the half-kicked velocity
        // (v = v_n + h (F_o,n - C v_n) / m):
        //   M v_new = M v + h F_o + dt (b - D v_new) - h C v_new
        // i.e. backward Euler for drag (L-stable: no ringing at dt >> the relaxation time, and the steady state of
        // the step is the true balance F_o + b - D v - C v = 0) and the trapezoidal rule for Coriolis (a Cayley
        // rotation: the speed of an inertial oscillation is kept exactly).
        const DriftModel::Velocity v = drift_.implicit_velocity(
            i, dt, drift_.inverse_of(i, dt, bodies_.mass[i], bodies_.inertia[i]), bodies_.mass[i], bodies_.inertia[i],
            bodies_.vel[i], bodies_.omega[i], bodies_.force[i], bodies_.torque[i]);
        bodies_.vel[i] = v.u;
        bodies_.omega[i] = v.w;
        // The drift load at the new velocity (the linear model's), so bodies_.force stays the total force.
        const Vec2 f_other = bodies_.force[i] - d.force;
        const double t_other = bodies_.torque[i] - d.torque;
        drift_.set_linear_load(i, v.u, v.w);
        bodies_.force[i] = f_other + d.force;
        bodies_.torque[i] = t_other + d.torque;
      }
      add_motion(i, sum);
    }
    motion_blocks_[static_cast<std::size_t>(blk)] = sum;
  }
  merge_motion_blocks();
}

void World::merge_motion_blocks() const {
  report_.motion = MotionSummary{};
  for (const MotionSummary& b : motion_blocks_) report_.motion.merge(b);
  motion_ready_ = true;
}

void World::add_motion(std::size_t i, MotionSummary& s) const {
  if (bodies_.ghost[i]) return;  // its owner's
  // A NaN or infinity anywhere in the pose or the velocity makes the sum non-finite.
  s.all_finite &= std::isfinite(bodies_.pos[i].x() + bodies_.pos[i].y() + bodies_.yaw[i] + bodies_.vel[i].x() +
                                bodies_.vel[i].y() + bodies_.omega[i]);
  if (!bodies_.is_dynamic[i]) return;
  const double v2 = bodies_.vel[i].squaredNorm();
  s.max_speed2 = std::max(s.max_speed2, v2);
  s.max_spin_speed = std::max(s.max_spin_speed, std::abs(bodies_.omega[i]) * bodies_.reach[i]);
  s.energy += 0.5 * bodies_.mass[i] * v2 + 0.5 * bodies_.inertia[i] * bodies_.omega[i] * bodies_.omega[i];
}

const StepReport& World::report() const {
  if (!motion_ready_) {
    // The same blocks as the final kick's, so that the sum has the same bits.
    const std::size_t n = size();
    motion_blocks_.assign((n + kSummaryBlock - 1) / kSummaryBlock, MotionSummary{});
    for (std::size_t i = 0; i < n; ++i) add_motion(i, motion_blocks_[i / kSummaryBlock]);
    merge_motion_blocks();
  }
  return report_;
}

void World::update_shape(int i) {
  const double c = std::cos(bodies_.yaw[i]), s = std::sin(bodies_.yaw[i]);
  rotation_[i] = {c, s};
  const Vec2* local = bodies_.local_xy.data() + bodies_.vert_off[i];
  const int count = bodies_.vert_off[i + 1] - bodies_.vert_off[i];
  Vec2* out = world_xy_.data() + vert_begin_[i];
  const Vec2 p = bodies_.pos[i];  // (held in a register: the stores to `out` could otherwise alias it)
  geometry::Aabb box{p, p};
  for (int k = 0; k < count; ++k) {
    out[k] = p + geometry::rotate(local[k], c, s);
    box.lo = box.lo.cwiseMin(out[k]);
    box.hi = box.hi.cwiseMax(out[k]);
  }
  if (!edge_nx_.empty())
    contact::edge_lines({out, static_cast<std::size_t>(count)}, edge_nx_.data() + vert_begin_[i],
                        edge_ny_.data() + vert_begin_[i], edge_offset_.data() + vert_begin_[i]);
  boxes_[static_cast<std::size_t>(order_.slot_of(i))] = box;
}

static_assert(contact::GridBroadPhase::kTile == geometry::kSpaceTile, "slots and the broad phase share their tiles");

bool World::set_slot_keys() {
  const int n = static_cast<int>(size());
  bool changed = false;
  POLYFLOE_OMP_FOR_ANY(threads_, changed)
  for (int i = 0; i < n; ++i) changed = order_.set_key(i, bodies_.pos[static_cast<std::size_t>(i)]) || changed;
  return changed;
}

void World::sort_slots(bool keys_changed) {
  const std::vector<std::pair<int, int>>& moved = order_.sort(keys_changed);
  if (!moved.empty()) lists_.note_slots_moved();
  // New layout of each moved interval: slot data and the bodies' places in their block of world_xy_ follow the
  // slot order; the fixed bodies there are redrawn (the others are every step).
  for (const auto& [first, last] : moved) {
    int off = vert_begin_[order_.body_at(first)];
    for (int k = first + 1; k <= last; ++k) off = std::min(off, vert_begin_[order_.body_at(k)]);
    for (int k = first; k <= last; ++k) {
      const int i = order_.body_at(k);
      vert_begin_[i] = off;
      slot_static_[k] = slot_static_of(i, off);
      slot_dynamic_[k] = bodies_.is_dynamic[i];
      off += slot_static_[k].vert_count;
    }
    for (int k = first; k <= last; ++k)
      if (bodies_.motion[order_.body_at(k)] == Motion::fixed) update_shape(order_.body_at(k));
    slots_moved_since_store_ += static_cast<std::size_t>(last - first + 1);
  }
  if (settings_.store_in_space_order && 8 * slots_moved_since_store_ >= size() && !moved.empty()) store_in_slot_order();
}

void World::store_in_slot_order() {
  const std::size_t n = size();
  std::vector<int> from(n), to(n);  // body k is body from[k] of before; body i becomes body to[i]
  for (std::size_t k = 0; k < n; ++k) {
    from[k] = order_.body_at(static_cast<int>(k));
    to[static_cast<std::size_t>(from[k])] = static_cast<int>(k);
  }
  bodies_.permute(from);
  drift_.permute(from);
  gather_rows(vert_begin_, from);  // (world_xy_ stays: its blocks are in slot order already)
  gather_rows(rotation_, from);
  if (bond_mass_.size() == n) gather_rows(bond_mass_, from);
  if (bonds_) bonds_->renumber(to);
  order_.bodies_in_slot_order();
  for (std::size_t k = 0; k < n; ++k) slot_static_[k].body = static_cast<int>(k);
  lists_.invalidate();      // their per-body records: rebuilt at the next evaluation
  by_id_ready_ = false;     // id_order() anew
  contacts_ready_ = false;  // the records listed anew, with the new indices
  slots_moved_since_store_ = 0;
  ++reorders_;
}

void World::update_shapes() {
  sort_slots(set_slot_keys());
  const int n = static_cast<int>(size());
  POLYFLOE_OMP_FOR(threads_)
  for (int i = 0; i < n; ++i)
    if (bodies_.motion[i] != Motion::fixed) update_shape(i);
}

}  // namespace polyfloe::dynamics
