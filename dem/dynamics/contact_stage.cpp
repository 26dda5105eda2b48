// Stage: broad phase, planar narrow phase and the contact law, accumulated into forces and torques.
#include <chrono>
#include <cmath>
#include <algorithm>
#include <limits>
#include <numbers>
#include <utility>

#include "dynamics/parallel.h"
#include "dynamics/world.h"

namespace polyfloe::dynamics {

SlotView World::slot_view() const {
  return {order_.slots(), order_.body_slots(), slot_static_, boxes_,       slot_dynamic_,
          world_xy_,      bodies_.pos,         bodies_.yaw,  bodies_.reach};
}

void World::sum_contacts(int n) {
  const ContactSum::Totals& t =
      sum_.sum({pairs_, pair_results_, pair_hit_, slot_static_, kOverlapLimit}, threads_, lists_, cache_);
  // Into the bodies' sums, in body order: each thread writes its own stretch of bodies_.force and bodies_.torque (written by
  // slot from the sum's blocks, neighbouring bodies of different blocks would share cache lines).
  POLYFLOE_OMP_FOR(threads_)
  for (int i = 0; i < n; ++i) {
    const int k = order_.slot_of(i);
    bodies_.force[i] += sum_.slot_force(k);
    bodies_.torque[i] += sum_.slot_torque(k);
  }
  contacts_.clear();
  contacts_ready_ = false;  // the records are listed from pair_results_ when asked for (contacts())
  contact_count_ = t.hits;
  narrow_phase_failures_ += t.failures;
  profile_.reused += t.reused;
  report_.deepest = t.deepest;
  report_.shortest = t.shortest;
  history_gen_ = cache_.generation();
}

const std::vector<ContactRecord>& World::contacts() const {
  if (!contacts_ready_) {
    contacts_.clear();
    for (const PairResult& r : pair_results_)
      if (r.hit)
        contacts_.push_back({slot_static_[r.a].body, slot_static_[r.b].body, r.g, r.cf.normal, r.cf.tangential,
                             r.cf.sliding, r.f, r.energy});
    contacts_ready_ = true;
  }
  return contacts_;
}

// The narrow phase of the pair of slots (a, b), ordered by id, with its neighbour-list entry (or -1): whether they
// touch, and how (g; the foundation model's normal is the direction of its force on b, `load` its |g.load|).
[[gnu::always_inline]] inline bool World::measure_pair(const PairStage& stage, int a, int b, int entry,
                                                       contact::PlanarContact& g, double& load, PairResult& r) {
  const SlotStatic& A = slot_static_[a];
  const SlotStatic& B = slot_static_[b];
  const std::span<const Vec2> verts_a{world_xy_.data() + A.vert_begin, static_cast<std::size_t>(A.vert_count)};
  const std::span<const Vec2> verts_b{world_xy_.data() + B.vert_begin, static_cast<std::size_t>(B.vert_count)};
  if (stage.gjk) {
    // The minimum translation at the witness midpoint; no overlap polygon, so the gradient force model sees the
    // plain normal (its containment fallback).
    const contact::Gjk2dContact m = contact::gjk_epa_2d(verts_a, verts_b);
    if (m.status == contact::Gjk2dStatus::separated) return false;
    if (m.status == contact::Gjk2dStatus::contact) {
      g = contact::PlanarContact{};
      g.normal = m.normal;
      g.point = m.point;
      g.depth = m.depth;
    } else {
      r.fallback = true;
      if (!contact::planar_overlap(verts_a, verts_b, g, stage.gradient)) return false;
    }
  } else {
    // The topology this listed pair's overlap had at its last contact (see planar_overlap), kept for the next.
    contact::OverlapTopology* topology = entry >= 0 ? &lists_.topology(entry) : nullptr;
    if (!contact::planar_overlap(verts_a, verts_b, g, stage.terms, topology)) return false;
    r.reused = topology && topology->reused;
  }
  // No force of the foundation model (one body centred inside the other, by symmetry): no contact.
  if (stage.foundation) {
    load = g.load.norm();
    if (!(load > 0.0) || !(g.energy > 0.0)) return false;
    g.normal = g.load / load;
  }
  return true;
}

// How the force model turns the contact g between the slots a and b into a direction on b, its moment and the
// approach rate (and, for the foundation model, its elastic force, stiffness and exponent).
[[gnu::always_inline]] inline World::PairDirection World::pair_direction(const PairStage& stage,
                                                                         const contact::PlanarContact& g, double load,
                                                                         int a, int b,
                                                                         contact::PairCoefficients& k) const {
  const SlotState& sa = slot_state_[a];
  const SlotState& sb = slot_state_[b];
  const Vec2 ra = g.point - sa.pos, rb = g.point - sb.pos;  // centroid relative to each body
  const Vec2 va = sa.vel + sa.omega * geometry::perp_left(ra);
  const Vec2 vb = sb.vel + sb.omega * geometry::perp_left(rb);
  const Vec2 v_rel = vb - va;
  PairDirection d;
  if (stage.gradient) {
    // The force is -F_n grad(depth) (see narrow_phase_planar.h): conservative with W = 2/5 k_n d^2.5.
    const contact::DepthGradient dg = contact::depth_gradient(g, sa.pos, sb.pos);
    d.dir_b = -dg.grad_b;
    d.arm_b = -dg.grad_wb;
    d.rate = dg.grad_a.dot(sa.vel) + dg.grad_wa * sa.omega + dg.grad_b.dot(sb.vel) + dg.grad_wb * sb.omega;
    // Coulomb caps friction by the normal component of the contact force; in the gradient model that is
    // F_n (-grad_b . n): 1 for faces, 1/2 for a corner on a face (a triangle's depth grows at half the corner's
    // penetration).
    k.mu *= std::max(0.0, d.dir_b.dot(g.normal));
  } else if (stage.foundation) {
    // The elastic wrench is kappa (g.load, g.load_moment) (contact/foundation.h); per unit normal force, its
    // direction and moment. The approach rate along it: dW/dt = -F_e rate. Locally the contact follows a power
    // law W ∝ approach^n, n = F_e extent / W (2 for a flat face, 2.5 round, 3 a corner in a face; exact for
    // those), and its stiffness is K = (n - 1) / n F_e^2 / W; the damping and the tangential spring follow them.
    d.elastic = stage.kappa * load;
    d.exponent = std::clamp(load * g.extent / g.energy, 2.0, 3.5);
    d.stiffness = (d.exponent - 1.0) / d.exponent * d.elastic * d.elastic / (stage.kappa * g.energy);
    d.dir_b = g.normal;
    d.arm_b = (g.load_moment + geometry::cross(rb, g.load)) / load;
    d.arm_a = g.load_moment / load + geometry::cross(ra, d.dir_b);
    d.rate = -(d.dir_b.dot(v_rel) + g.load_moment / load * (sb.omega - sa.omega));
  } else {
    d.dir_b = g.normal;
    d.arm_b = geometry::cross(rb, g.normal);
    d.rate = -v_rel.dot(g.normal);
  }
  d.slip = v_rel.dot(geometry::perp_left(g.normal));
  d.rb = rb;
  d.a_from_b = rb - ra;
  return d;
}

// One candidate pair's evaluation into r (hit: it touches, outside a bond). Reads only, but for r and the pair's
// own kept topology: the pairs run in parallel. The three parts are inlined into the pair loop (as one function
// they cost no call, and the stage's flags stay in registers).
[[gnu::always_inline]] inline void World::evaluate_pair(const PairStage& stage, std::size_t p, PairResult& r) {
  r.hit = false;
  pair_hit_[p] = 0;
  r.fallback = false;
  r.reused = false;
  // Orient every pair by id so the stored spring has one meaning whatever the index order.
  int a = pairs_[p].a, b = pairs_[p].b;
  const int entry = pairs_[p].entry;  // its neighbour-list entry: the kept topology and coefficients
  if (slot_static_[a].id > slot_static_[b].id) std::swap(a, b);
  const SlotStatic& A = slot_static_[a];
  const SlotStatic& B = slot_static_[b];
  if (bonds_ && bonds_->bonded(A.body, B.body)) return;  // frozen together: the bond carries the load
  contact::PlanarContact g;
  double load = 0.0;  // |g.load| (foundation)
  if (!measure_pair(stage, a, b, entry, g, load, r)) return;
  // (symmetric in the two bodies, bit for bit: the list's order of the pair does not matter)
  contact::PairCoefficients k =
      entry >= 0 ? lists_.coefficients(entry) : law_.coefficients(A.radius, B.radius, A.mass, B.mass);
  const PairDirection d = pair_direction(stage, g, load, a, b, k);

  // What the previous step stored for this pair, and whether it did (the pair touched then).
  bool continuing = false;
  const contact::PlanarHistory last =
      stage.by_entry  // (every pair of candidate_pairs() has its list entry)
          ? ((continuing = lists_.store_generation(entry) == history_gen_) ? cache_.stored(lists_.store(entry))
                                                                           : contact::PlanarHistory{})
          : cache_.previous(contact::PairKey{A.id, B.id}, cache_hint_[polyfloe_thread_index()].at, &continuing);
  if (stage.foundation) {
    // The damping at the end of the step (see contact::DampingStep): the velocities were predicted there with
    // the last step's forces (World::evaluate_forces), and this pair's own change of normal force since moves
    // its approach rate by the final half kick, through w = the inverse of its effective mass along its
    // direction (with the arms). A contact's first step: it began tau = extent / rate before now (at most dt).
    contact::DampingStep step;
    step.inverse_mass = bodies_.inv_mass[A.body] + bodies_.inv_mass[B.body] +
                        bodies_.inv_inertia[A.body] * d.arm_a * d.arm_a +
                        bodies_.inv_inertia[B.body] * d.arm_b * d.arm_b;
    step.last_normal = last.normal_force;
    if (!continuing) step.since_entry = d.rate > 0.0 ? std::min(g.extent / d.rate, stage.dt) : stage.dt;
    r.cf = law_.evaluate_stiffness(k, d.elastic, d.stiffness, d.exponent, d.rate, d.slip, last.spring, stage.dt, step);
    // The contact's duration from its stiffness now: t = g pi sqrt(m* / K), g = 1 for a linear spring (exact),
    // 1.283 for Hertz (its t_c at its deepest), between them linear in n. As q2 below:
    // (3.2181 / t)^10 = (x K / m*)^5, x = (3.2181 / (g pi))^2.
    const double gpi = std::numbers::pi * (1.0 + 0.5652 * (std::min(d.exponent, 2.5) - 2.0));
    const double x = (3.2181 / gpi) * (3.2181 / gpi) * d.stiffness / k.m_star;
    r.energy = stage.kappa * g.energy;
    r.v2 = d.rate * d.rate + 2.0 * r.energy / k.m_star;  // the impact speed of this energy
    r.q2 = x * x * x * x * x;
  } else {
    r.cf = law_.evaluate(k, g.depth, d.rate, d.slip, last.spring, stage.dt);
    // t_c^5 = 3.2181^5 (m*/k_n)^2 / v: track the contact with the largest v^2 (k_n/m*)^4 (no pow in the loop),
    // v^2 = rate^2 + 2 W / m* the impact speed of this energy W = 2/5 k_n d^2.5.
    const double km = k.k_per_m;
    r.energy = 0.4 * k.k_n * g.depth * g.depth * std::sqrt(g.depth);
    r.v2 = d.rate * d.rate + 2.0 * r.energy / k.m_star;
    r.q2 = r.v2 * (km * km) * (km * km);
  }

  // On b: the normal part, and friction along t at the centroid; a gets the opposite force and the torque that
  // keeps the total angular momentum unchanged.
  const Vec2 ft = r.cf.tangential * geometry::perp_left(g.normal);
  r.f = r.cf.normal * d.dir_b + ft;
  r.tau_b = r.cf.normal * d.arm_b + geometry::cross(d.rb, ft);
  r.tau_a = -r.tau_b + geometry::cross(d.a_from_b, r.f);
  r.g = {g.normal, g.point, g.depth, g.area};
  r.a = a;
  r.b = b;
  r.hit = true;
  pair_hit_[p] = 1;
}

void World::contact_forces(double dt) {
  using clock = std::chrono::steady_clock;
  const auto t0 = clock::now();
  // Everything below works on slots (bodies sorted by position, world.h): the pairs, the bodies' hot state and
  // the force sums are read and written in memory order close to the order of space.
  PairStage stage;
  stage.dt = dt;
  stage.gjk = settings_.narrow_phase == PlanarNarrowPhase::gjk_epa;
  lists_.candidate_pairs(slot_view(), law_, !stage.gjk, threads_, pairs_);
  const auto t1 = clock::now();

  // Every candidate pair evaluated apart (in parallel: the cache is only read here), then added up in the broad
  // phase's order (sum_contacts: in parallel, each slot in pair order), so nothing depends on the threads.
  // slot_state_: gathered by compute_forces' first pass.
  const std::size_t np = pairs_.size();
  pair_results_.resize(np);
  pair_hit_.resize(np);
  stage.gradient = law_.settings().force_model == contact::ForceModel::gradient;
  stage.foundation = law_.settings().force_model == contact::ForceModel::foundation;
  stage.terms = stage.gradient     ? contact::OverlapTerms::depth_gradient
                : stage.foundation ? contact::OverlapTerms::foundation
                                   : contact::OverlapTerms::basic;
  stage.kappa = law_.foundation_modulus();
  cache_hint_.assign(static_cast<std::size_t>(threads_), CacheHint{});
  // Last step's histories by the list entries where the lists stand and the cache is the one the last sum stored
  // into; otherwise by key, through the cache's index (built here, before the threads read it).
  stage.by_entry = !lists_.fresh() && history_gen_ == cache_.generation();
  if (!stage.by_entry) cache_.prepare_lookups();
  const int np_int = static_cast<int>(np);
  POLYFLOE_OMP_FOR(threads_)
  for (int p = 0; p < np_int; ++p)
    evaluate_pair(stage, static_cast<std::size_t>(p), pair_results_[static_cast<std::size_t>(p)]);

  sum_contacts(static_cast<int>(size()));
  const auto t2 = clock::now();
  profile_.broad += std::chrono::duration<double>(t1 - t0).count();
  profile_.candidates += pairs_.size();
  profile_.contacts += contact_count_;
  profile_.narrow_and_law += std::chrono::duration<double>(t2 - t1).count();
}

}  // namespace polyfloe::dynamics
