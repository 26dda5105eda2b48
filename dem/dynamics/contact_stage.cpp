// Stage: broad phase, planar narrow phase and the contact law, each pair apart, then their sum in pair order.
#include "dynamics/contact_stage.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>
#include <utility>

#include "contact/narrow_phase_gjk2d.h"
#include "contact/narrow_phase_planar.h"
#include "dynamics/parallel.h"

namespace polyfloe::dynamics {

namespace {

// What every pair of one contact evaluation shares.
struct PairContext {
  PlanarContactInput in;
  const contact::ContactLaw& law;
  NeighbourLists& lists;  // the listed pairs' kept topologies (each pair writes only its own) and coefficients
  const contact::ContactCache& cache;
  PlanarContactStage::CacheHint* hints;  // by thread
  std::uint64_t history_gen = 0;         // the cache's generation the last sum stored under
  bool gjk = false, gradient = false, foundation = false;
  contact::OverlapTerms terms = contact::OverlapTerms::basic;
  double kappa = 0.0;     // the foundation modulus [Pa]
  bool by_entry = false;  // last step's histories found through the neighbour-list entries (else by key)
};

// A touching pair as the force model sees it: the direction of the normal force on b (per unit force) and its
// moments about b's and a's centres, the approach rate along it and the slip rate along k x normal; with the
// foundation model its elastic force, stiffness and exponent.
struct PairDirection {
  Vec2 dir_b{1.0, 0.0};
  double arm_b = 0.0, arm_a = 0.0;                        // [m]
  double rate = 0.0, slip = 0.0;                          // [m/s]
  double elastic = 0.0, stiffness = 0.0, exponent = 2.5;  // [N], [N/m], [-]
  Vec2 rb{0.0, 0.0};                                      // the contact point relative to b's centre [m]
  Vec2 a_from_b{0.0, 0.0};                                // a's centre relative to b's, through the contact point [m]
};

// The narrow phase of the pair of slots (a, b), ordered by id, with its neighbour-list entry (or -1): whether they
// touch, and how (g; the foundation model's normal is the direction of its force on b, `load` its |g.load|).
[[gnu::always_inline]] inline bool measure_pair(const PairContext& c, int a, int b, int entry,
                                                contact::PlanarContact& g, double& load, PairResult& r) {
  const SlotStatic& A = c.in.statics[a];
  const SlotStatic& B = c.in.statics[b];
  const std::span<const Vec2> verts_a{c.in.world_xy.data() + A.vert_begin, static_cast<std::size_t>(A.vert_count)};
  const std::span<const Vec2> verts_b{c.in.world_xy.data() + B.vert_begin, static_cast<std::size_t>(B.vert_count)};
  if (c.gjk) {
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
      if (!contact::planar_overlap(verts_a, verts_b, g, c.gradient)) return false;
    }
  } else {
    // The topology this listed pair's overlap had at its last contact (see planar_overlap), kept for the next.
    contact::OverlapTopology* topology = entry >= 0 ? &c.lists.topology(entry) : nullptr;
    const bool lines = c.foundation && !c.in.edge_nx.empty();
    auto lines_of = [&](const SlotStatic& s, const Vec2& ref) {
      return lines ? contact::EdgeLines{&c.in.edge_nx[s.vert_begin], &c.in.edge_ny[s.vert_begin],
                                        &c.in.edge_offset[s.vert_begin], ref}
                   : contact::EdgeLines{};
    };
    const contact::EdgeLines la = lines_of(A, verts_a[0]), lb = lines_of(B, verts_b[0]);
    if (!contact::planar_overlap(verts_a, verts_b, g, c.terms, topology, lines ? &la : nullptr, lines ? &lb : nullptr))
      return false;
    r.reused = topology && topology->reused;
  }
  // No force of the foundation model (one body centred inside the other, by symmetry): no contact.
  if (c.foundation) {
    load = g.load.norm();
    if (!(load > 0.0) || !(g.energy > 0.0)) return false;
    g.normal = g.load / load;
  }
  return true;
}

// How the force model turns the contact g between the slots a and b into a direction on b, its moment and the
// approach rate (and, for the foundation model, its elastic force, stiffness and exponent).
[[gnu::always_inline]] inline PairDirection pair_direction(const PairContext& c, const contact::PlanarContact& g,
                                                           double load, int a, int b, contact::PairCoefficients& k) {
  const SlotState& sa = c.in.states[a];
  const SlotState& sb = c.in.states[b];
  const Vec2 ra = g.point - sa.pos, rb = g.point - sb.pos;  // centroid relative to each body
  const Vec2 va = sa.vel + sa.omega * geometry::perp_left(ra);
  const Vec2 vb = sb.vel + sb.omega * geometry::perp_left(rb);
  const Vec2 v_rel = vb - va;
  PairDirection d;
  if (c.gradient) {
    // The force is -F_n grad(depth) (see narrow_phase_planar.h): conservative with W = 2/5 k_n d^2.5.
    const contact::DepthGradient dg = contact::depth_gradient(g, sa.pos, sb.pos);
    d.dir_b = -dg.grad_b;
    d.arm_b = -dg.grad_wb;
    d.arm_a = -dg.grad_wa;
    d.rate = dg.grad_a.dot(sa.vel) + dg.grad_wa * sa.omega + dg.grad_b.dot(sb.vel) + dg.grad_wb * sb.omega;
    // Coulomb caps friction by the normal component of the contact force; in the gradient model that is
    // F_n (-grad_b . n): 1 for faces, 1/2 for a corner on a face (a triangle's depth grows at half the corner's
    // penetration).
    k.mu *= std::max(0.0, d.dir_b.dot(g.normal));
  } else if (c.foundation) {
    // The elastic wrench is kappa (g.load, g.load_moment) (contact/foundation.h); per unit normal force, its
    // direction and moment. The approach rate along it: dW/dt = -F_e rate. Locally the contact follows a power
    // law W ∝ approach^n, n = F_e extent / W (2 for a flat face, 2.5 round, 3 a corner in a face; exact for
    // those), and its stiffness is K = (n - 1) / n F_e^2 / W; the damping and the tangential spring follow them.
    d.elastic = c.kappa * load;
    d.exponent = std::clamp(load * g.extent / g.energy, 2.0, 3.5);
    d.stiffness = (d.exponent - 1.0) / d.exponent * d.elastic * d.elastic / (c.kappa * g.energy);
    d.dir_b = g.normal;
    d.arm_b = (g.load_moment + geometry::cross(rb, g.load)) / load;
    d.arm_a = g.load_moment / load + geometry::cross(ra, d.dir_b);
    d.rate = -(d.dir_b.dot(v_rel) + g.load_moment / load * (sb.omega - sa.omega));
  } else {
    d.dir_b = g.normal;
    d.arm_b = geometry::cross(rb, g.normal);
    d.arm_a = geometry::cross(ra, g.normal);
    d.rate = -v_rel.dot(g.normal);
  }
  d.slip = v_rel.dot(geometry::perp_left(g.normal));
  d.rb = rb;
  d.a_from_b = rb - ra;
  return d;
}

// How a pair's damping meets the step (contact::DampingStep): the velocities were predicted at the end of the step
// with the last step's forces (World::evaluate_forces), and the pair's own change of normal force since moves its
// approach rate by the final half kick, through w = the inverse of its effective mass along its direction (the
// arms included; the translation's share weighted by `weight`, |grad_b|^2 for the gradient model). A contact's
// first step: it began `extent` / rate before now (at most dt).
[[gnu::always_inline]] inline contact::DampingStep damping_step(const PairContext& c, int a, int b,
                                                                const PairDirection& d, double weight, double extent,
                                                                const contact::PlanarHistory& last, bool continuing) {
  const int body_a = c.in.statics[a].body, body_b = c.in.statics[b].body;
  contact::DampingStep step;
  step.inverse_mass = (c.in.inv_mass[body_a] + c.in.inv_mass[body_b]) * weight +
                      c.in.inv_inertia[body_a] * d.arm_a * d.arm_a + c.in.inv_inertia[body_b] * d.arm_b * d.arm_b;
  step.last_normal = last.normal_force;
  if (!continuing) step.since_entry = d.rate > 0.0 ? std::min(extent / d.rate, c.in.dt) : c.in.dt;
  return step;
}

// The centroid and gradient models' normal and friction forces (the Hertz law in the depth) for the touching pair
// of slots (a, b), with the last step's history `last` (`continuing`: the pair touched then).
[[gnu::always_inline]] inline contact::ContactForce hertz_force(const PairContext& c, const contact::PlanarContact& g,
                                                                const PairDirection& d,
                                                                const contact::PairCoefficients& k, int a, int b,
                                                                const contact::PlanarHistory& last, bool continuing) {
  // The Hertz law in the coordinate whose rate d.rate is (contact::ContactLaw::evaluate_hertz): for the centroid
  // model the approach along the normal, which the depth follows at g.slope; for the gradient model the depth
  // itself, the pair's mass along it m* / |grad_b|^2 (|grad_b| 1 for faces, 1/2 for a corner in a face).
  const double s2 = c.gradient ? d.dir_b.squaredNorm() : 1.0;
  const double slope = c.gradient ? 1.0 : g.slope, mass_ratio = s2 > 0.0 ? 1.0 / s2 : 1.0;
  contact::DampingStep step = damping_step(c, a, b, d, s2, g.depth / slope, last, continuing);
  step.entry_power = c.law.settings().damping == contact::DampingModel::paper ? 0.5 : 0.25;
  return c.law.evaluate_hertz(k, g.depth, slope, mass_ratio, d.rate, d.slip, last.spring, c.in.dt, step);
}

// One candidate pair's evaluation into r (hit: it touches, outside a bond). Reads only, but for r and the pair's
// own kept topology: the pairs run in parallel. The three parts are inlined into the pair loop (as one function
// they cost no call, and the stage's flags stay in registers).
[[gnu::always_inline]] inline void evaluate_pair(const PairContext& c, const contact::CandidatePair& pair,
                                                 PairResult& r, std::uint8_t& hit) {
  r.hit = false;
  hit = 0;
  r.fallback = false;
  r.reused = false;
  // Orient every pair by id so the stored spring has one meaning whatever the index order.
  int a = pair.a, b = pair.b;
  const int entry = pair.entry;  // its neighbour-list entry: the kept topology and coefficients
  if (c.in.statics[a].id > c.in.statics[b].id) std::swap(a, b);
  const SlotStatic& A = c.in.statics[a];
  const SlotStatic& B = c.in.statics[b];
  if (A.ghost) return;                                           // evaluated by the World that owns a
  if (c.in.bonds && c.in.bonds->bonded(A.body, B.body)) return;  // frozen together: the bond carries the load
  contact::PlanarContact g;
  double load = 0.0;  // |g.load| (foundation)
  if (!measure_pair(c, a, b, entry, g, load, r)) return;
  // (symmetric in the two bodies, bit for bit: the list's order of the pair does not matter)
  contact::PairCoefficients k =
      entry >= 0 ? c.lists.coefficients(entry) : c.law.coefficients(A.radius, B.radius, A.mass, B.mass);
  const PairDirection d = pair_direction(c, g, load, a, b, k);

  // What the previous step stored for this pair, and whether it did (the pair touched then).
  bool continuing = false;
  const contact::PlanarHistory last =
      c.by_entry  // (every pair of candidate_pairs() has its list entry)
          ? ((continuing = c.lists.store_generation(entry) == c.history_gen) ? c.cache.stored(c.lists.store(entry))
                                                                             : contact::PlanarHistory{})
          : c.cache.previous(contact::PairKey{A.id, B.id}, c.hints[polyfloe_thread_index()].at, &continuing);
  if (c.foundation) {
    const contact::DampingStep step = damping_step(c, a, b, d, 1.0, g.extent, last, continuing);
    r.cf = c.law.evaluate_stiffness(k, d.elastic, d.stiffness, d.exponent, d.rate, d.slip, last.spring, c.in.dt, step);
    // The contact's duration from its stiffness now: t = g pi sqrt(m* / K), g = 1 for a linear spring (exact),
    // 1.283 for Hertz (its t_c at its deepest), between them linear in n. As q2 below:
    // (3.2181 / t)^10 = (x K / m*)^5, x = (3.2181 / (g pi))^2.
    const double gpi = std::numbers::pi * (1.0 + 0.5652 * (std::min(d.exponent, 2.5) - 2.0));
    const double x = (3.2181 / gpi) * (3.2181 / gpi) * d.stiffness / k.m_star;
    r.energy = c.kappa * g.energy;
    r.v2 = d.rate * d.rate + 2.0 * r.energy / k.m_star;  // the impact speed of this energy
    r.q2 = x * x * x * x * x;
  } else {
    r.cf = hertz_force(c, g, d, k, a, b, last, continuing);
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
  hit = 1;
}

}  // namespace

void PlanarContactStage::find_pairs(const SlotView& view, const contact::ContactLaw& law,
                                    PlanarNarrowPhase narrow_phase, int threads, NeighbourLists& lists) {
  lists.candidate_pairs(view, law, narrow_phase == PlanarNarrowPhase::exact, threads, pairs_);
}

void PlanarContactStage::evaluate(const PlanarContactInput& in, const contact::ContactLaw& law, NeighbourLists& lists,
                                  const contact::ContactCache& cache) {
  // Every candidate pair evaluated apart (in parallel: the cache is only read here), then added up in the broad
  // phase's order (ContactSum: in parallel, each slot in pair order), so nothing depends on the threads.
  const std::size_t np = pairs_.size();
  results_.resize(np);
  hit_.resize(np);
  hints_.assign(static_cast<std::size_t>(in.threads), CacheHint{});
  const contact::ForceModel model = law.settings().force_model;
  PairContext c{in, law, lists, cache, hints_.data()};
  c.history_gen = history_gen_;
  c.gjk = in.narrow_phase == PlanarNarrowPhase::gjk_epa;
  c.gradient = model == contact::ForceModel::gradient;
  c.foundation = model == contact::ForceModel::foundation;
  c.terms = c.gradient     ? contact::OverlapTerms::depth_gradient
            : c.foundation ? contact::OverlapTerms::foundation
                           : contact::OverlapTerms::basic;
  c.kappa = law.foundation_modulus();
  // Last step's histories by the list entries where the lists stand and the cache is the one the last sum stored
  // into; otherwise by key, through the cache's index (built here, before the threads read it).
  c.by_entry = !lists.fresh() && history_gen_ == cache.generation();
  if (!c.by_entry) cache.prepare_lookups();
  const int np_int = static_cast<int>(np);
  POLYFLOE_OMP_FOR(in.threads)
  for (int p = 0; p < np_int; ++p) {
    const auto q = static_cast<std::size_t>(p);
    // The pairs come slot by slot, so a's data stream in order; b, a neighbour, is read out of order: fetch its
    // slot records 8 pairs ahead, and its vertices 4 ahead (once its record, which says where they are, is here).
    // In random order about 10 % faster at 150k floes and 20 % at 1.5M, nothing measurable at 1.5k or in lattice
    // order (docs/performance.md, "Fetching a pair's partner ahead"); twice these distances gained nothing.
    if (p + 8 < np_int) {
      const int b = pairs_[q + 8].b;
      __builtin_prefetch(&in.statics[b]);
      __builtin_prefetch(&in.states[b]);
    }
    if (p + 4 < np_int) {
      const SlotStatic& B = in.statics[pairs_[q + 4].b];
      const Vec2* v = in.world_xy.data() + B.vert_begin;
      for (int k = 0; k < B.vert_count; k += 4) __builtin_prefetch(v + k);  // 4 vertices a 64-byte line
    }
    evaluate_pair(c, pairs_[q], results_[q], hit_[q]);
  }
}

void PlanarContactStage::outgoing(std::span<const SlotStatic> statics, std::vector<PairForce>& out) const {
  for (std::size_t p = 0; p < results_.size(); ++p) {
    const PairResult& r = results_[p];
    if (hit_[p] == 1 && statics[r.b].ghost) out.push_back({statics[r.a].id, statics[r.b].id, r.f, r.tau_b});
  }
}

void PlanarContactStage::take_incoming(std::span<const SlotStatic> statics, std::span<const PairForce> in) {
  if (in.empty()) return;
  incoming_.assign(in.begin(), in.end());
  auto less = [](const PairForce& x, const PairForce& y) { return x.a != y.a ? x.a < y.a : x.b < y.b; };
  std::sort(incoming_.begin(), incoming_.end(), less);
  std::size_t taken = 0;
  for (std::size_t p = 0; p < pairs_.size(); ++p) {
    int a = pairs_[p].a, b = pairs_[p].b;
    if (statics[a].id > statics[b].id) std::swap(a, b);
    if (!statics[a].ghost || statics[b].ghost) continue;
    const PairForce key{statics[a].id, statics[b].id};
    const auto it = std::lower_bound(incoming_.begin(), incoming_.end(), key, less);
    if (it == incoming_.end() || it->a != key.a || it->b != key.b) continue;
    PairResult& r = results_[p];
    r = PairResult{};
    r.hit = true;
    r.a = a;
    r.b = b;
    r.f = it->f;
    r.tau_b = it->tau_b;  // (a's share stays with a's owner: tau_a = 0 on this ghost)
    hit_[p] = 2;
    ++taken;
  }
  if (taken != incoming_.size()) {
    // Name one force that found no pair: a pair the other World saw touch is not a candidate here.
    for (const PairForce& f : incoming_) {
      bool found = false;
      for (std::size_t p = 0; p < pairs_.size() && !found; ++p)
        found = hit_[p] == 2 && statics[results_[p].a].id == f.a && statics[results_[p].b].id == f.b;
      if (!found)
        throw std::logic_error("a contact force between bodies " + std::to_string(f.a) + " and " + std::to_string(f.b) +
                               " came from the World that owns the first, but the pair is not a candidate here "
                               "with the first a ghost and the second owned: the ghosts do not cover the pairs");
    }
  }
}

const ContactSum::Totals& PlanarContactStage::sum(const PlanarContactInput& in, NeighbourLists& lists,
                                                  contact::ContactCache& cache) {
  const ContactSum::Totals& t =
      sum_.sum({pairs_, results_, hit_, in.statics, in.overlap_limit}, in.threads, lists, cache);
  history_gen_ = cache.generation();
  return t;
}

void PlanarContactStage::list_contacts(std::span<const SlotStatic> statics, std::vector<ContactRecord>& out) const {
  // In order of the pairs' ids (a's, then b's): one order whatever the bodies' storage, threads or ranks.
  std::vector<std::size_t> listed;
  for (std::size_t p = 0; p < results_.size(); ++p)
    if (hit_[p] == 1) listed.push_back(p);
  auto key = [&](std::size_t p) { return std::make_pair(statics[results_[p].a].id, statics[results_[p].b].id); };
  std::sort(listed.begin(), listed.end(), [&](std::size_t x, std::size_t y) { return key(x) < key(y); });
  out.clear();
  out.reserve(listed.size());
  for (const std::size_t p : listed) {
    const PairResult& r = results_[p];
    out.push_back(
        {statics[r.a].body, statics[r.b].body, r.g, r.cf.normal, r.cf.tangential, r.cf.sliding, r.f, r.energy});
  }
}

}  // namespace polyfloe::dynamics
