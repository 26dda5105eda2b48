// The planar World's neighbour lists (dynamics/neighbour_lists.h).
#include "dynamics/neighbour_lists.h"

#include <algorithm>
#include <limits>

#include "dynamics/parallel.h"

namespace polyfloe::dynamics {

namespace {

// Lexicographic order of slot pairs (a, b), a < b: the order the contact stage takes them in.
bool pair_less(const contact::CandidatePair& p, const contact::CandidatePair& q) {
  return p.a != q.a ? p.a < q.a : p.b < q.b;
}

}  // namespace

void NeighbourLists::join_chunks(int chunks, std::vector<contact::CandidatePair>& pairs) {
  if (chunks == 1) {
    pairs.swap(chunks_[0]);
    return;
  }
  pairs.clear();
  for (int c = 0; c < chunks; ++c)
    pairs.insert(pairs.end(), chunks_[static_cast<std::size_t>(c)].begin(), chunks_[static_cast<std::size_t>(c)].end());
}

// On several threads the grid's scan is split into consecutive tile ranges, scanned in parallel and concatenated
// in order (the same list as the serial scan).
void NeighbourLists::grid_pairs(std::span<const geometry::Aabb> boxes, std::span<const std::uint8_t> dynamic,
                                int threads, std::vector<contact::CandidatePair>& pairs) {
  if (threads == 1) {
    grid_.find_pairs(boxes, dynamic, pairs);
    return;
  }
  grid_.build(boxes, dynamic);
  const std::size_t tiles = grid_.tile_count();
  const int chunks = static_cast<int>(std::min<std::size_t>(tiles, 8 * static_cast<std::size_t>(threads)));
  chunks_.resize(static_cast<std::size_t>(std::max(chunks, 1)));
  POLYFLOE_OMP_FOR(threads)
  for (int c = 0; c < chunks; ++c) {
    std::vector<contact::CandidatePair>& out = chunks_[static_cast<std::size_t>(c)];
    out.clear();
    grid_.scan_tiles(tiles * c / chunks, tiles * (c + 1) / chunks, out);
  }
  join_chunks(chunks, pairs);
}

bool NeighbourLists::outrun(const SlotView& v, int threads) {
  if (kick_verdict_) {  // tested by the step's first kick, at these positions
    const bool verdict = *kick_verdict_;
    kick_verdict_.reset();
    return verdict;
  }
  if (!built_for(v.position.size())) return true;
  const int n = static_cast<int>(v.position.size());
  bool out = false;
  POLYFLOE_OMP_FOR_ANY(threads, out)
  for (int i = 0; i < n; ++i) {
    const std::size_t b = static_cast<std::size_t>(i);
    out = !within(b, v.position[b], v.yaw[b], v.reach[b]) || out;
  }
  return out;
}

void NeighbourLists::build(const SlotView& v, const contact::ContactLaw& law, bool exact, int threads,
                           std::vector<contact::CandidatePair>& pairs) {
  // The grid's pairs of the boxes grown by half the skin, sorted by slot, as neighbour lists of the build's slots:
  // the pair (a, b), a < b, in the list of a. The slots move little between builds, so a slot's list is mostly
  // where the current slot would look for it, and so are its partners (checked, else found through the body).
  const int n = static_cast<int>(v.slots.size());
  const double half = 0.5 * skin_;
  grown_.resize(static_cast<std::size_t>(n));
  for (int k = 0; k < n; ++k) grown_[k] = {v.boxes[k].lo.array() - half, v.boxes[k].hi.array() + half};
  grid_pairs(grown_, v.dynamic, threads, pairs);
  std::sort(pairs.begin(), pairs.end(), pair_less);
  off_.assign(static_cast<std::size_t>(n) + 1, 0);
  for (const contact::CandidatePair& p : pairs) ++off_[static_cast<std::size_t>(p.a) + 1];
  for (int k = 0; k < n; ++k) off_[k + 1] += off_[k];
  adj_.resize(pairs.size());
  for (std::size_t e = 0; e < pairs.size(); ++e) adj_[e] = pairs[e].b;  // sorted: the lists in order
  body_.resize(static_cast<std::size_t>(n));
  slot_.resize(static_cast<std::size_t>(n));
  for (int k = 0; k < n; ++k) {
    body_[k] = v.slots[k].body;
    slot_[v.slots[k].body] = k;
  }
  // Each listed pair's distance at the build, from below (separating axes; -inf: never skipped): the pair cannot
  // touch while its two bodies have moved less than that in all, so the filter skips it without the narrow phase.
  // Less a margin far above the round-off of the coordinates, so that a skipped pair is one planar_overlap would
  // certainly reject; the comparison method (gjk_epa, with its own tolerance) skips none.
  gap_.resize(adj_.size());
  coefficients_.resize(adj_.size());
  POLYFLOE_OMP_FOR(threads)
  for (int k = 0; k < n; ++k) {
    const SlotStatic& A = v.statics[k];
    const std::span<const Vec2> va{v.world_xy.data() + A.vert_begin, static_cast<std::size_t>(A.vert_count)};
    for (int e = off_[k]; e < off_[k + 1]; ++e) {
      const int b = adj_[static_cast<std::size_t>(e)];
      const SlotStatic& B = v.statics[b];
      const geometry::Aabb &ba = v.boxes[k], &bb = v.boxes[b];
      const bool finite = ba.lo.allFinite() && ba.hi.allFinite() && bb.lo.allFinite() && bb.hi.allFinite();
      double gap = -std::numeric_limits<double>::infinity();
      if (exact && finite) {
        const double scale = std::max({ba.lo.cwiseAbs().maxCoeff(), ba.hi.cwiseAbs().maxCoeff(),
                                       bb.lo.cwiseAbs().maxCoeff(), bb.hi.cwiseAbs().maxCoeff()});
        const std::span<const Vec2> vb{v.world_xy.data() + B.vert_begin, static_cast<std::size_t>(B.vert_count)};
        gap = contact::separation_lower_bound(va, vb) - 1e-9 * (1.0 + scale);
      }
      gap_[static_cast<std::size_t>(e)] = gap;
      coefficients_[static_cast<std::size_t>(e)] = law.coefficients(A.radius, B.radius, A.mass, B.mass);
    }
  }
  topology_.assign(adj_.size(), contact::OverlapTopology{});
  store_.resize(adj_.size());
  store_generation_.assign(adj_.size(), 0);  // no generation: the cache's stores are looked up by key
  fresh_ = true;
  pos_.assign(v.position.begin(), v.position.end());
  yaw_.assign(v.yaw.begin(), v.yaw.end());
  slots_moved_ = false;
  moved_.assign(static_cast<std::size_t>(n), 0.0);
  ++builds_;
}

void NeighbourLists::candidate_pairs(const SlotView& v, const contact::ContactLaw& law, bool exact, int threads,
                                     std::vector<contact::CandidatePair>& pairs) {
  // The pairs whose boxes overlap now, found among the neighbour lists of the last build (a superset while no
  // vertex has moved more than half the skin), less the pairs still farther apart than their bodies have moved
  // since the build (they cannot touch).
  fresh_ = false;
  if (outrun(v, threads)) build(v, law, exact, threads, pairs);
  const int n = static_cast<int>(v.slots.size());
  const int chunks = threads == 1 ? 1 : std::min(n, 8 * threads);
  chunks_.resize(static_cast<std::size_t>(std::max(chunks, 1)));
  POLYFLOE_OMP_FOR(threads)
  for (int c = 0; c < chunks; ++c) {
    std::vector<contact::CandidatePair>& out = chunks_[static_cast<std::size_t>(c)];
    out.clear();
    std::size_t m = 0;
    for (int k = static_cast<int>(static_cast<long long>(n) * c / chunks),
             k1 = static_cast<int>(static_cast<long long>(n) * (c + 1) / chunks);
         k < k1; ++k) {
      const int i = v.slots[k].body;
      const int built = body_[k] == i ? k : slot_[i];  // this body's slot at the build
      const int e0 = off_[built], e1 = off_[built + 1];
      const double moved = moved_[static_cast<std::size_t>(i)];
      out.resize(m + static_cast<std::size_t>(e1 - e0));
      const geometry::Aabb box = v.boxes[k];
      // Without branches (whether a listed pair overlaps is a coin toss to the predictor): every pair is written,
      // the kept ones advance the end.
      for (int e = e0; e < e1; ++e) {
        const int sb = adj_[static_cast<std::size_t>(e)];  // the partner's slot at the build ...
        const int j = body_[sb];
        const int s = v.slots[sb].body == j ? sb : v.body_slot[j];  // ... and now
        const geometry::Aabb& o = v.boxes[s];
        const int hit = static_cast<int>(box.lo.x() <= o.hi.x()) & static_cast<int>(o.lo.x() <= box.hi.x()) &
                        static_cast<int>(box.lo.y() <= o.hi.y()) & static_cast<int>(o.lo.y() <= box.hi.y()) &
                        static_cast<int>(moved + moved_[static_cast<std::size_t>(j)] >= gap_[e]);
        out[m] = {std::min(k, s), std::max(k, s), e};
        m += static_cast<std::size_t>(hit);
      }
    }
    out.resize(m);
  }
  join_chunks(chunks, pairs);
  // Sorted as built, while no slot has changed bodies since the build (the pairs of each slot in its list's order,
  // the slots in order). Slots that swapped since move a few pairs out of order: an insertion sort puts them back,
  // and past a budget of moves (bodies that crossed many others, or the slots sorted anew since the build) a full
  // sort, and the lists are rebuilt next time. Both give the one sorted order.
  if (!slots_moved_) return;
  std::size_t moves = 0;
  const std::size_t budget = 4 * pairs.size() + 64;
  for (std::size_t u = 1; u < pairs.size() && moves <= budget; ++u) {
    if (!pair_less(pairs[u], pairs[u - 1])) continue;
    const contact::CandidatePair x = pairs[u];
    std::size_t w = u;
    for (; w > 0 && pair_less(x, pairs[w - 1]); --w) pairs[w] = pairs[w - 1];
    pairs[w] = x;
    moves += u - w;
  }
  if (moves > budget) {
    std::sort(pairs.begin(), pairs.end(), pair_less);
    pos_.clear();  // the lists' order is stale: rebuild them at the next evaluation
  }
}

}  // namespace polyfloe::dynamics
