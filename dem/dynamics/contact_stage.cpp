// Stage: broad phase, planar narrow phase and the contact law, accumulated into forces and torques.
#include <chrono>
#include <cmath>
#include <algorithm>
#include <utility>

#include "dynamics/parallel.h"
#include "dynamics/world.h"

namespace polyfloe::dynamics {

void World::contact_forces(double dt) {
  using clock = std::chrono::steady_clock;
  const auto t0 = clock::now();
  // Everything below works on slots (bodies sorted by position, world.h): the pairs, the bodies' hot state and
  // the force sums are read and written in memory order close to the order of space.
  if (threads_ == 1) {
    broad_.find_pairs(boxes_, slot_dynamic_, pairs_);
  } else {
    // The grid's scan split into consecutive tile ranges, scanned in parallel and concatenated in order: the same
    // list as the serial scan.
    broad_.build(boxes_, slot_dynamic_);
    const std::size_t tiles = broad_.tile_count();
    const int chunks = static_cast<int>(std::min<std::size_t>(tiles, 8 * static_cast<std::size_t>(threads_)));
    pair_chunks_.resize(static_cast<std::size_t>(std::max(chunks, 1)));
    POLYFLOE_OMP_FOR_DYNAMIC(threads_)
    for (int c = 0; c < chunks; ++c) {
      std::vector<contact::CandidatePair>& out = pair_chunks_[static_cast<std::size_t>(c)];
      out.clear();
      broad_.scan_tiles(tiles * c / chunks, tiles * (c + 1) / chunks, out);
    }
    pairs_.clear();
    for (int c = 0; c < chunks; ++c)
      pairs_.insert(pairs_.end(), pair_chunks_[static_cast<std::size_t>(c)].begin(),
                    pair_chunks_[static_cast<std::size_t>(c)].end());
  }
  const auto t1 = clock::now();

  const int n = static_cast<int>(size());
  slot_state_.resize(static_cast<std::size_t>(n));
  POLYFLOE_OMP_FOR(threads_)
  for (int k = 0; k < n; ++k) {
    const int i = slots_[k].body;
    slot_state_[k] = {pos_[i], vel_eval_[i], omega_eval_[i]};
  }

  // Every candidate pair evaluated apart (in parallel: the cache is only read here), then added up in the broad
  // phase's order on one thread, so the sums, the stored springs and the contact list do not depend on the threads.
  const std::size_t np = pairs_.size();
  pair_results_.resize(np);
  const bool gradient = law_.settings().force_model == contact::ForceModel::gradient;
  const bool gjk = settings_.narrow_phase == PlanarNarrowPhase::gjk_epa;
  const int np_int = static_cast<int>(np);
  cache_hint_.assign(static_cast<std::size_t>(threads_), CacheHint{});
  POLYFLOE_OMP_FOR(threads_)
  for (int p = 0; p < np_int; ++p) {
    PairResult& r = pair_results_[static_cast<std::size_t>(p)];
    r.hit = false;
    r.fallback = false;
    // Orient every pair by id so the stored spring has one meaning whatever the index order.
    int a = pairs_[p].a, b = pairs_[p].b;
    if (slot_static_[a].id > slot_static_[b].id) std::swap(a, b);
    const SlotStatic& A = slot_static_[a];
    const SlotStatic& B = slot_static_[b];
    if (bonds_ && bonds_->bonded(A.body, B.body)) continue;  // frozen together: the bond carries the load
    const std::span<const Vec2> verts_a{world_xy_.data() + A.vert_begin, static_cast<std::size_t>(A.vert_count)};
    const std::span<const Vec2> verts_b{world_xy_.data() + B.vert_begin, static_cast<std::size_t>(B.vert_count)};
    contact::PlanarContact g;
    if (gjk) {
      // The minimum translation at the witness midpoint; no overlap polygon, so the gradient force model sees the
      // plain normal (its containment fallback).
      const contact::Gjk2dContact m = contact::gjk_epa_2d(verts_a, verts_b);
      if (m.status == contact::Gjk2dStatus::separated) continue;
      if (m.status == contact::Gjk2dStatus::contact) {
        g = contact::PlanarContact{};
        g.normal = m.normal;
        g.point = m.point;
        g.depth = m.depth;
      } else {
        r.fallback = true;
        if (!contact::planar_overlap(verts_a, verts_b, g, gradient)) continue;
      }
    } else if (!contact::planar_overlap(verts_a, verts_b, g, gradient)) {
      continue;
    }

    const SlotState& sa = slot_state_[a];
    const SlotState& sb = slot_state_[b];
    const Vec2 t = geometry::perp_left(g.normal);
    const Vec2 ra = g.point - sa.pos, rb = g.point - sb.pos;  // centroid relative to each body
    const Vec2 va = sa.vel + sa.omega * geometry::perp_left(ra);
    const Vec2 vb = sb.vel + sb.omega * geometry::perp_left(rb);
    const Vec2 v_rel = vb - va;

    const Vec2 da = -ra, db = -rb;  // body centres relative to the centroid
    // Normal direction on b (per unit normal force) and its moment about b's centre, and the depth rate.
    Vec2 dir_b;
    double arm_b, rate;
    if (gradient) {
      // The force is -F_n grad(depth) (see narrow_phase_planar.h): conservative with W = 2/5 k_n d^2.5.
      const contact::DepthGradient dg = contact::depth_gradient(g, sa.pos, sb.pos);
      dir_b = -dg.grad_b;
      arm_b = -dg.grad_wb;
      rate = dg.grad_a.dot(sa.vel) + dg.grad_wa * sa.omega + dg.grad_b.dot(sb.vel) + dg.grad_wb * sb.omega;
    } else {
      dir_b = g.normal;
      arm_b = geometry::cross(rb, g.normal);
      rate = -v_rel.dot(g.normal);
    }

    const contact::PairKey key{A.id, B.id};
    contact::PairCoefficients k = law_.coefficients(A.radius, B.radius, A.mass, B.mass);
    // Coulomb caps friction by the normal component of the contact force; in the gradient model that is
    // F_n (-grad_b . n): 1 for faces, 1/2 for a corner on a face (a triangle's depth grows at half the corner's
    // penetration).
    if (gradient) k.mu *= std::max(0.0, dir_b.dot(g.normal));
    const double spring = cache_.previous(key, cache_hint_[polyfloe_thread_index()].at);
    r.cf = law_.evaluate(k, g.depth, rate, v_rel.dot(t), spring, dt);
    // t_c^5 = 3.2181^5 (m*/k_n)^2 / v: track the contact with the largest v^2 (k_n/m*)^4 (no pow in the loop).
    const double km = k.k_n / k.m_star;
    r.v2 = rate * rate + 0.8 * km * g.depth * g.depth * std::sqrt(g.depth);
    r.q2 = r.v2 * (km * km) * (km * km);

    // On b: the normal part, and friction along t at the centroid; a gets the opposite force and the torque that
    // keeps the total angular momentum unchanged.
    const Vec2 ft = r.cf.tangential * t;
    r.f = r.cf.normal * dir_b + ft;
    r.tau_b = r.cf.normal * arm_b + geometry::cross(rb, ft);
    r.tau_a = -r.tau_b + geometry::cross(da - db, r.f);
    r.g = {g.normal, g.point, g.depth, g.area};
    r.a = a;
    r.b = b;
    r.hit = true;
  }

  // The contact forces summed per slot in pair order, then added to each body's force.
  slot_force_.assign(static_cast<std::size_t>(n), Vec2{0.0, 0.0});
  slot_torque_.assign(static_cast<std::size_t>(n), 0.0);
  contacts_.clear();
  worst_q2_ = worst_v2_ = 0.0;
  worst_a_ = worst_b_ = -1;
  for (const PairResult& r : pair_results_) {
    narrow_phase_failures_ += r.fallback;
    if (!r.hit) continue;
    const SlotStatic& A = slot_static_[r.a];
    const SlotStatic& B = slot_static_[r.b];
    if (r.q2 > worst_q2_) {
      worst_q2_ = r.q2;
      worst_v2_ = r.v2;
      worst_a_ = A.body;
      worst_b_ = B.body;
    }
    cache_.store(contact::PairKey{A.id, B.id}, r.cf.spring);
    slot_force_[r.b] += r.f;
    slot_torque_[r.b] += r.tau_b;
    slot_force_[r.a] -= r.f;
    slot_torque_[r.a] += r.tau_a;
    contacts_.push_back({A.body, B.body, r.g, r.cf.normal, r.cf.tangential, r.cf.sliding, r.f});
  }
  cache_.end_step();
  POLYFLOE_OMP_FOR(threads_)
  for (int k = 0; k < n; ++k) {
    const int i = slots_[k].body;
    force_[i] += slot_force_[k];
    torque_[i] += slot_torque_[k];
  }
  const auto t2 = clock::now();
  profile_.broad += std::chrono::duration<double>(t1 - t0).count();
  profile_.narrow_and_law += std::chrono::duration<double>(t2 - t1).count();
}

}  // namespace polyfloe::dynamics
