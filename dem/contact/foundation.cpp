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

// Keeps the part of `in` where w·x <= c; the cut's edges are internal.
void clip(const Piece& in, const Vec2& w, double c, Piece& out) {
  double s[kMaxPiece];
  for (int k = 0; k < in.n; ++k) s[k] = w.dot(in.p[k]) - c;
  out.n = 0;
  for (int k = 0; k < in.n; ++k) {
    const int k1 = (k + 1 == in.n) ? 0 : k + 1;
    const bool in0 = s[k] <= 0.0, in1 = s[k1] <= 0.0;
    if (out.n + 2 > kMaxPiece) break;  // cannot happen: each cut adds at most one vertex
    if (in0) {
      out.p[out.n] = in.p[k];
      out.edge[out.n++] = in.edge[k];
    }
    if (in0 != in1) {
      const double t = s[k] / (s[k] - s[k1]);
      out.p[out.n] = in.p[k] + t * (in.p[k1] - in.p[k]);
      out.edge[out.n++] = in0 ? kInternal : in.edge[k];
    }
  }
}

// Adds ∫_Q h dA to the energy and sign * (∫ h ν ds, ∫ h cross(x - g, ν) ds) over Q's edges on the other body's
// boundary (labels >= na when that body is B, in [0, na) when it is A) to the force and moment. h is linear on Q.
void integrate(const Vec2* qp, const int* qe, int qn, const Line& h, bool other_is_b, int na, const Vec2& g,
               double sign, FoundationTerms& out) {
  if (qn < 3) return;
  const Vec2 q0 = qp[0];
  double a2 = 0.0;
  Vec2 cm{0.0, 0.0}, force{0.0, 0.0};
  double moment = 0.0;
  double hp = h.at(qp[0]);
  for (int k = 0; k < qn; ++k) {
    const int k1 = (k + 1 == qn) ? 0 : k + 1;
    const Vec2 u = qp[k] - q0, v = qp[k1] - q0;
    const double w = cross(u, v);
    a2 += w;
    cm += w * (u + v);
    const double hq = h.at(qp[k1]);
    const int e = qe[k];
    if (e >= 0 && (e >= na) == other_is_b) {
      const Vec2 nrm = perp_right(qp[k1] - qp[k]);  // outward normal x length
      const Vec2 rp = qp[k] - g, rq = qp[k1] - g;
      const Vec2 r = (hp * rp + hq * rq) / 3.0 + (hp * rq + hq * rp) / 6.0;
      force += 0.5 * (hp + hq) * nrm;
      moment += cross(r, nrm);
    }
    hp = hq;
  }
  out.force += sign * force;
  out.moment += sign * moment;
  if (a2 > 0.0) out.energy += 0.5 * a2 * h.at(q0 + cm / (3.0 * a2));
}

// The parts of `in` where w·x <= c and where w·x > c (the cut's edges internal in both).
void split(const Piece& in, const Vec2& w, double c, Piece& lo, Piece& hi) {
  double s[kMaxPiece];
  for (int k = 0; k < in.n; ++k) s[k] = w.dot(in.p[k]) - c;
  lo.n = hi.n = 0;
  for (int k = 0; k < in.n; ++k) {
    const int k1 = (k + 1 == in.n) ? 0 : k + 1;
    const bool in0 = s[k] <= 0.0, in1 = s[k1] <= 0.0;
    if (lo.n + 2 > kMaxPiece || hi.n + 2 > kMaxPiece) break;  // cannot happen: a cut adds at most one vertex
    Piece& here = in0 ? lo : hi;
    here.p[here.n] = in.p[k];
    here.edge[here.n++] = in.edge[k];
    if (in0 != in1) {
      const double t = s[k] / (s[k] - s[k1]);
      const Vec2 x = in.p[k] + t * (in.p[k1] - in.p[k]);
      Piece& there = in0 ? hi : lo;
      here.p[here.n] = x;  // leaving `here` along the cut
      here.edge[here.n++] = kInternal;
      there.p[there.n] = x;  // entering `there`, continuing the edge
      there.edge[there.n++] = in.edge[k];
    }
  }
}

// The part of I and of its gradient that comes from one body's distance field: d_X over P, and its line load on
// the part of ∂P that lies on the other body's boundary (sign -1 for X = A, +1 for X = B).
void body_field(std::span<const Vec2> x, bool x_is_a, int na, const Vec2& origin, const Vec2* p, const int* edge, int n,
                const Vec2& g, FoundationTerms& out) {
  const int nx = static_cast<int>(x.size());
  // X's edge i relative to the origin: start s and direction e (A's edge i: a[i] -> a[i+1]; B's edge j:
  // b[j-1] -> b[j]); the distance inside its line is cross(e, x - s) / |e|.
  auto start = [&](int i) { return (x_is_a ? x[i] : x[(i == 0) ? nx - 1 : i - 1]) - origin; };
  auto direction = [&](int i) {
    return x_is_a ? Vec2(x[(i + 1 == nx) ? 0 : i + 1] - x[i]) : Vec2(x[i] - x[(i == 0) ? nx - 1 : i - 1]);
  };
  auto line = [&](int i) {
    const Vec2 e = direction(i);
    const double len = e.norm();
    const Vec2 m = len > 0.0 ? Vec2(perp_left(e) / len) : Vec2(0.0, 0.0);
    return Line{m, m.dot(start(i))};
  };
  auto own = [&](int e) { return e >= 0 && (e < na) == x_is_a; };
  auto own_index = [&](int e) { return x_is_a ? e : e - na; };
  // An upper bound of d_X over P: the largest distance of P's vertices from any one edge of X that bounds P (P
  // lies inside that edge's line), else (P has no edge on X's boundary: the other body lies inside X) from any
  // edge of X.
  double upper = std::numeric_limits<double>::infinity();
  auto bound_by = [&](const Line& l) {
    double hi = 0.0;
    for (int v = 0; v < n; ++v) hi = std::max(hi, l.at(p[v]));
    upper = std::min(upper, hi);
  };
  bool any_own = false;
  for (int k = 0; k < n; ++k)
    if (own(edge[k])) any_own = true, bound_by(line(own_index(edge[k])));
  if (!any_own)
    for (int i = 0; i < nx; ++i) bound_by(line(i));
  // The edges that can be nearest somewhere in P: those whose line comes within `upper` of one of P's vertices
  // (P is convex and the distance linear). First a test against the circle about g that holds P, radius r, then
  // against the vertices; both on cross(e, x - s) = |e| h(x), without the square root.
  double radius2 = 0.0;
  for (int v = 0; v < n; ++v) radius2 = std::max(radius2, (p[v] - g).squaredNorm());
  const double radius = std::sqrt(radius2);
  auto within = [&](double c, double reach, double len2) { return c <= 0.0 || c * c < reach * reach * len2; };
  Line lines[kMaxPolygonVertices];
  int nn = 0;
  for (int i = 0; i < nx; ++i) {
    const Vec2 s = start(i), e = direction(i);
    const double len2 = e.squaredNorm();
    if (!within(cross(e, g - s), upper + radius, len2)) continue;
    double c_min = std::numeric_limits<double>::infinity();
    for (int v = 0; v < n; ++v) c_min = std::min(c_min, cross(e, p[v] - s));
    if (within(c_min, upper, len2)) lines[nn++] = line(i);
  }
  if (nn == 0) return;  // P has no thickness
  const double sign = x_is_a ? -1.0 : 1.0;
  const bool other = x_is_a;  // the other body is B when X is A
  if (nn == 1) {
    integrate(p, edge, n, lines[0], other, na, g, sign, out);
    return;
  }
  Piece whole;
  whole.n = n;
  for (int k = 0; k < n; ++k) {
    whole.p[k] = p[k];
    whole.edge[k] = edge[k];
  }
  // d_X = h_i where h_i <= h_j for every other near edge j: P cut into those regions (for two, by one line).
  if (nn == 2) {
    Piece lo, hi;
    split(whole, lines[0].m - lines[1].m, lines[0].c - lines[1].c, lo, hi);
    integrate(lo.p, lo.edge, lo.n, lines[0], other, na, g, sign, out);
    integrate(hi.p, hi.edge, hi.n, lines[1], other, na, g, sign, out);
    return;
  }
  Piece buf[2];
  for (int a = 0; a < nn; ++a) {
    const Line& li = lines[a];
    const Piece* cur = &whole;
    int which = 0;
    for (int b = 0; b < nn && cur->n >= 3; ++b) {
      if (b == a) continue;
      const Line& lj = lines[b];
      clip(*cur, li.m - lj.m, li.c - lj.c, buf[which]);
      cur = &buf[which];
      which ^= 1;
    }
    integrate(cur->p, cur->edge, cur->n, li, other, na, g, sign, out);
  }
}

}  // namespace

FoundationTerms foundation_terms(std::span<const Vec2> a, std::span<const Vec2> b, const Vec2& origin, const Vec2* p,
                                 const int* edge, int n, const Vec2& g) {
  FoundationTerms t;
  const int na = static_cast<int>(a.size());
  body_field(a, true, na, origin, p, edge, n, g, t);
  body_field(b, false, na, origin, p, edge, n, g, t);
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
