#include "contact/narrow_phase_planar.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "contact/foundation.h"
#include "geometry/inside_edges.h"

namespace polyfloe::contact {

using geometry::cross;
using geometry::perp_right;

namespace {

constexpr int kMaxClipped = 2 * kMaxPolygonVertices + 2;

// A polygon under clipping: vertices and, per vertex, where the edge leaving it lies (on ∂A or on ∂B).
struct ClipPolygon {
  Vec2 p[kMaxClipped];
  int edge[kMaxClipped];  // the edge leaving each vertex: i < na is A's edge i, na + j is B's edge j
  int n = 0;
};

// The largest separation of the two polygons along their edges' outward normals (separating axes), and that axis,
// pointing from A to B: > 0 is a lower bound of their distance, <= 0 minus the least penetration. `edge`: whose
// edge gives it, numbered as the clipping numbers B's edges (edge j from [j - 1] to [j]); of A when `of_a`.
double max_separation(std::span<const Vec2> a, std::span<const Vec2> b, Vec2& axis, int* edge = nullptr,
                      bool* of_a = nullptr) {
  double best = -std::numeric_limits<double>::infinity();
  axis = Vec2{1.0, 0.0};
  auto scan = [&](std::span<const Vec2> s, std::span<const Vec2> t, double sign) {
    const std::size_t n = s.size();
    for (std::size_t i = 0; i < n; ++i) {
      const Vec2 e = s[(i + 1) % n] - s[i];
      const double len = e.norm();
      if (len <= 0.0) continue;
      const Vec2 u = perp_right(e) / len;  // outward normal of s's edge
      double sep = std::numeric_limits<double>::infinity();
      for (const Vec2& q : t) sep = std::min(sep, u.dot(q - s[i]));
      if (sep > best) {
        best = sep;
        axis = sign * u;
        if (edge) *edge = static_cast<int>((i + 1) % n), *of_a = sign > 0.0;
      }
    }
  };
  scan(a, b, 1.0);   // A's face normals point from A to B
  scan(b, a, -1.0);  // B's face normals point from B to A
  return best;
}

// Separating-axis fallback for containment (no boundary crossing): the axis of least penetration.
void least_penetration(std::span<const Vec2> a, std::span<const Vec2> b, PlanarContact& out) {
  out.depth = std::max(0.0, -max_separation(a, b, out.normal));
}

// How far inside its edges (times the edge's length) a crossing, and inside the other polygon a vertex of a chain,
// must lie for a kept topology to be used: far above the round-off of the clipping, so that where the check passes
// the clipping finds the same topology (docs/model.md, "Kept topologies").
constexpr double kTopologyMargin = 1e-9;  // [-]

// The crossing of A's edge i (a[i] -> a[i+1]) with the line of B's edge j (b[j-1] -> b[j]) - normal `nrm`
// (outward, unnormalised) and offset d = nrm . (b[j-1] - origin) - where A's boundary leaves B's half-plane (exit)
// or enters it: x = p0 + t (p1 - p0) relative to `origin`, from the edge's own end points. The clipping cuts A's
// edges this way, and a kept topology is built this way, so that both give the same bits. False when A's edge does
// not cross that line in that sense (round-off, where an earlier cut left a point just off the line).
struct Crossing {
  Vec2 x;
  double t = 0.0;
};
bool cross_edge(std::span<const Vec2> a, const Vec2& origin, int i, const Vec2& nrm, double d, bool exit, Crossing& c) {
  const int na = static_cast<int>(a.size());
  const Vec2 p0 = a[i] - origin, p1 = a[(i + 1 == na) ? 0 : i + 1] - origin;
  const double s0 = nrm.dot(p0) - d, s1 = nrm.dot(p1) - d;
  if (exit ? !(s0 <= 0.0 && s1 > 0.0) : !(s0 > 0.0 && s1 <= 0.0)) return false;
  c.t = s0 / (s0 - s1);
  c.x = p0 + c.t * (p1 - p0);
  return true;
}

// B's edge j relative to `origin`: its start q0, direction e = q1 - q0, outward normal perp_right(e) and offset.
struct EdgeLine {
  Vec2 q0, e, nrm;
  double d;
};
EdgeLine b_edge(std::span<const Vec2> b, const Vec2& origin, int j) {
  const int nb = static_cast<int>(b.size());
  const Vec2 q0 = b[(j == 0) ? nb - 1 : j - 1] - origin, q1 = b[j] - origin;
  const Vec2 nrm = perp_right(q1 - q0);
  return {q0, q1 - q0, nrm, nrm.dot(q0)};
}

// Whether v (relative to `origin`) lies inside every edge of the counter-clockwise polygon `poly`, by more than
// kTopologyMargin times each edge's length.
bool strictly_inside(std::span<const Vec2> poly, const Vec2& origin, const Vec2& v) {
  return geometry::inside_all_edges(poly, origin, v, kTopologyMargin);
}

// Vertices of A inside B (a_first + 1 ... a_last) and of B inside A (b_first ... b_last - 1) in a topology.
int chain_a(const OverlapTopology& t, int na) { return t.a_last - t.a_first + (t.a_last < t.a_first ? na : 0); }
int chain_b(const OverlapTopology& t, int nb) { return t.b_last - t.b_first + (t.b_last < t.b_first ? nb : 0); }

// The overlap polygon of topology t - X2, A's chain, X1, B's chain, with the edge each vertex leaves along - when t
// is this pair's topology with room to spare; else false. The checks are the steps of the proof in docs/model.md:
// both crossings inside both their edges, in the right sense, in the right order where they share an edge, and
// both chains strictly inside the other polygon.
bool build_from_topology(std::span<const Vec2> a, std::span<const Vec2> b, const Vec2& origin, const OverlapTopology& t,
                         ClipPolygon& out) {
  const int na = static_cast<int>(a.size()), nb = static_cast<int>(b.size());
  if (t.a_first < 0 || t.a_last < 0 || t.b_first < 0 || t.b_last < 0 || t.a_first >= na || t.a_last >= na ||
      t.b_first >= nb || t.b_last >= nb)
    return false;
  const int ca = chain_a(t, na), cb = chain_b(t, nb);
  // A leaves B at x1 (A's edge a_last, B's edge b_first) and enters it at x2 (a_first, b_last); u: where each
  // lies along its edge of B.
  const EdgeLine l1 = b_edge(b, origin, t.b_first), l2 = b_edge(b, origin, t.b_last);
  Crossing x1, x2;
  if (!cross_edge(a, origin, t.a_last, l1.nrm, l1.d, true, x1) ||
      !cross_edge(a, origin, t.a_first, l2.nrm, l2.d, false, x2))
    return false;
  const double u1 = (x1.x - l1.q0).dot(l1.e) / l1.e.squaredNorm();
  const double u2 = (x2.x - l2.q0).dot(l2.e) / l2.e.squaredNorm();
  constexpr double lo = kTopologyMargin, hi = 1.0 - kTopologyMargin;
  if (!(x1.t >= lo && x1.t <= hi && u1 >= lo && u1 <= hi && x2.t >= lo && x2.t <= hi && u2 >= lo && u2 <= hi))
    return false;
  // Both crossings on one edge of A (no vertex of A inside B): x2 comes first along it, else the part of A's
  // boundary inside B would be the rest of A. The same on B's side: x1 first.
  if (ca == 0 && !(x1.t - x2.t > kTopologyMargin)) return false;
  if (cb == 0 && !(u2 - u1 > kTopologyMargin)) return false;
  int m = 0;
  out.p[m] = x2.x;
  out.edge[m++] = t.a_first;
  for (int k = 0, i = t.a_first; k < ca; ++k) {
    i = (i + 1 == na) ? 0 : i + 1;
    out.p[m] = a[i] - origin;
    if (!strictly_inside(b, origin, out.p[m])) return false;
    out.edge[m++] = i;
  }
  out.p[m] = x1.x;
  out.edge[m++] = na + t.b_first;
  for (int k = 0, j = t.b_first; k < cb; ++k) {
    out.p[m] = b[j] - origin;
    if (!strictly_inside(a, origin, out.p[m])) return false;
    j = (j + 1 == nb) ? 0 : j + 1;
    out.edge[m++] = na + j;
  }
  out.n = m;
  return true;
}

// The topology of a clipped polygon: known when its boundary passes from A to B once and back once.
OverlapTopology read_topology(const ClipPolygon& poly, int na, int nb) {
  OverlapTopology t;
  int exits = 0, entries = 0;
  for (int k = 0, in = poly.edge[poly.n - 1]; k < poly.n; in = poly.edge[k++]) {
    const int out = poly.edge[k];
    if (in < na && out >= na) {
      ++exits;
      t.a_last = static_cast<std::int8_t>(in);
      t.b_first = static_cast<std::int8_t>(out - na);
    } else if (in >= na && out < na) {
      ++entries;
      t.b_last = static_cast<std::int8_t>(in - na);
      t.a_first = static_cast<std::int8_t>(out);
    }
  }
  // Exactly the polygon the topology describes (no vertex more, as where A's boundary enters and leaves B on one
  // edge with the rest of A inside B).
  if (exits != 1 || entries != 1 || poly.n != 2 + chain_a(t, na) + chain_b(t, nb)) return {};
  return t;
}

// Area, centroid, chord, depth and (with_gradient) the gradient terms of the overlap polygon `poly`.
bool measure(std::span<const Vec2> a, std::span<const Vec2> b, const Vec2& origin, const ClipPolygon& poly,
             PlanarContact& out, OverlapTerms terms, const EdgeLines* lines_a, const EdgeLines* lines_b);

// A clipped by B's edge lines into `buf` (one of the two buffers); false when they do not overlap.
// `apart`: set to the edge of B whose line the whole of A lies outside, where the clipping ends there before any cut;
// to -2 where it ends after cuts.
const ClipPolygon* clip(std::span<const Vec2> a, std::span<const Vec2> b, const Vec2& origin, ClipPolygon (&buf)[2],
                        int& apart);

// Whether all of `p` lies outside the line of `q`'s edge j (q[j-1] -> q[j]) by more than kTopologyMargin times the
// edge's length.
bool outside_edge(std::span<const Vec2> p, std::span<const Vec2> q, const Vec2& origin, int j) {
  const EdgeLine l = b_edge(q, origin, j);
  const double margin = kTopologyMargin * l.e.squaredNorm();
  for (const Vec2& x : p)
    if (!(l.nrm.dot(x - origin) - l.d > margin)) return false;
  return true;
}

// The edge (of A or of B) along whose outward normal the two polygons are farthest apart (max_separation), into
// t.a_apart or t.b_apart, when the other polygon lies outside its line by outside_edge's margin.
void find_apart_edge(std::span<const Vec2> a, std::span<const Vec2> b, const Vec2& origin, OverlapTopology& t) {
  Vec2 axis;
  int edge = -1;
  bool of_a = false;
  if (!(max_separation(a, b, axis, &edge, &of_a) > 0.0) || edge < 0) return;
  if (of_a ? outside_edge(b, a, origin, edge) : outside_edge(a, b, origin, edge))
    (of_a ? t.a_apart : t.b_apart) = static_cast<std::int8_t>(edge);
}

}  // namespace

bool planar_overlap(std::span<const Vec2> a, std::span<const Vec2> b, PlanarContact& out, OverlapTerms terms,
                    OverlapTopology* topology, const EdgeLines* lines_a, const EdgeLines* lines_b) {
  // Work relative to A's first vertex: keeps precision for floes far from the origin.
  const Vec2 origin = a[0];
  ClipPolygon buf[2];
  const ClipPolygon* poly = nullptr;
  if (topology && ((topology->b_apart >= 0 && topology->b_apart < static_cast<int>(b.size()) &&
                    outside_edge(a, b, origin, topology->b_apart)) ||
                   (topology->a_apart >= 0 && topology->a_apart < static_cast<int>(a.size()) &&
                    outside_edge(b, a, origin, topology->a_apart)))) {
    // Apart still, as the kept edge shows (and the clipping would find).
    *topology = OverlapTopology{.a_apart = topology->a_apart, .b_apart = topology->b_apart, .reused = true};
    return false;
  }
  if (topology && topology->known() && build_from_topology(a, b, origin, *topology, buf[0])) {
    poly = &buf[0];
    topology->reused = true;
  } else {
    int apart = -1;
    poly = clip(a, b, origin, buf, apart);
    if (topology) {
      *topology =
          poly ? read_topology(*poly, static_cast<int>(a.size()), static_cast<int>(b.size())) : OverlapTopology{};
      // Apart: the edge of B that showed it before any cut; else (the vertex means' line showed it, or the clipping
      // after cuts) the edge of either polygon with the largest separation, found once for the steps to come.
      if (apart >= 0)
        topology->b_apart = static_cast<std::int8_t>(apart);
      else if (!poly)
        find_apart_edge(a, b, origin, *topology);
    }
    if (!poly) return false;
  }
  const bool hit = measure(a, b, origin, *poly, out, terms, lines_a, lines_b);
  if (!hit && topology) *topology = {};
  return hit;
}

namespace {

const ClipPolygon* clip(std::span<const Vec2> a, std::span<const Vec2> b, const Vec2& origin, ClipPolygon (&buf)[2],
                        int& apart) {
  const int na = static_cast<int>(a.size());
  const int nb = static_cast<int>(b.size());

  int j_near = 0;  // B's vertex nearest A along the axis: clipping starts with the edges around it
  // Quick rejection along the line between the vertex means: most broad-phase candidates that do not touch are
  // separated along it (touching counts as separated, as below). When the means coincide there is no such line
  // (every projection is 0): concentric polygons always overlap.
  {
    Vec2 ma{0.0, 0.0}, mb{0.0, 0.0};
    for (int i = 0; i < na; ++i) ma += a[i];
    for (int j = 0; j < nb; ++j) mb += b[j];
    const Vec2 axis = mb / nb - ma / na;
    double hi_a = -std::numeric_limits<double>::infinity(), lo_b = std::numeric_limits<double>::infinity();
    for (int i = 0; i < na; ++i) hi_a = std::max(hi_a, axis.dot(a[i] - origin));
    for (int j = 0; j < nb; ++j) {
      const double v = axis.dot(b[j] - origin);
      if (v < lo_b) {
        lo_b = v;
        j_near = j;
      }
    }
    if (hi_a <= lo_b && axis != Vec2::Zero()) return nullptr;
  }

  ClipPolygon* cur = &buf[0];
  ClipPolygon* nxt = &buf[1];
  cur->n = na;
  bool whole = true;  // cur is A itself
  for (int i = 0; i < na; ++i) {
    cur->p[i] = a[i] - origin;
    cur->edge[i] = i;
  }
  double s[kMaxClipped];
  // The bounding box of the current polygon (centre, half extents): an edge of B whose half-plane holds the whole
  // box cannot cut the polygon, which one test shows (after the first cuts the polygon is the overlap sliver and
  // most of B's edges lie far from it).
  Vec2 box_c{0.0, 0.0}, box_h{-1.0, -1.0};  // h < 0: not computed yet
  auto bound = [&]() {
    Vec2 lo = cur->p[0], hi = cur->p[0];
    for (int k = 1; k < cur->n; ++k) {
      lo = lo.cwiseMin(cur->p[k]);
      hi = hi.cwiseMax(cur->p[k]);
    }
    box_c = 0.5 * (lo + hi);
    box_h = 0.5 * (hi - lo);
  };
  // Clip by B's edges starting with the one that ends at j_near (they face A): the first cuts shrink the polygon
  // to the overlap sliver, and a separated pair is usually rejected by the first edge.
  Vec2 b0 = b[(j_near == 0) ? nb - 1 : j_near - 1] - origin;
  for (int jj = 0, j = j_near; jj < nb; ++jj, j = (j + 1 == nb) ? 0 : j + 1) {
    const Vec2 b1 = b[j] - origin;
    const Vec2 nrm = perp_right(b1 - b0);  // outward normal of B's edge (b0 -> b1), unnormalised
    const double d = nrm.dot(b0);
    b0 = b1;
    if (box_h.x() >= 0.0 && nrm.dot(box_c) - d + std::abs(nrm.x()) * box_h.x() + std::abs(nrm.y()) * box_h.y() < 0.0)
      continue;  // the box, hence the polygon, lies strictly inside this edge's half-plane
    // Signed distances (scaled by |nrm|): <= 0 is inside B's half-plane.
    bool any_out = false, any_in = false;
    for (int k = 0; k < cur->n; ++k) {
      s[k] = nrm.dot(cur->p[k]) - d;
      if (s[k] > 0.0)
        any_out = true;
      else
        any_in = true;
    }
    if (!any_out) continue;    // this edge of B does not cut the polygon
    if (!any_in) {             // the polygon lies wholly outside: separated (or touching)
      apart = whole ? j : -2;  // not cut yet: all of A lies outside this line; else it took several lines
      return nullptr;
    }
    int m = 0;
    for (int k = 0; k < cur->n; ++k) {
      const int k1 = (k + 1 == cur->n) ? 0 : k + 1;
      const bool in0 = s[k] <= 0.0, in1 = s[k1] <= 0.0;
      // At most na + nb vertices in exact arithmetic (< kMaxClipped); this only guards the buffer.
      if (m + 2 > kMaxClipped) return nullptr;
      if (in0) {
        nxt->p[m] = cur->p[k];
        nxt->edge[m++] = cur->edge[k];
      }
      if (in0 != in1) {
        const double t = s[k] / (s[k] - s[k1]);
        nxt->p[m] = cur->p[k] + t * (cur->p[k1] - cur->p[k]);
        // Leaving the half-plane: the new edge runs along B's line. Entering: it continues the old edge.
        nxt->edge[m++] = in0 ? na + j : cur->edge[k];
      }
    }
    nxt->n = m;
    std::swap(cur, nxt);
    whole = false;
    if (jj + 1 < nb) bound();
  }
  // Each vertex on two edges anew from those edges alone: a crossing from A's edge's end points (cross_edge), a
  // vertex of B as itself. The polygon then does not depend on the order of the cuts, and a kept topology builds
  // the same bits (where round-off puts a crossing just off its edge, the cut's point stays).
  // The polygon then starts where A's boundary enters B (as build_from_topology's does): the sums over it run in
  // the same order.
  int entry = -1;
  for (int k = 0, in = cur->edge[cur->n - 1]; k < cur->n; in = cur->edge[k++]) {
    const int out = cur->edge[k];
    if ((in < na) != (out < na)) {
      const bool exit = in < na;
      if (!exit && entry < 0) entry = k;
      const EdgeLine l = b_edge(b, origin, (exit ? out : in) - na);
      Crossing x;
      if (cross_edge(a, origin, exit ? in : out, l.nrm, l.d, exit, x)) cur->p[k] = x.x;
    } else if (in >= na && out - na == ((in - na + 1 == nb) ? 0 : in - na + 1)) {
      cur->p[k] = b[in - na] - origin;
    }
  }
  if (entry > 0) {
    std::rotate(cur->p, cur->p + entry, cur->p + cur->n);
    std::rotate(cur->edge, cur->edge + entry, cur->edge + cur->n);
  }
  return cur;
}

bool measure(std::span<const Vec2> a, std::span<const Vec2> b, const Vec2& origin, const ClipPolygon& poly,
             PlanarContact& out, OverlapTerms terms, const EdgeLines* lines_a, const EdgeLines* lines_b) {
  const int na = static_cast<int>(a.size());
  const int nb = static_cast<int>(b.size());
  // A's edge i runs from a[i] to a[i+1]; B's edge j from b[j-1] to b[j] (the order the clipping visits them).
  auto a_normal = [&](int i) { return perp_right(a[(i + 1 == na) ? 0 : i + 1] - a[i]); };
  auto b_normal = [&](int j) { return perp_right(b[j] - b[(j == 0) ? nb - 1 : j - 1]); };
  const ClipPolygon* cur = &poly;
  // Area, centroid and the chord vector of the overlap polygon.
  const int n = cur->n;
  if (n < 3) return false;
  const Vec2 p0 = cur->p[0];
  double a2 = 0.0;
  Vec2 c{0.0, 0.0};
  Vec2 chord_a{0.0, 0.0}, chord_b{0.0, 0.0};
  for (int k = 0; k < n; ++k) {
    const int k1 = (k + 1 == n) ? 0 : k + 1;
    const Vec2 e = cur->p[k1] - cur->p[k];
    (cur->edge[k] < na ? chord_a : chord_b) += perp_right(e);
    const Vec2 q0 = cur->p[k] - p0, q1 = cur->p[k1] - p0;
    const double w = cross(q0, q1);
    a2 += w;
    c += w * (q0 + q1);
  }
  if (!(a2 > 0.0)) return false;  // touching along an edge or at a vertex: no overlap
  out.area = 0.5 * a2;
  // chord_a = -chord_b for a closed polygon; averaging keeps the result antisymmetric in A and B.
  const Vec2 chord = 0.5 * (chord_a - chord_b);
  const double len = chord.norm();
  Vec2 lo = p0, hi = p0;  // bounding box of the overlap polygon
  for (int k = 1; k < n; ++k) {
    lo = lo.cwiseMin(cur->p[k]);
    hi = hi.cwiseMax(cur->p[k]);
  }
  const double scale = std::max((hi - p0).maxCoeff(), (p0 - lo).maxCoeff());  // max |p_k - p0|_inf
  // Centroid, relative to `origin`. Kept in the overlap's bounding box, where it lies in exact arithmetic: for a
  // sliver whose area is round-off (faces flush to within epsilon) the quotient can land metres away.
  const Vec2 g = (p0 + c / (3.0 * a2)).cwiseMax(lo).cwiseMin(hi);
  out.point = origin + g;
  out.moment = 0.0;
  out.ga = out.gb = Vec2{0.0, 0.0};
  out.ha = out.hb = 0.0;
  out.energy = out.load_moment = out.extent = out.breadth = 0.0;
  out.slope = 1.0;
  out.load = Vec2{0.0, 0.0};
  auto foundation = [&] {
    const detail::FoundationTerms f =
        detail::foundation_terms(a, b, lines_a, lines_b, origin, cur->p, cur->edge, n, g, out.area);
    out.energy = f.energy;
    out.load = f.force;
    out.load_moment = f.moment;
    out.extent = f.extent;
    out.breadth = f.breadth;
  };
  if (!(len > 1e-9 * scale)) {
    // One polygon inside the other: no boundary crossing to define a chord. Or one of them, far smaller than its
    // distance from `origin` (by 1/epsilon), collapsed there by round-off to a segment or a point that cut a sliver
    // of round-off: no overlap.
    auto collapsed = [&](std::span<const Vec2> v) {  // its area, from its coordinates relative to `origin`
      const Vec2 t0 = v[0] - origin;
      double twice_area = 0.0;
      for (std::size_t k = 1; k + 1 < v.size(); ++k) twice_area += cross(v[k] - origin - t0, v[k + 1] - origin - t0);
      return !(twice_area > 0.0);
    };
    if (collapsed(a) || collapsed(b)) return false;
    out.chord = 0.0;
    least_penetration(a, b, out);
    if (terms == OverlapTerms::foundation) foundation();
    return true;
  }
  out.chord = len;
  out.normal = chord / len;
  out.depth = out.area / len;
  // A sliver thinner than the round-off of the coordinates it was computed from (the pair's distance from the world
  // origin, the overlap's from `origin`, its own size) is a touch that round-off opened up (a vertex exactly on an
  // edge gave 1e-17 m slivers: tests/unit/test_contact_failure_modes.cpp): no contact.
  const double coords = std::max({origin.cwiseAbs().maxCoeff(), p0.cwiseAbs().maxCoeff(), scale});
  if (!(out.depth > 64.0 * std::numeric_limits<double>::epsilon() * coords)) return false;
  if (terms == OverlapTerms::foundation) foundation();
  if (terms == OverlapTerms::basic) {
    // The depth's slope: the chord's rate of growth with the approach (gb . normal, as the gradient terms below take
    // it, but every crossing of edges that are not parallel counts: a wedge of nearly parallel faces crosses fast
    // but bounds a thin overlap, S/L^2 dL/dx stays of order 1), kept to [1/4, 4] against round-off.
    double gbn = 0.0;
    for (int k = 0, in = cur->edge[n - 1]; k < n; in = cur->edge[k++]) {
      const int outgoing = cur->edge[k];
      if ((in < na) == (outgoing < na)) continue;
      const bool exit = in < na;
      const Vec2 n_a = a_normal(exit ? in : outgoing), n_b = b_normal((exit ? outgoing : in) - na);
      const double det = cross(n_a, n_b);
      if (det == 0.0) continue;
      const double rate = cross(out.normal, geometry::perp_left(n_a)) * n_b.dot(out.normal) / det;
      gbn += exit ? rate : -rate;
    }
    out.slope = std::clamp(1.0 + out.area / (len * len) * gbn, 0.25, 4.0);
  }
  if (terms != OverlapTerms::depth_gradient) return true;
  // Gradient terms: the moment of the ∂A part (averaged with minus the ∂B part) and the sliding crossings.
  double m_a = 0.0, m_b = 0.0;
  for (int k = 0; k < n; ++k) {
    const int k1 = (k + 1 == n) ? 0 : k + 1;
    const Vec2 ne = perp_right(cur->p[k1] - cur->p[k]);
    const double m = cross(0.5 * (cur->p[k] + cur->p[k1]) - g, ne);
    (cur->edge[k] < na ? m_a : m_b) += m;
    const int in = cur->edge[(k == 0) ? n - 1 : k - 1], outgoing = cur->edge[k];
    if ((in < na) == (outgoing < na)) continue;  // not a crossing of the two boundaries
    // Exit of a ∂A chain (arriving on A, leaving on B) counts +, an entry -.
    const bool exit = in < na;
    const int ia = exit ? in : outgoing, jb = (exit ? outgoing : in) - na;
    const Vec2 n_a = a_normal(ia), n_b = b_normal(jb);
    const double det = cross(n_a, n_b);
    // Nearly parallel edges: the crossing's speed is unbounded but the overlap it bounds is a sliver whose
    // contribution S/L^2 * dL vanishes with it; leave it out rather than divide by ~0.
    if (std::abs(det) <= 1e-9 * n_a.norm() * n_b.norm()) continue;
    const double sgn = exit ? 1.0 : -1.0;
    const double c1 = sgn * cross(out.normal, perp_right(n_b)) / det;
    const double c2 = sgn * cross(out.normal, geometry::perp_left(n_a)) / det;
    const Vec2 r = cur->p[k] - g;
    out.ga += c1 * n_a;
    out.ha += c1 * cross(r, n_a);
    out.gb += c2 * n_b;
    out.hb += c2 * cross(r, n_b);
  }
  out.moment = 0.5 * (m_a - m_b);
  return true;
}

}  // namespace

double separation_lower_bound(std::span<const Vec2> a, std::span<const Vec2> b) {
  Vec2 axis;
  return max_separation(a, b, axis);
}

}  // namespace polyfloe::contact
