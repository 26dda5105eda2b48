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

// pairs_ = the first `chunks` lists of pair_chunks_, in order (one list is taken over whole).
void World::join_pair_chunks(int chunks) {
  if (chunks == 1) {
    pairs_.swap(pair_chunks_[0]);
    return;
  }
  pairs_.clear();
  for (int c = 0; c < chunks; ++c)
    pairs_.insert(pairs_.end(), pair_chunks_[static_cast<std::size_t>(c)].begin(),
                  pair_chunks_[static_cast<std::size_t>(c)].end());
}

// The grid's pairs of `boxes` (by slot) into pairs_: on one thread, or its scan split into consecutive tile
// ranges, scanned in parallel and concatenated in order (the same list as the serial scan).
void World::grid_pairs(std::span<const geometry::Aabb> boxes) {
  if (threads_ == 1) {
    broad_.find_pairs(boxes, slot_dynamic_, pairs_);
    return;
  }
  broad_.build(boxes, slot_dynamic_);
  const std::size_t tiles = broad_.tile_count();
  const int chunks = static_cast<int>(std::min<std::size_t>(tiles, 8 * static_cast<std::size_t>(threads_)));
  pair_chunks_.resize(static_cast<std::size_t>(std::max(chunks, 1)));
  POLYFLOE_OMP_FOR(threads_)
  for (int c = 0; c < chunks; ++c) {
    std::vector<contact::CandidatePair>& out = pair_chunks_[static_cast<std::size_t>(c)];
    out.clear();
    broad_.scan_tiles(tiles * c / chunks, tiles * (c + 1) / chunks, out);
  }
  join_pair_chunks(chunks);
}

bool World::skin_outrun() {
  if (kick_outrun_) {  // tested by the step's first kick, at these positions
    const bool verdict = *kick_outrun_;
    kick_outrun_.reset();
    return verdict;
  }
  if (skin_pos_.size() != size()) return true;
  const double half = 0.5 * skin_;
  const int n = static_cast<int>(size());
  bool outrun = false;
  POLYFLOE_OMP_FOR_ANY(threads_, outrun)
  for (int i = 0; i < n; ++i) outrun = !skin_within(static_cast<std::size_t>(i), half) || outrun;
  return outrun;
}

namespace {

// Lexicographic order of slot pairs (a, b), a < b: the order the contact stage takes them in.
bool pair_less(const contact::CandidatePair& p, const contact::CandidatePair& q) {
  return p.a != q.a ? p.a < q.a : p.b < q.b;
}

}  // namespace

void World::build_skin() {
  // The grid's pairs of the boxes grown by half the skin, sorted by slot, as neighbour lists of the build's slots:
  // the pair (a, b), a < b, in the list of a. The slots move little between builds, so a slot's list is mostly
  // where the current slot would look for it, and so are its partners (checked, else found through the body).
  const int n = static_cast<int>(size());
  const double half = 0.5 * skin_;
  skin_boxes_.resize(static_cast<std::size_t>(n));
  for (int k = 0; k < n; ++k) skin_boxes_[k] = {boxes_[k].lo.array() - half, boxes_[k].hi.array() + half};
  grid_pairs(skin_boxes_);
  std::sort(pairs_.begin(), pairs_.end(), pair_less);
  skin_off_.assign(static_cast<std::size_t>(n) + 1, 0);
  for (const contact::CandidatePair& p : pairs_) ++skin_off_[static_cast<std::size_t>(p.a) + 1];
  for (int k = 0; k < n; ++k) skin_off_[k + 1] += skin_off_[k];
  skin_adj_.resize(pairs_.size());
  for (std::size_t e = 0; e < pairs_.size(); ++e) skin_adj_[e] = pairs_[e].b;  // sorted: the lists in order
  skin_body_.resize(static_cast<std::size_t>(n));
  skin_slot_.resize(static_cast<std::size_t>(n));
  for (int k = 0; k < n; ++k) {
    skin_body_[k] = slots_[k].body;
    skin_slot_[slots_[k].body] = k;
  }
  // Each listed pair's distance at the build, from below (separating axes; -inf: never skipped): the pair cannot
  // touch while its two bodies have moved less than that in all, so the filter skips it without the narrow phase.
  // Less a margin far above the round-off of the coordinates, so that a skipped pair is one planar_overlap would
  // certainly reject; the comparison method (gjk_epa, with its own tolerance) skips none.
  skin_gap_.resize(skin_adj_.size());
  skin_coef_.resize(skin_adj_.size());
  const bool exact = settings_.narrow_phase == PlanarNarrowPhase::exact;
  POLYFLOE_OMP_FOR(threads_)
  for (int k = 0; k < n; ++k) {
    const SlotStatic& A = slot_static_[k];
    const std::span<const Vec2> va{world_xy_.data() + A.vert_begin, static_cast<std::size_t>(A.vert_count)};
    for (int e = skin_off_[k]; e < skin_off_[k + 1]; ++e) {
      const int b = skin_adj_[static_cast<std::size_t>(e)];
      const SlotStatic& B = slot_static_[b];
      const geometry::Aabb &ba = boxes_[k], &bb = boxes_[b];
      const bool finite = ba.lo.allFinite() && ba.hi.allFinite() && bb.lo.allFinite() && bb.hi.allFinite();
      double gap = -std::numeric_limits<double>::infinity();
      if (exact && finite) {
        const double scale = std::max({ba.lo.cwiseAbs().maxCoeff(), ba.hi.cwiseAbs().maxCoeff(),
                                       bb.lo.cwiseAbs().maxCoeff(), bb.hi.cwiseAbs().maxCoeff()});
        const std::span<const Vec2> vb{world_xy_.data() + B.vert_begin, static_cast<std::size_t>(B.vert_count)};
        gap = contact::separation_lower_bound(va, vb) - 1e-9 * (1.0 + scale);
      }
      skin_gap_[static_cast<std::size_t>(e)] = gap;
      skin_coef_[static_cast<std::size_t>(e)] = law_.coefficients(A.radius, B.radius, A.mass, B.mass);
    }
  }
  skin_topo_.assign(skin_adj_.size(), contact::OverlapTopology{});
  skin_store_.resize(skin_adj_.size());
  skin_store_gen_.assign(skin_adj_.size(), 0);  // no generation: the cache's stores are looked up by key
  lists_built_ = true;
  skin_pos_ = pos_;
  skin_yaw_ = yaw_;
  slots_moved_ = false;
  skin_moved_.assign(static_cast<std::size_t>(n), 0.0);
  ++skin_builds_;
}

void World::candidate_pairs() {
  // The pairs whose boxes overlap now, found among the neighbour lists of the last build (a superset while no
  // vertex has moved more than half the skin), as slot pairs (a, b), a < b, sorted by a, then b; less the pairs
  // still farther apart than their bodies have moved since the build (they cannot touch). The pairs that touch
  // are therefore a function of the current state alone, in an order that is one too, whenever the lists were
  // built: a restarted run and any number of threads sum the same contacts in the same order.
  lists_built_ = false;
  if (skin_outrun()) build_skin();
  const int n = static_cast<int>(size());
  const int chunks = threads_ == 1 ? 1 : std::min(n, 8 * threads_);
  pair_chunks_.resize(static_cast<std::size_t>(std::max(chunks, 1)));
  POLYFLOE_OMP_FOR(threads_)
  for (int c = 0; c < chunks; ++c) {
    std::vector<contact::CandidatePair>& out = pair_chunks_[static_cast<std::size_t>(c)];
    out.clear();
    std::size_t m = 0;
    for (int k = static_cast<int>(static_cast<long long>(n) * c / chunks),
             k1 = static_cast<int>(static_cast<long long>(n) * (c + 1) / chunks);
         k < k1; ++k) {
      const int i = slots_[k].body;
      const int built = skin_body_[k] == i ? k : skin_slot_[i];  // this body's slot at the build
      const int e0 = skin_off_[built], e1 = skin_off_[built + 1];
      const double moved = skin_moved_[static_cast<std::size_t>(i)];
      out.resize(m + static_cast<std::size_t>(e1 - e0));
      const geometry::Aabb box = boxes_[k];
      // Without branches (whether a listed pair overlaps is a coin toss to the predictor): every pair is written,
      // the kept ones advance the end.
      for (int e = e0; e < e1; ++e) {
        const int sb = skin_adj_[static_cast<std::size_t>(e)];  // the partner's slot at the build ...
        const int j = skin_body_[sb];
        const int s = slots_[sb].body == j ? sb : body_slot_[j];  // ... and now
        const geometry::Aabb& o = boxes_[s];
        const int hit = static_cast<int>(box.lo.x() <= o.hi.x()) & static_cast<int>(o.lo.x() <= box.hi.x()) &
                        static_cast<int>(box.lo.y() <= o.hi.y()) & static_cast<int>(o.lo.y() <= box.hi.y()) &
                        static_cast<int>(moved + skin_moved_[static_cast<std::size_t>(j)] >= skin_gap_[e]);
        out[m] = {std::min(k, s), std::max(k, s), e};
        m += static_cast<std::size_t>(hit);
      }
    }
    out.resize(m);
  }
  join_pair_chunks(chunks);
  // Sorted as built, while no slot has changed bodies since the build (the pairs of each slot in its list's order,
  // the slots in order). Slots that swapped since move a few pairs out of order: an insertion sort puts them back,
  // and past a budget of moves (bodies that crossed many others, or the slots sorted anew since the build) a full
  // sort, and the lists are rebuilt next time. Both give the one sorted order.
  if (!slots_moved_) return;
  std::size_t moves = 0;
  const std::size_t budget = 4 * pairs_.size() + 64;
  for (std::size_t u = 1; u < pairs_.size() && moves <= budget; ++u) {
    if (!pair_less(pairs_[u], pairs_[u - 1])) continue;
    const contact::CandidatePair x = pairs_[u];
    std::size_t v = u;
    for (; v > 0 && pair_less(x, pairs_[v - 1]); --v) pairs_[v] = pairs_[v - 1];
    pairs_[v] = x;
    moves += u - v;
  }
  if (moves > budget) {
    std::sort(pairs_.begin(), pairs_.end(), pair_less);
    skin_pos_.clear();  // the lists' order is stale: rebuild them at the next evaluation
  }
}

void World::sum_contacts(int n) {
  // The contact forces summed per slot in pair order, as one loop over the pairs would, but in parallel: the slots
  // are cut into consecutive blocks, and the pairs, sorted by their lower slot, into the blocks of that slot. A
  // slot's contributions from pairs of earlier blocks come before those of its own block's pairs in pair order, so
  // each block first collects the pairs whose upper slot lies in a later block (pass 1), then sums its slots: the
  // pairs collected by earlier blocks, block by block, then its own (pass 2). Every slot sees the same additions
  // in the same order as the serial loop, whatever the blocks: the sums, the stored springs, the counts and the
  // extremes do not depend on the threads.
  const int blocks = threads_ == 1 ? 1 : std::min(n, 8 * threads_);
  sum_blocks_.resize(static_cast<std::size_t>(blocks));  // none without bodies (on several threads)
  auto first_slot = [&](int c) { return static_cast<int>(static_cast<long long>(n) * c / blocks); };
  for (int c = 0; c < blocks; ++c) {
    const int lo = first_slot(c);
    sum_blocks_[c].first_pair = static_cast<std::size_t>(
        std::lower_bound(pairs_.begin(), pairs_.end(), lo,
                         [](const contact::CandidatePair& p, int slot) { return p.a < slot; }) -
        pairs_.begin());
  }
  auto last_pair = [&](int c) { return c + 1 < blocks ? sum_blocks_[c + 1].first_pair : pairs_.size(); };
  POLYFLOE_OMP_FOR(threads_)
  for (int c = 0; c < blocks; ++c) {
    SumBlock& blk = sum_blocks_[c];
    blk.spilled.clear();
    blk.hits = 0;
    const int hi = first_slot(c + 1);
    for (std::size_t p = blk.first_pair, p1 = last_pair(c); p < p1; ++p) {
      if (!pair_hit_[p]) continue;
      ++blk.hits;
      if (pairs_[p].b >= hi) blk.spilled.push_back(p);
    }
  }
  std::size_t hits = 0;
  for (SumBlock& blk : sum_blocks_) {
    blk.first_store = hits;
    hits += blk.hits;
  }
  const std::span<contact::ContactCache::Entry> stores = cache_.store_slots(hits);
  const std::uint64_t next_gen = cache_.generation() + 1;  // the generation end_step() makes them the previous
  slot_force_.resize(static_cast<std::size_t>(n));
  slot_torque_.resize(static_cast<std::size_t>(n));
  POLYFLOE_OMP_FOR(threads_)
  for (int c = 0; c < blocks; ++c) {
    SumBlock& blk = sum_blocks_[c];
    const int lo = first_slot(c), hi = first_slot(c + 1);
    for (int k = lo; k < hi; ++k) {
      slot_force_[k] = Vec2{0.0, 0.0};
      slot_torque_[k] = 0.0;
    }
    // A pair's share to one of its slots (a gets minus the force on b).
    auto add = [&](const PairResult& r, int slot) {
      if (slot == r.b) {
        slot_force_[slot] += r.f;
        slot_torque_[slot] += r.tau_b;
      } else {
        slot_force_[slot] -= r.f;
        slot_torque_[slot] += r.tau_a;
      }
    };
    for (int e = 0; e < c; ++e)
      for (const std::size_t p : sum_blocks_[e].spilled)
        if (const int b = pairs_[p].b; b >= lo && b < hi) add(pair_results_[p], b);
    blk.failures = blk.reused = 0;
    blk.worst_q2 = blk.worst_v2 = 0.0;
    blk.worst_a = blk.worst_b = -1;
    blk.deepest = DeepestOverlap{};
    std::size_t store = blk.first_store;
    for (std::size_t p = blk.first_pair, p1 = last_pair(c); p < p1; ++p) {
      const PairResult& r = pair_results_[p];
      blk.failures += r.fallback;
      if (!r.hit) continue;
      blk.reused += r.reused;
      const SlotStatic& A = slot_static_[r.a];
      const SlotStatic& B = slot_static_[r.b];
      if (r.q2 > blk.worst_q2) {
        blk.worst_q2 = r.q2;
        blk.worst_v2 = r.v2;
        blk.worst_a = A.body;
        blk.worst_b = B.body;
      }
      if (const int e = pairs_[p].entry; e >= 0) {  // where the next evaluation finds it (see world.h)
        skin_store_[static_cast<std::size_t>(e)] = static_cast<std::uint32_t>(store);
        skin_store_gen_[static_cast<std::size_t>(e)] = next_gen;
      }
      stores[store++] = {contact::PairKey{A.id, B.id}, {r.cf.spring, r.cf.normal}};
      add(r, pairs_[p].a);
      if (pairs_[p].b < hi) add(r, pairs_[p].b);
      // The overlap deepest against half the smaller floe's equivalent radius (the run guard's limit).
      const double limit = 0.5 * std::min(A.equivalent_radius, B.equivalent_radius);
      if (const double ratio = r.g.depth / limit; ratio > blk.deepest.ratio)
        blk.deepest = {ratio, r.g.depth, limit, A.body, B.body};
    }
  }
  // Into the bodies' sums, in body order: each thread writes its own stretch of force_ and torque_ (written by
  // slot from the blocks, neighbouring bodies of different blocks would share cache lines).
  POLYFLOE_OMP_FOR(threads_)
  for (int i = 0; i < n; ++i) {
    const int k = body_slot_[static_cast<std::size_t>(i)];
    force_[i] += slot_force_[k];
    torque_[i] += slot_torque_[k];
  }
  // The counts and extremes, block by block in order (the first of equals wins, as in one loop).
  contacts_.clear();
  contacts_ready_ = false;  // the records are listed from pair_results_ when asked for (contacts())
  contact_count_ = hits;
  worst_q2_ = worst_v2_ = 0.0;
  worst_a_ = worst_b_ = -1;
  deepest_ = DeepestOverlap{};
  for (const SumBlock& blk : sum_blocks_) {
    narrow_phase_failures_ += blk.failures;
    profile_.reused += blk.reused;
    if (blk.worst_q2 > worst_q2_) {
      worst_q2_ = blk.worst_q2;
      worst_v2_ = blk.worst_v2;
      worst_a_ = blk.worst_a;
      worst_b_ = blk.worst_b;
    }
    if (blk.deepest.ratio > deepest_.ratio) deepest_ = blk.deepest;
  }
  cache_.end_step();
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

void World::contact_forces(double dt) {
  using clock = std::chrono::steady_clock;
  const auto t0 = clock::now();
  // Everything below works on slots (bodies sorted by position, world.h): the pairs, the bodies' hot state and
  // the force sums are read and written in memory order close to the order of space.
  candidate_pairs();
  const auto t1 = clock::now();

  const int n = static_cast<int>(size());
  // slot_state_: gathered by compute_forces' first pass.

  // Every candidate pair evaluated apart (in parallel: the cache is only read here), then added up in the broad
  // phase's order (sum_contacts: in parallel, each slot in pair order), so nothing depends on the threads.
  const std::size_t np = pairs_.size();
  pair_results_.resize(np);
  pair_hit_.resize(np);
  const bool gradient = law_.settings().force_model == contact::ForceModel::gradient;
  const bool foundation = law_.settings().force_model == contact::ForceModel::foundation;
  const contact::OverlapTerms terms = gradient     ? contact::OverlapTerms::depth_gradient
                                      : foundation ? contact::OverlapTerms::foundation
                                                   : contact::OverlapTerms::basic;
  const double kappa = law_.foundation_modulus();
  const bool gjk = settings_.narrow_phase == PlanarNarrowPhase::gjk_epa;
  const int np_int = static_cast<int>(np);
  cache_hint_.assign(static_cast<std::size_t>(threads_), CacheHint{});
  // Last step's springs by the list entries where the lists stand and the cache is the one the last sum stored
  // into; otherwise by key, through the cache's index (built here, before the threads read it).
  const bool by_entry = !lists_built_ && history_gen_ == cache_.generation();
  if (!by_entry) cache_.prepare_lookups();
  POLYFLOE_OMP_FOR(threads_)
  for (int p = 0; p < np_int; ++p) {
    PairResult& r = pair_results_[static_cast<std::size_t>(p)];
    r.hit = false;
    pair_hit_[static_cast<std::size_t>(p)] = 0;
    r.fallback = false;
    r.reused = false;
    // Orient every pair by id so the stored spring has one meaning whatever the index order.
    int a = pairs_[p].a, b = pairs_[p].b;
    const int entry = pairs_[p].entry;  // its neighbour-list entry: the kept topology and coefficients
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
    } else {
      // The topology this listed pair's overlap had at its last contact (see planar_overlap), kept for the next.
      contact::OverlapTopology* topology = entry >= 0 ? &skin_topo_[static_cast<std::size_t>(entry)] : nullptr;
      if (!contact::planar_overlap(verts_a, verts_b, g, terms, topology)) continue;
      r.reused = topology && topology->reused;
    }
    // The foundation model's normal is the direction of its force on b; no force (one body centred inside the
    // other, by symmetry): no contact.
    double load = 0.0;
    if (foundation) {
      load = g.load.norm();
      if (!(load > 0.0) || !(g.energy > 0.0)) continue;
      g.normal = g.load / load;
    }

    const SlotState& sa = slot_state_[a];
    const SlotState& sb = slot_state_[b];
    const Vec2 t = geometry::perp_left(g.normal);
    const Vec2 ra = g.point - sa.pos, rb = g.point - sb.pos;  // centroid relative to each body
    const Vec2 va = sa.vel + sa.omega * geometry::perp_left(ra);
    const Vec2 vb = sb.vel + sb.omega * geometry::perp_left(rb);
    const Vec2 v_rel = vb - va;

    const Vec2 da = -ra, db = -rb;  // body centres relative to the centroid
    // (symmetric in the two bodies, bit for bit: the list's order of the pair does not matter)
    contact::PairCoefficients k = entry >= 0 ? skin_coef_[static_cast<std::size_t>(entry)]
                                             : law_.coefficients(A.radius, B.radius, A.mass, B.mass);
    // Normal direction on b (per unit normal force) and its moment about b's centre, and the depth rate.
    Vec2 dir_b;
    double arm_b, rate, elastic = 0.0, stiffness = 0.0, exponent = 2.5;
    if (gradient) {
      // The force is -F_n grad(depth) (see narrow_phase_planar.h): conservative with W = 2/5 k_n d^2.5.
      const contact::DepthGradient dg = contact::depth_gradient(g, sa.pos, sb.pos);
      dir_b = -dg.grad_b;
      arm_b = -dg.grad_wb;
      rate = dg.grad_a.dot(sa.vel) + dg.grad_wa * sa.omega + dg.grad_b.dot(sb.vel) + dg.grad_wb * sb.omega;
      // Coulomb caps friction by the normal component of the contact force; in the gradient model that is
      // F_n (-grad_b . n): 1 for faces, 1/2 for a corner on a face (a triangle's depth grows at half the corner's
      // penetration).
      k.mu *= std::max(0.0, dir_b.dot(g.normal));
    } else if (foundation) {
      // The elastic wrench is kappa (g.load, g.load_moment) (contact/foundation.h); per unit normal force, its
      // direction and moment. The approach rate along it: dW/dt = -F_e rate. Locally the contact follows a power
      // law W ∝ approach^n, n = F_e extent / W (2 for a flat face, 2.5 round, 3 a corner in a face; exact for
      // those), and its stiffness is K = (n - 1) / n F_e^2 / W; the damping and the tangential spring follow them.
      elastic = kappa * load;
      exponent = std::clamp(load * g.extent / g.energy, 2.0, 3.5);
      stiffness = (exponent - 1.0) / exponent * elastic * elastic / (kappa * g.energy);
      dir_b = g.normal;
      arm_b = (g.load_moment + geometry::cross(rb, g.load)) / load;
      rate = -(dir_b.dot(v_rel) + g.load_moment / load * (sb.omega - sa.omega));
    } else {
      dir_b = g.normal;
      arm_b = geometry::cross(rb, g.normal);
      rate = -v_rel.dot(g.normal);
    }

    const contact::PairKey key{A.id, B.id};
    // What the previous step stored for this pair, and whether it did (the pair touched then).
    bool continuing = false;
    const contact::PlanarHistory last =
        by_entry  // (every pair of candidate_pairs() has its list entry)
            ? ((continuing = skin_store_gen_[static_cast<std::size_t>(entry)] == history_gen_)
                   ? cache_.stored(skin_store_[static_cast<std::size_t>(entry)])
                   : contact::PlanarHistory{})
            : cache_.previous(key, cache_hint_[polyfloe_thread_index()].at, &continuing);
    const double spring = last.spring;
    if (foundation) {
      // The damping at the end of the step (see contact::DampingStep): the velocities were predicted there with
      // the last step's forces (World::evaluate_forces), and this pair's own change of normal force since moves
      // its approach rate by the final half kick, through w = the inverse of its effective mass along its
      // direction (with the arms). A contact's first step: it began tau = extent / rate before now (at most dt).
      const double arm_a = g.load_moment / load + geometry::cross(ra, dir_b);
      contact::DampingStep step;
      step.inverse_mass = inv_mass_[A.body] + inv_mass_[B.body] + inv_inertia_[A.body] * arm_a * arm_a +
                          inv_inertia_[B.body] * arm_b * arm_b;
      step.last_normal = last.normal_force;
      if (!continuing) step.since_entry = rate > 0.0 ? std::min(g.extent / rate, dt) : dt;
      r.cf = law_.evaluate_stiffness(k, elastic, stiffness, exponent, rate, v_rel.dot(t), spring, dt, step);
      // The contact's duration from its stiffness now: t = g pi sqrt(m* / K), g = 1 for a linear spring (exact),
      // 1.283 for Hertz (its t_c at its deepest), between them linear in n. As q2 below:
      // (3.2181 / t)^10 = (x K / m*)^5, x = (3.2181 / (g pi))^2.
      const double gpi = std::numbers::pi * (1.0 + 0.5652 * (std::min(exponent, 2.5) - 2.0));
      const double x = (3.2181 / gpi) * (3.2181 / gpi) * stiffness / k.m_star;
      r.energy = kappa * g.energy;
      r.v2 = rate * rate + 2.0 * r.energy / k.m_star;  // the impact speed of this energy
      r.q2 = x * x * x * x * x;
    } else {
      r.cf = law_.evaluate(k, g.depth, rate, v_rel.dot(t), spring, dt);
      // t_c^5 = 3.2181^5 (m*/k_n)^2 / v: track the contact with the largest v^2 (k_n/m*)^4 (no pow in the loop),
      // v^2 = rate^2 + 2 W / m* the impact speed of this energy W = 2/5 k_n d^2.5.
      const double km = k.k_per_m;
      r.energy = 0.4 * k.k_n * g.depth * g.depth * std::sqrt(g.depth);
      r.v2 = rate * rate + 2.0 * r.energy / k.m_star;
      r.q2 = r.v2 * (km * km) * (km * km);
    }

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
    pair_hit_[static_cast<std::size_t>(p)] = 1;
  }

  sum_contacts(n);
  const auto t2 = clock::now();
  profile_.broad += std::chrono::duration<double>(t1 - t0).count();
  profile_.candidates += pairs_.size();
  profile_.contacts += contact_count_;
  profile_.narrow_and_law += std::chrono::duration<double>(t2 - t1).count();
}

}  // namespace polyfloe::dynamics
