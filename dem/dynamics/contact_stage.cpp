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
  broad_.find_pairs(boxes_, is_dynamic_, pairs_);
  const auto t1 = clock::now();

  // Every candidate pair evaluated apart (in parallel: the cache is only read here), then added up in the broad
  // phase's order on one thread, so the sums, the stored springs and the contact list do not depend on the threads.
  const std::size_t np = pairs_.size();
  pair_results_.resize(np);
  const bool gradient = law_.settings().force_model == contact::ForceModel::gradient;
  const bool gjk = settings_.narrow_phase == PlanarNarrowPhase::gjk_epa;
  const int np_int = static_cast<int>(np);
  POLYFLOE_OMP_FOR(threads_)
  for (int p = 0; p < np_int; ++p) {
    PairResult& r = pair_results_[static_cast<std::size_t>(p)];
    r.hit = false;
    r.fallback = false;
    // Orient every pair by id so the stored spring has one meaning whatever the index order.
    int a = pairs_[p].a, b = pairs_[p].b;
    if (id_[a] > id_[b]) std::swap(a, b);
    if (bonds_ && bonds_->bonded(a, b)) continue;  // frozen together: the bond carries the load
    contact::PlanarContact& g = r.g;
    if (gjk) {
      // The minimum translation at the witness midpoint; no overlap polygon, so the gradient force model sees the
      // plain normal (its containment fallback).
      const contact::Gjk2dContact m = contact::gjk_epa_2d(world_vertices(a), world_vertices(b));
      if (m.status == contact::Gjk2dStatus::separated) continue;
      if (m.status == contact::Gjk2dStatus::contact) {
        g = contact::PlanarContact{};
        g.normal = m.normal;
        g.point = m.point;
        g.depth = m.depth;
      } else {
        r.fallback = true;
        if (!contact::planar_overlap(world_vertices(a), world_vertices(b), g, gradient)) continue;
      }
    } else if (!contact::planar_overlap(world_vertices(a), world_vertices(b), g, gradient)) {
      continue;
    }

    const Vec2 t = geometry::perp_left(g.normal);
    const Vec2 ra = g.point - pos_[a], rb = g.point - pos_[b];  // centroid relative to each body
    const Vec2 va = vel_eval_[a] + omega_eval_[a] * geometry::perp_left(ra);
    const Vec2 vb = vel_eval_[b] + omega_eval_[b] * geometry::perp_left(rb);
    const Vec2 v_rel = vb - va;

    const Vec2 da = -ra, db = -rb;  // body centres relative to the centroid
    // Normal direction on b (per unit normal force) and its moment about b's centre, and the depth rate.
    Vec2 dir_b;
    double arm_b, rate;
    if (gradient) {
      // The force is -F_n grad(depth) (see narrow_phase_planar.h): conservative with W = 2/5 k_n d^2.5.
      const contact::DepthGradient dg = contact::depth_gradient(g, pos_[a], pos_[b]);
      dir_b = -dg.grad_b;
      arm_b = -dg.grad_wb;
      rate = dg.grad_a.dot(vel_eval_[a]) + dg.grad_wa * omega_eval_[a] + dg.grad_b.dot(vel_eval_[b]) +
             dg.grad_wb * omega_eval_[b];
    } else {
      dir_b = g.normal;
      arm_b = geometry::cross(rb, g.normal);
      rate = -v_rel.dot(g.normal);
    }

    const contact::PairKey key{id_[a], id_[b]};
    const double m_a = is_dynamic_[a] ? mass_[a] : contact::kInfinite;
    const double m_b = is_dynamic_[b] ? mass_[b] : contact::kInfinite;
    contact::PairCoefficients k = law_.coefficients(radius_[a], radius_[b], m_a, m_b);
    // Coulomb caps friction by the normal component of the contact force; in the gradient model that is
    // F_n (-grad_b . n): 1 for faces, 1/2 for a corner on a face (a triangle's depth grows at half the corner's
    // penetration).
    if (gradient) k.mu *= std::max(0.0, dir_b.dot(g.normal));
    r.cf = law_.evaluate(k, g.depth, rate, v_rel.dot(t), cache_.previous(key), dt);
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
    r.a = a;
    r.b = b;
    r.hit = true;
  }

  contacts_.clear();
  worst_q2_ = worst_v2_ = 0.0;
  worst_a_ = worst_b_ = -1;
  for (const PairResult& r : pair_results_) {
    narrow_phase_failures_ += r.fallback;
    if (!r.hit) continue;
    if (r.q2 > worst_q2_) {
      worst_q2_ = r.q2;
      worst_v2_ = r.v2;
      worst_a_ = r.a;
      worst_b_ = r.b;
    }
    cache_.store(contact::PairKey{id_[r.a], id_[r.b]}, r.cf.spring);
    force_[r.b] += r.f;
    torque_[r.b] += r.tau_b;
    force_[r.a] -= r.f;
    torque_[r.a] += r.tau_a;
    contacts_.push_back({r.a, r.b, r.g, r.cf.normal, r.cf.tangential, r.cf.sliding, r.f});
  }
  cache_.end_step();
  const auto t2 = clock::now();
  profile_.broad += std::chrono::duration<double>(t1 - t0).count();
  profile_.narrow_and_law += std::chrono::duration<double>(t2 - t1).count();
}

}  // namespace polyfloe::dynamics
