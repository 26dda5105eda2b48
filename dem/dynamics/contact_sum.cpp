// The contact sum (dynamics/contact_sum.h).
#include "dynamics/contact_sum.h"

#include <algorithm>
#include <cmath>

#include "dynamics/parallel.h"

namespace polyfloe::dynamics {

const ContactSum::Totals& ContactSum::sum(const Input& in, int threads, NeighbourLists& lists,
                                          contact::ContactCache& cache) {
  // The contact forces summed per slot in pair order, as one loop over the pairs would, but in parallel: the slots
  // are cut into consecutive blocks, and the pairs, sorted by their lower slot, into the blocks of that slot. A
  // slot's contributions from pairs of earlier blocks come before those of its own block's pairs in pair order, so
  // each block first collects the pairs whose upper slot lies in a later block (pass 1), then sums its slots: the
  // pairs collected by earlier blocks, block by block, then its own (pass 2). Every slot sees the same additions
  // in the same order as the serial loop, whatever the blocks: the sums, the stored springs, the counts and the
  // extremes do not depend on the threads.
  const int n = static_cast<int>(in.statics.size());
  const std::span<const contact::CandidatePair> pairs = in.pairs;
  const int blocks = threads == 1 ? 1 : std::min(n, 8 * threads);
  blocks_.resize(static_cast<std::size_t>(blocks));  // none without bodies (on several threads)
  for (int c = 0; c < blocks; ++c) {
    Block& blk = blocks_[c];
    blk.first_slot = static_cast<int>(static_cast<long long>(n) * c / blocks);
    blk.end_slot = static_cast<int>(static_cast<long long>(n) * (c + 1) / blocks);
    blk.first_pair = static_cast<std::size_t>(
        std::lower_bound(pairs.begin(), pairs.end(), blk.first_slot,
                         [](const contact::CandidatePair& p, int slot) { return p.a < slot; }) -
        pairs.begin());
  }
  for (int c = 0; c < blocks; ++c) blocks_[c].end_pair = c + 1 < blocks ? blocks_[c + 1].first_pair : pairs.size();
  POLYFLOE_OMP_FOR(threads)
  for (int c = 0; c < blocks; ++c) {  // pass 1
    Block& blk = blocks_[c];
    blk.spilled.clear();
    blk.hits = 0;
    for (std::size_t p = blk.first_pair; p < blk.end_pair; ++p) {
      if (!in.hit[p]) continue;
      blk.hits += in.hit[p] == 1;  // (a force from elsewhere is not stored)
      if (pairs[p].b >= blk.end_slot) blk.spilled.push_back(p);
    }
  }
  std::size_t hits = 0;
  for (Block& blk : blocks_) {
    blk.first_store = hits;
    hits += blk.hits;
  }
  const std::span<contact::ContactCache::Entry> stores = cache.store_slots(hits);
  const std::uint64_t next_gen = cache.generation() + 1;  // the generation end_step() makes them the previous
  slot_force_.resize(static_cast<std::size_t>(n));
  slot_torque_.resize(static_cast<std::size_t>(n));
  POLYFLOE_OMP_FOR(threads)
  for (int c = 0; c < blocks; ++c) sum_block(in, c, stores, next_gen, lists);  // pass 2
  merge_blocks(hits);
  cache.end_step();
  return totals_;
}

// Pass 2 for block c: its slots' sums, its pairs' histories stored, its counts and extremes.
void ContactSum::sum_block(const Input& in, int c, std::span<contact::ContactCache::Entry> stores,
                           std::uint64_t next_gen, NeighbourLists& lists) {
  Block& blk = blocks_[c];
  const int lo = blk.first_slot, hi = blk.end_slot;
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
  const std::span<const contact::CandidatePair> pairs = in.pairs;
  for (int e = 0; e < c; ++e)
    for (const std::size_t p : blocks_[e].spilled)
      if (const int b = pairs[p].b; b >= lo && b < hi) add(in.results[p], b);
  blk.failures = blk.reused = 0;
  blk.worst_q2 = blk.worst_v2 = 0.0;
  blk.worst_a = blk.worst_b = -1;
  blk.deepest = DeepestOverlap{};
  std::size_t store = blk.first_store;
  for (std::size_t p = blk.first_pair; p < blk.end_pair; ++p) {
    const PairResult& r = in.results[p];
    blk.failures += r.fallback;
    if (!r.hit) continue;
    if (in.hit[p] == 2) {  // evaluated by the World that owns its lower-id body: its force only
      add(r, pairs[p].a);
      if (pairs[p].b < hi) add(r, pairs[p].b);
      continue;
    }
    blk.reused += r.reused;
    const SlotStatic& A = in.statics[r.a];
    const SlotStatic& B = in.statics[r.b];
    if (r.q2 > blk.worst_q2) {
      blk.worst_q2 = r.q2;
      blk.worst_v2 = r.v2;
      blk.worst_a = A.body;
      blk.worst_b = B.body;
    }
    // Where the next evaluation finds it (NeighbourLists::store).
    if (const int e = pairs[p].entry; e >= 0) lists.set_store(e, static_cast<std::uint32_t>(store), next_gen);
    stores[store++] = {contact::PairKey{A.id, B.id}, {r.cf.spring, r.cf.normal}};
    add(r, pairs[p].a);
    if (pairs[p].b < hi) add(r, pairs[p].b);
    blk.deepest.consider(r.g.depth, in.overlap_limit * std::min(A.equivalent_radius, B.equivalent_radius), A.body,
                         B.body);
  }
}

// The counts and extremes, block by block in order (the first of equals wins, as in one loop).
void ContactSum::merge_blocks(std::size_t hits) {
  Totals& t = totals_;
  t = Totals{};
  t.hits = hits;
  double worst_q2 = 0.0, worst_v2 = 0.0;
  int worst_a = -1, worst_b = -1;
  for (const Block& blk : blocks_) {
    t.failures += blk.failures;
    t.reused += blk.reused;
    if (blk.worst_q2 > worst_q2) {
      worst_q2 = blk.worst_q2;
      worst_v2 = blk.worst_v2;
      worst_a = blk.worst_a;
      worst_b = blk.worst_b;
    }
    if (blk.deepest.ratio > t.deepest.ratio) t.deepest = blk.deepest;
  }
  if (worst_a >= 0 && worst_q2 > 0.0) {
    // t_c = 3.2181 (m*/k_n)^(2/5) v^(-1/5) = 3.2181 (v^2 (k_n/m*)^4)^(-1/10)
    t.shortest = {3.2181 * std::pow(worst_q2, -0.1), std::sqrt(worst_v2), worst_a, worst_b};
  }
}

}  // namespace polyfloe::dynamics
