#include "contact/foundation.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "contact/narrow_phase_planar.h"

namespace polyfloe::contact::detail {

using geometry::cross;
using geometry::perp_left;
using geometry::perp_right;

namespace {

constexpr int kMaxPiece = 2 * kMaxPolygonVertices + 2 + kMaxPolygonVertices;
constexpr int kInternal = -1;  // a piece's edge along a line where two edges of the body are equally near

// A piece of the overlap polygon: vertices (relative to the origin) and the edge leaving each, labelled as the
// overlap's (kInternal for the cuts between the nearest-edge regions).
struct Piece {
  Vec2 p[kMaxPiece];
  int edge[kMaxPiece];
  int n = 0;
};

// The line of one edge of a body: distance inside it h(x) = m·x - c (m the unit inward normal).
struct Line {
  Vec2 m;
  double c;
  double at(const Vec2& x) const { return m.dot(x) - c; }
};

// The part of the piece (p, e, n) where w·x <= c into `out`; the cut's edges are internal. Returns false, leaving
// `out` alone, when the whole piece lies there (nothing to cut).
bool clip(const Vec2* p, const int* e, int n, const Vec2& w, double c, Piece& out) {
  double s[kMaxPiece];
  bool all_in = true;
  for (int k = 0; k < n; ++k) {
    s[k] = w.dot(p[k]) - c;
    all_in &= s[k] <= 0.0;
  }
  if (all_in) return false;
  out.n = 0;
  for (int k = 0; k < n; ++k) {
    const int k1 = (k + 1 == n) ? 0 : k + 1;
    const bool in0 = s[k] <= 0.0, in1 = s[k1] <= 0.0;
    if (out.n + 2 > kMaxPiece) break;  // cannot happen: each cut adds at most one vertex
    if (in0) {
      out.p[out.n] = p[k];
      out.edge[out.n++] = e[k];
    }
    if (in0 != in1) {
      const double t = s[k] / (s[k] - s[k1]);
      out.p[out.n] = p[k] + t * (p[k1] - p[k]);
      out.edge[out.n++] = in0 ? kInternal : e[k];
    }
  }
  return true;
}

// For h = min(h0, h1), linear on each side of the line h0 = h1 (h0 and h1 may be one line: h linear on all of
// it): adds sign * (∫ h ν ds, ∫ h cross(x - g, ν) ds) over the edges of the polygon (p, e, n) that lie on the
// other body's boundary (labels >= na when that body is B, in [0, na) when it is A) to the force and moment and,
// `with_energy`, ∫ h dA to the energy. In one pass without building the two parts: each edge (or its piece on
// either side of the cut) adds to its part, and each part's ∫ h dA is taken by the fan of triangles from a point O
// on the cut, so that the cut itself (a side of both parts, collinear with O) adds nothing. The cut carries no load.
void integrate_two(const Vec2* p, const int* e, int n, const Line& h0, const Line& h1, bool other_is_b, int na,
                   const Vec2& g, double sign, FoundationTerms& out, bool with_energy = true) {
  if (n < 3) return;
  double s[kMaxPiece];
  Vec2 o = p[0];  // O: where the boundary first crosses the cut (or any vertex, where it does not)
  if (&h0 == &h1) {
    std::fill(s, s + n, 0.0);  // one line: no cut
  } else {
    const Vec2 w = h0.m - h1.m;
    const double c = h0.c - h1.c;
    for (int k = 0; k < n; ++k) s[k] = w.dot(p[k]) - c;
    for (int k = 0; k < n; ++k) {
      const int k1 = (k + 1 == n) ? 0 : k + 1;
      if ((s[k] <= 0.0) != (s[k1] <= 0.0)) {
        o = p[k] + s[k] / (s[k] - s[k1]) * (p[k1] - p[k]);
        break;
      }
    }
  }
  const double o0 = h0.at(o), o1 = h1.at(o);
  double energy6 = 0.0;   // 6 ∫ h dA
  Vec2 force2{0.0, 0.0};  // 2 ∫ h ν ds
  double moment6 = 0.0;   // 6 ∫ h cross(x - g, ν) ds
  // The segment a -> b of an edge with label `label`, in the part of h (its value at O: ho).
  auto segment = [&](const Vec2& a, const Vec2& b, int label, const Line& h, double ho) {
    const double ha = h.at(a), hb = h.at(b);
    if (with_energy) energy6 += cross(a - o, b - o) * (ho + ha + hb);  // 6 ∫ h dA
    if (label >= 0 && (label >= na) == other_is_b) {
      const Vec2 nrm = perp_right(b - a);                                     // outward normal x length
      const Vec2 r6 = (2.0 * ha + hb) * (a - g) + (ha + 2.0 * hb) * (b - g);  // 6 x arm x mean load
      force2 += (ha + hb) * nrm;
      moment6 += cross(r6, nrm);
    }
  };
  for (int k = 0; k < n; ++k) {
    const int k1 = (k + 1 == n) ? 0 : k + 1;
    const bool in0 = s[k] <= 0.0, in1 = s[k1] <= 0.0;
    if (in0 == in1) {
      segment(p[k], p[k1], e[k], in0 ? h0 : h1, in0 ? o0 : o1);
    } else {
      const Vec2 x = p[k] + s[k] / (s[k] - s[k1]) * (p[k1] - p[k]);
      segment(p[k], x, e[k], in0 ? h0 : h1, in0 ? o0 : o1);
      segment(x, p[k1], e[k], in1 ? h0 : h1, in1 ? o0 : o1);
    }
  }
  out.force += (0.5 * sign) * force2;
  out.moment += (sign / 6.0) * moment6;
  if (energy6 > 0.0) out.energy += energy6 / 6.0;
}

// The parts of the piece (p, e, n) where w·x <= c and where w·x > c (the cut's edges internal in both).
void split(const Vec2* p, const int* e, int n, const Vec2& w, double c, Piece& lo, Piece& hi) {
  double s[kMaxPiece];
  for (int k = 0; k < n; ++k) s[k] = w.dot(p[k]) - c;
  lo.n = hi.n = 0;
  for (int k = 0; k < n && lo.n + 2 <= kMaxPiece && hi.n + 2 <= kMaxPiece; ++k) {  // (a cut adds one vertex)
    const int k1 = (k + 1 == n) ? 0 : k + 1;
    const bool in0 = s[k] <= 0.0, in1 = s[k1] <= 0.0;
    Piece& here = in0 ? lo : hi;
    here.p[here.n] = p[k];
    here.edge[here.n++] = e[k];
    if (in0 != in1) {
      const Vec2 x = p[k] + s[k] / (s[k] - s[k1]) * (p[k1] - p[k]);
      Piece& there = in0 ? hi : lo;
      here.p[here.n] = x;  // leaving `here` along the cut
      here.edge[here.n++] = kInternal;
      there.p[there.n] = x;  // entering `there`, continuing the edge
      there.edge[there.n++] = e[k];
    }
  }
}

// The most lines integrate_min() takes (it splits once per line beyond two, so its work doubles with each).
constexpr int kMaxSplitLines = 5;

// integrate_two() for h = the least of lines[0..k) over the piece (p, e, n), k <= kMaxSplitLines: the piece split where
// the first two lines are equal, each part going on with the lesser of them and the rest (two lines: in one pass).
void integrate_min(const Vec2* p, const int* e, int n, const Line* lines, int k, bool other_is_b, int na, const Vec2& g,
                   double sign, FoundationTerms& out) {
  if (n < 3) return;
  if (k == 1) return integrate_two(p, e, n, lines[0], lines[0], other_is_b, na, g, sign, out);
  if (k == 2) return integrate_two(p, e, n, lines[0], lines[1], other_is_b, na, g, sign, out);
  Piece lo, hi;
  split(p, e, n, lines[0].m - lines[1].m, lines[0].c - lines[1].c, lo, hi);
  Line rest[kMaxSplitLines];
  for (int j = 2; j < k; ++j) rest[j - 1] = lines[j];
  rest[0] = lines[0];
  integrate_min(lo.p, lo.edge, lo.n, rest, k - 1, other_is_b, na, g, sign, out);
  rest[0] = lines[1];
  integrate_min(hi.p, hi.edge, hi.n, rest, k - 1, other_is_b, na, g, sign, out);
}

// The part of I and of its gradient that comes from one body's distance field: d_X over P, and its line load on
// the part of ∂P that lies on the other body's boundary (sign -1 for X = A, +1 for X = B). `x`: X's edge lines
// (edge i from vertex i to i + 1; P labels B's edge j from vertex j - 1 to j).
void body_field(const EdgeLines& x, int nx, bool x_is_a, int na, const Vec2& origin, const Vec2* p, const int* edge,
                int n, const Vec2& g, double area, FoundationTerms& out) {
  // Line i relative to the origin: h_i(y) = normal[i]·y - (offset[i] - normal[i]·d), y = position - origin.
  const Vec2 d = origin - x.ref;
  auto line = [&](int i) {
    const Vec2 m{x.nx[i], x.ny[i]};
    return Line{m, x.offset[i] - m.dot(d)};
  };
  auto own = [&](int e) { return e >= 0 && (e < na) == x_is_a; };
  auto line_of = [&](int e) { return x_is_a ? e : (e == na ? nx - 1 : e - na - 1); };
  // Each edge's least and largest distance over P's vertices (P is convex and the distances linear), all edges at
  // once, vertex by vertex (vectorised).
  double nearest[kMaxPolygonVertices], farthest[kMaxPolygonVertices];
  for (int i = 0; i < nx; ++i) {
    nearest[i] = std::numeric_limits<double>::infinity();
    farthest[i] = -nearest[i];
  }
  for (int v = 0; v < n; ++v) {
    const double px = p[v].x() + d.x(), py = p[v].y() + d.y();
    for (int i = 0; i < nx; ++i) {
      const double h = x.nx[i] * px + x.ny[i] * py;
      nearest[i] = std::min(nearest[i], h);
      farthest[i] = std::max(farthest[i], h);
    }
  }
  // An upper bound of d_X over P: the largest distance of P's vertices from any one edge of X that bounds P (P
  // lies inside that edge's line), else (P has no edge on X's boundary: the other body lies inside X) from any
  // edge of X.
  double upper = std::numeric_limits<double>::infinity();
  bool any_own = false;
  for (int k = 0; k < n; ++k) {
    if (!own(edge[k])) continue;
    const int i = line_of(edge[k]);
    upper = std::min(upper, farthest[i] - x.offset[i]);
    any_own = true;
  }
  if (!any_own)
    for (int i = 0; i < nx; ++i) upper = std::min(upper, farthest[i] - x.offset[i]);
  upper = std::max(upper, 0.0);
  // The edges that can be nearest somewhere in P: those whose line comes within `upper` of one of P's vertices;
  // without branches (which pass is as good as random).
  int near[kMaxPolygonVertices];
  int nn = 0;
  for (int i = 0; i < nx; ++i) {
    const double h = nearest[i] - x.offset[i];
    near[nn] = i;
    nn += (h <= 0.0) | (h < upper);
  }
  Line lines[kMaxPolygonVertices];
  for (int k = 0; k < nn; ++k) lines[k] = line(near[k]);
  // Where there are many: an edge whose distance is at least another's at every vertex of P (so everywhere in P) is
  // nearest nowhere but on a set of no area: left out (of two equal lines, the first). (A few are split in turn,
  // where a beaten one leaves an empty piece at once.)
  int kept = 0;
  for (int i = 0; i < nn && nn > kMaxSplitLines; ++i) {
    bool beaten = false;
    for (int j = 0; j < nn && !beaten; ++j) {
      if (j == i || (j < i && lines[j].c != lines[j].c)) continue;  // (NaN c: an edge left out already)
      const Vec2 w = lines[i].m - lines[j].m;
      const double c = lines[i].c - lines[j].c;
      double least = std::numeric_limits<double>::infinity();
      for (int v = 0; v < n; ++v) least = std::min(least, w.dot(p[v]) - c);
      beaten = least >= 0.0;
    }
    if (beaten)
      lines[i].c = std::numeric_limits<double>::quiet_NaN();
    else
      ++kept;
  }
  if (nn > kMaxSplitLines && kept < nn) {
    int k = 0;
    for (int i = 0; i < nn; ++i)
      if (lines[i].c == lines[i].c) lines[k++] = lines[i];
    nn = k;
  }
  if (nn == 0) return;  // P has no thickness
  const double sign = x_is_a ? -1.0 : 1.0;
  const bool other = x_is_a;  // the other body is B when X is A
  if (nn == 1) {
    // All of P: ∫_P h dA = |P| h(centroid).
    integrate_two(p, edge, n, lines[0], lines[0], other, na, g, sign, out, false);
    out.energy += area * lines[0].at(g);
    return;
  }
  // d_X = h_i where h_i <= h_j for every other near edge j: P cut into those regions (a few by splitting in turn,
  // more by clipping P to each region).
  if (nn <= kMaxSplitLines) return integrate_min(p, edge, n, lines, nn, other, na, g, sign, out);
  Piece buf[2];
  for (int a = 0; a < nn; ++a) {
    const Line& li = lines[a];
    const Vec2* cp = p;
    const int* ce = edge;
    int cn = n, which = 0;
    for (int b = 0; b < nn && cn >= 3; ++b) {
      if (b == a) continue;
      const Line& lj = lines[b];
      if (!clip(cp, ce, cn, li.m - lj.m, li.c - lj.c, buf[which])) continue;  // all of it nearer to i than to j
      cp = buf[which].p, ce = buf[which].edge, cn = buf[which].n;
      which ^= 1;
    }
    integrate_two(cp, ce, cn, li, li, other, na, g, sign, out);
  }
}

}  // namespace

FoundationTerms foundation_terms(std::span<const Vec2> a, std::span<const Vec2> b, const EdgeLines* lines_a,
                                 const EdgeLines* lines_b, const Vec2& origin, const Vec2* p, const int* edge, int n,
                                 const Vec2& g, double area) {
  FoundationTerms t;
  const int na = static_cast<int>(a.size()), nb = static_cast<int>(b.size());
  double nx[2][kMaxPolygonVertices], ny[2][kMaxPolygonVertices], offset[2][kMaxPolygonVertices];
  auto lines_of = [&](std::span<const Vec2> v, const EdgeLines* given, int k) {
    if (given) return *given;
    edge_lines(v, nx[k], ny[k], offset[k]);
    return EdgeLines{nx[k], ny[k], offset[k], v[0]};
  };
  body_field(lines_of(a, lines_a, 0), na, true, na, origin, p, edge, n, g, area, t);
  body_field(lines_of(b, lines_b, 1), nb, false, na, origin, p, edge, n, g, area, t);
  if (const double l = t.force.norm(); l > 0.0) {
    const Vec2 across = perp_left(t.force);
    double lo = std::numeric_limits<double>::infinity(), hi = -lo, lo_t = lo, hi_t = -lo;
    for (int k = 0; k < n; ++k) {
      const double x = t.force.dot(p[k]), y = across.dot(p[k]);
      lo = std::min(lo, x);
      hi = std::max(hi, x);
      lo_t = std::min(lo_t, y);
      hi_t = std::max(hi_t, y);
    }
    t.extent = (hi - lo) / l;
    t.breadth = (hi_t - lo_t) / l;
  }
  return t;
}

}  // namespace polyfloe::contact::detail

namespace polyfloe::contact {

void edge_lines(std::span<const Vec2> v, double* nx, double* ny, double* offset) {
  const int n = static_cast<int>(v.size());
  for (int i = 0; i < n; ++i) {
    const Vec2 e = v[(i + 1 == n) ? 0 : i + 1] - v[i];
    const double len = e.norm();
    const Vec2 m = len > 0.0 ? Vec2(geometry::perp_left(e) / len) : Vec2(0.0, 0.0);
    nx[i] = m.x();
    ny[i] = m.y();
    offset[i] = m.dot(v[i] - v[0]);
  }
}

}  // namespace polyfloe::contact
