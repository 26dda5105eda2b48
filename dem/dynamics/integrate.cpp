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
    if (i < drift_load_.size() && drift_load_[i].has_damping()) {
      // Other forces, and Coriolis at v_n: the first half of its trapezoidal rule.
      const forcing::DriftLoad& d = drift_load_[i];
      f -= d.force + d.mf * geometry::perp_left(vel_[i]);
      t -= d.torque;
    }
    vel_[i] += (half_dt * inv_mass_[i]) * f;
    omega_[i] += half_dt * inv_inertia_[i] * t;
    if (motion_[i] != Motion::fixed) {
      pos_[i] += dt * vel_[i];
      yaw_[i] += dt * omega_[i];
    }
    changed = set_slot_key(ii) || changed;
    if (lists) outrun = !lists_.within(i, pos_[i], yaw_[i], reach_[i]) || outrun;
  }
  lists_.set_kick_verdict(!lists || outrun);
  return changed;
}

// A = M + dt D_drag + h C (C the Coriolis part m f [[0, -1], [1, 0]]) is positive definite (M > 0, D_drag >= 0,
// C antisymmetric), so the cofactor inverse of the 3 x 3 is safe.
World::DampedInverse World::damped_inverse(const forcing::DriftLoad& d, double dt, double mass, double inertia) {
  const double half_dt = 0.5 * dt;
  const double a00 = mass + dt * d.dxx, a01 = dt * d.dxy - half_dt * d.mf, a02 = dt * d.dxw;
  const double a10 = dt * d.dxy + half_dt * d.mf, a11 = mass + dt * d.dyy, a12 = dt * d.dyw;
  const double a20 = dt * d.dxw, a21 = dt * d.dyw, a22 = inertia + dt * d.dww;
  const double c00 = a11 * a22 - a12 * a21, c01 = a12 * a20 - a10 * a22, c02 = a10 * a21 - a11 * a20;
  // x = A^-1 f via the adjugate (transposed cofactors).
  return {{c00, a02 * a21 - a01 * a22, a01 * a12 - a02 * a11,  //
           c01, a00 * a22 - a02 * a20, a02 * a10 - a00 * a12,  //
           c02, a01 * a20 - a00 * a21, a00 * a11 - a01 * a10},
          1.0 / (a00 * c00 + a01 * c01 + a02 * c02)};
}

World::BodyVelocity World::apply(const DampedInverse& a, const Vec2& f1, double f2) {
  const double* m = a.adj;
  return {{(m[0] * f1.x() + m[1] * f1.y() + m[2] * f2) * a.inv_det,
           (m[3] * f1.x() + m[4] * f1.y() + m[5] * f2) * a.inv_det},
          (m[6] * f1.x() + m[7] * f1.y() + m[8] * f2) * a.inv_det};
}

World::BodyVelocity World::implicit_velocity(std::size_t i, double dt, const DampedInverse& a) const {
  // Drag linear in v with each sample's speed factor frozen at the prediction v*: F_d(v) = b - D v; Coriolis
  // F_c(v) = -C v. With F_o the other forces at the end of the step and v the half-kicked velocity
  // (v = v_n + h (F_o,n - C v_n) / m):
  //   M v_new = M v + h F_o + dt (b - D v_new) - h C v_new
  // i.e. backward Euler for drag (L-stable: no ringing at dt >> the relaxation time, and the steady state of the
  // step is the true balance F_o + b - D v - C v = 0) and the trapezoidal rule for Coriolis (a Cayley rotation:
  // the speed of an inertial oscillation is kept exactly).
  const forcing::DriftLoad& d = drift_load_[i];
  const double half_dt = 0.5 * dt;
  const Vec2 f_other = force_[i] - d.force;
  const double t_other = torque_[i] - d.torque;
  return apply(a, mass_[i] * vel_[i] + half_dt * f_other + dt * lin_force_[i],
               inertia_[i] * omega_[i] + half_dt * t_other + dt * lin_torque_[i]);
}

void World::set_linear_drift_load(std::size_t i, const Vec2& u, double w) {
  forcing::DriftLoad& d = drift_load_[i];
  const Eigen::Vector3d dv = d.damping_times(u, w);
  d.force = lin_force_[i] - dv.head<2>();
  d.torque = lin_torque_[i] - dv.z();
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
      forcing::DriftLoad& d = drift_load_[i];  // with lin_force_, set by compute_forces()
      if (!is_dynamic_[i] || !d.has_damping()) {
        vel_[i] += (half_dt * inv_mass_[i]) * force_[i];
        omega_[i] += half_dt * inv_inertia_[i] * torque_[i];
      } else {
        const BodyVelocity v = implicit_velocity(i, dt, inverse_of(i, dt));
        vel_[i] = v.u;
        omega_[i] = v.w;
        // The drift load at the new velocity (the linear model's), so force_ stays the total force.
        const Vec2 f_other = force_[i] - d.force;
        const double t_other = torque_[i] - d.torque;
        set_linear_drift_load(i, v.u, v.w);
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
  summary_ = MotionSummary{};
  for (const MotionSummary& b : motion_blocks_) summary_.merge(b);
  summary_ready_ = true;
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

void World::MotionSummary::merge(const MotionSummary& o) {
  all_finite &= o.all_finite;
  max_speed2 = std::max(max_speed2, o.max_speed2);
  max_spin_speed = std::max(max_spin_speed, o.max_spin_speed);
  energy += o.energy;
}

const World::MotionSummary& World::motion_summary() const {
  if (!summary_ready_) {
    // The same blocks as the final kick's, so that the sum has the same bits.
    const std::size_t n = size();
    motion_blocks_.assign((n + kSummaryBlock - 1) / kSummaryBlock, MotionSummary{});
    for (std::size_t i = 0; i < n; ++i) add_motion(i, motion_blocks_[i / kSummaryBlock]);
    merge_motion_blocks();
  }
  return summary_;
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
  boxes_[static_cast<std::size_t>(body_slot_[i])] = box;
}

namespace {

static_assert(contact::GridBroadPhase::kTile == geometry::kSpaceTile, "slots and the broad phase share their tiles");

bool slot_less(const auto& a, const auto& b) { return a.key != b.key ? a.key < b.key : a.body < b.body; }

}  // namespace

bool World::set_slot_key(int i) {
  SlotKey& slot = slots_[static_cast<std::size_t>(body_slot_[static_cast<std::size_t>(i)])];
  const std::uint64_t key = geometry::space_key(pos_[static_cast<std::size_t>(i)], order_cell_);
  const bool changed = key != slot.key;
  slot.key = key;
  return changed;
}

bool World::set_slot_keys() {
  const int n = static_cast<int>(size());
  bool changed = false;
  POLYFLOE_OMP_FOR_ANY(threads_, changed)
  for (int i = 0; i < n; ++i) changed = set_slot_key(i) || changed;
  return changed;
}

void World::sort_slots(bool keys_changed) {
  const int n = static_cast<int>(slots_.size());
  moved_.clear();
  if (!keys_changed) return;  // sorted by (key, body) as before: nothing moves (most steps)
  // Insertion sort from the last order: floes that keep their neighbours make it O(N). Past a budget of moves
  // (bodies crossing many others, or the first sort) a full sort; both give the one order sorted by (key, body).
  // Each move permutes the slots of an interval among themselves; overlapping intervals are merged, so that each
  // recorded interval holds the same bodies as before, whose vertices filled one block of world_xy_.
  std::size_t moves = 0;
  const std::size_t budget = 8 * static_cast<std::size_t>(n) + 64;
  for (int k = 1; k < n && moves <= budget; ++k) {
    if (!slot_less(slots_[k], slots_[k - 1])) continue;
    const SlotKey x = slots_[k];
    int j = k;
    for (; j > 0 && slot_less(x, slots_[j - 1]); --j) slots_[j] = slots_[j - 1];
    slots_[j] = x;
    moves += static_cast<std::size_t>(k - j);
    int first = j;
    while (!moved_.empty() && moved_.back().second >= first) {
      first = std::min(first, moved_.back().first);
      moved_.pop_back();
    }
    moved_.emplace_back(first, k);
  }
  if (moves > budget) {
    std::sort(slots_.begin(), slots_.end(), [](const SlotKey& a, const SlotKey& b) { return slot_less(a, b); });
    moved_.assign(1, {0, n - 1});
  }
  if (!moved_.empty()) lists_.note_slots_moved();
  // New layout of each moved interval: slot data and the bodies' places in their block of world_xy_ follow the
  // slot order; the fixed bodies there are redrawn (the others are every step).
  for (const auto& [first, last] : moved_) {
    int off = vert_begin_[slots_[first].body];
    for (int k = first + 1; k <= last; ++k) off = std::min(off, vert_begin_[slots_[k].body]);
    for (int k = first; k <= last; ++k) {
      const int i = slots_[k].body;
      body_slot_[i] = k;
      vert_begin_[i] = off;
      slot_static_[k] = slot_static_of(i, off);
      slot_dynamic_[k] = is_dynamic_[i];
      off += slot_static_[k].vert_count;
    }
    for (int k = first; k <= last; ++k)
      if (motion_[slots_[k].body] == Motion::fixed) update_shape(slots_[k].body);
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
