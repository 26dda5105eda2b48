// Stage: velocity-Verlet kicks and moves, and the world-frame shapes that follow the bodies. (Velocity Verlet's
// "drift", the position update, is called the move here: drift is what wind and currents do to the ice.)
#include <algorithm>
#include <cmath>
#include <cstdint>

#include "dynamics/parallel.h"
#include "geometry/space_order.h"
#include "dynamics/world.h"

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
    Vec2 f = force_[i];
    double t = torque_[i];
    if (drift_.damped(i)) {
      // Other forces, and Coriolis at v_n: the first half of its trapezoidal rule.
      const forcing::DriftLoad& d = drift_.load(i);
      f -= d.force + d.mf * geometry::perp_left(vel_[i]);
      t -= d.torque;
    }
    vel_[i] += (half_dt * inv_mass_[i]) * f;
    omega_[i] += half_dt * inv_inertia_[i] * t;
    if (motion_[i] != Motion::fixed) {
      pos_[i] += dt * vel_[i];
      yaw_[i] += dt * omega_[i];
    }
    changed = order_.set_key(ii, pos_[i]) || changed;
    if (lists) outrun = !lists_.within(i, pos_[i], yaw_[i], reach_[i]) || outrun;
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
      const forcing::DriftLoad& d = drift_.load(i);  // and its linear model, set by compute_forces()
      if (!is_dynamic_[i] || !d.has_damping()) {
        vel_[i] += (half_dt * inv_mass_[i]) * force_[i];
        omega_[i] += half_dt * inv_inertia_[i] * torque_[i];
      } else {
        // Drag linear in v with each sample's speed factor frozen at the prediction v*: F_d(v) = b - D v;
        // Coriolis F_c(v) = -C v. With F_o the other forces at the end of the step and v the half-kicked velocity
        // (v = v_n + h (F_o,n - C v_n) / m):
        //   M v_new = M v + h F_o + dt (b - D v_new) - h C v_new
        // i.e. backward Euler for drag (L-stable: no ringing at dt >> the relaxation time, and the steady state of
        // the step is the true balance F_o + b - D v - C v = 0) and the trapezoidal rule for Coriolis (a Cayley
        // rotation: the speed of an inertial oscillation is kept exactly).
        const DriftModel::Velocity v =
            drift_.implicit_velocity(i, dt, drift_.inverse_of(i, dt, mass_[i], inertia_[i]), mass_[i], inertia_[i],
                                     vel_[i], omega_[i], force_[i], torque_[i]);
        vel_[i] = v.u;
        omega_[i] = v.w;
        // The drift load at the new velocity (the linear model's), so force_ stays the total force.
        const Vec2 f_other = force_[i] - d.force;
        const double t_other = torque_[i] - d.torque;
        drift_.set_linear_load(i, v.u, v.w);
        force_[i] = f_other + d.force;
        torque_[i] = t_other + d.torque;
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
  // A NaN or infinity anywhere in the pose or the velocity makes the sum non-finite.
  s.all_finite &= std::isfinite(pos_[i].x() + pos_[i].y() + yaw_[i] + vel_[i].x() + vel_[i].y() + omega_[i]);
  if (!is_dynamic_[i]) return;
  const double v2 = vel_[i].squaredNorm();
  s.max_speed2 = std::max(s.max_speed2, v2);
  s.max_spin_speed = std::max(s.max_spin_speed, std::abs(omega_[i]) * reach_[i]);
  s.energy += 0.5 * mass_[i] * v2 + 0.5 * inertia_[i] * omega_[i] * omega_[i];
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
  const double c = std::cos(yaw_[i]), s = std::sin(yaw_[i]);
  rotation_[i] = {c, s};
  const Vec2* local = local_xy_.data() + vert_off_[i];
  const int count = vert_off_[i + 1] - vert_off_[i];
  Vec2* out = world_xy_.data() + vert_begin_[i];
  const Vec2 p = pos_[i];  // (held in a register: the stores to `out` could otherwise alias it)
  geometry::Aabb box{p, p};
  for (int k = 0; k < count; ++k) {
    out[k] = p + geometry::rotate(local[k], c, s);
    box.lo = box.lo.cwiseMin(out[k]);
    box.hi = box.hi.cwiseMax(out[k]);
  }
  boxes_[static_cast<std::size_t>(order_.slot_of(i))] = box;
}

static_assert(contact::GridBroadPhase::kTile == geometry::kSpaceTile, "slots and the broad phase share their tiles");

bool World::set_slot_keys() {
  const int n = static_cast<int>(size());
  bool changed = false;
  POLYFLOE_OMP_FOR_ANY(threads_, changed)
  for (int i = 0; i < n; ++i) changed = order_.set_key(i, pos_[static_cast<std::size_t>(i)]) || changed;
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
      slot_dynamic_[k] = is_dynamic_[i];
      off += slot_static_[k].vert_count;
    }
    for (int k = first; k <= last; ++k)
      if (motion_[order_.body_at(k)] == Motion::fixed) update_shape(order_.body_at(k));
  }
}

void World::update_shapes() {
  sort_slots(set_slot_keys());
  const int n = static_cast<int>(size());
  POLYFLOE_OMP_FOR(threads_)
  for (int i = 0; i < n; ++i)
    if (motion_[i] != Motion::fixed) update_shape(i);
}

}  // namespace polyfloe::dynamics
