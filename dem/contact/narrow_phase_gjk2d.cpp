#include "contact/narrow_phase_gjk2d.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "contact/narrow_phase_planar.h"  // kMaxPolygonVertices

// Conventions used throughout:
//   D = A - B = {x - y : x in A, y in B}, the Minkowski difference. The interiors overlap iff the origin is inside
//   D. Translating B by t moves D by -t, so the least t that separates the pair is the point of ∂D closest to the
//   origin: t = depth * n with n the outward normal of D there, which is therefore the normal from A to B.
//   Support functions scan the vertex lists (no adjacency used, so no walk can stall on a bad polygon). Every
//   point of D that the algorithm holds is a support point a[i] - b[j] and carries (i, j): EPA stops exactly
//   when the support along its nearest edge is one of that edge's ends.
//   Scratch lives on the stack (EPA's polygon: at most kMaxEpaVertices points); nothing is allocated.

namespace polyfloe::contact {

using geometry::cross;
using geometry::perp_left;
using geometry::perp_right;

namespace {

// D has at most na + nb <= 2 kMaxPolygonVertices vertices, and EPA's polygon holds only vertices of D (plus, in
// the degenerate start, points on its edges): 256 leaves room.
constexpr int kMaxEpaVertices = 256;
static_assert(kMaxEpaVertices >= 2 * kMaxPolygonVertices + 3);

struct Support {
  Vec2 w;  // a[i] - b[j] [m]
  int i, j;
};

// Support point of D along d: A's vertex furthest along d minus B's vertex furthest along -d. Ties keep the first.
Support support(std::span<const Vec2> a, std::span<const Vec2> b, const Vec2& d) {
  int i = 0, j = 0;
  double ha = d.dot(a[0]), hb = d.dot(b[0]);
  for (int k = 1; k < static_cast<int>(a.size()); ++k) {
    const double h = d.dot(a[k]);
    if (h > ha) {
      ha = h;
      i = k;
    }
  }
  for (int k = 1; k < static_cast<int>(b.size()); ++k) {
    const double h = d.dot(b[k]);
    if (h < hb) {
      hb = h;
      j = k;
    }
  }
  return {a[i] - b[j], i, j};
}

// EPA's polygon: counter-clockwise points of D; edge k runs from v[k] to v[k + 1] (cyclic).
struct EpaPolygon {
  Support v[kMaxEpaVertices];
  Vec2 normal[kMaxEpaVertices];  // unit outward normal of edge k
  double dist[kMaxEpaVertices];  // signed distance of edge k's line from the origin [m]
  int n = 0;

  // False when edge k has no direction (coincident ends) or is not finite.
  bool set_edge(int k) {
    const Vec2& p = v[k].w;
    const Vec2& q = v[k + 1 == n ? 0 : k + 1].w;
    const Vec2 e = q - p;
    const double len = e.norm();
    if (!(len > 0.0) || !std::isfinite(len)) return false;
    normal[k] = perp_right(e) / len;  // counter-clockwise: outward is to the right of the edge
    dist[k] = cross(p, q) / len;      // = normal·p = normal·q, one rounding fewer
    return std::isfinite(dist[k]);
  }
};

Gjk2dContact fail(Gjk2dContact r, const char* reason) {
  r.status = Gjk2dStatus::failed;
  r.reason = reason;
  r.depth = 0.0;
  r.normal = Vec2(1.0, 0.0);
  r.point = Vec2(0.0, 0.0);
  return r;
}

}  // namespace

Gjk2dContact gjk_epa_2d(std::span<const Vec2> a, std::span<const Vec2> b, const Gjk2dSettings& settings) {
  Gjk2dContact r;
  if (a.size() < 3 || b.size() < 3) return fail(r, "polygon with fewer than 3 vertices");
  if (a.size() > static_cast<std::size_t>(kMaxPolygonVertices) ||
      b.size() > static_cast<std::size_t>(kMaxPolygonVertices))
    return fail(r, "polygon with more than kMaxPolygonVertices vertices");
  if (!(settings.tolerance >= 0.0) || !std::isfinite(settings.tolerance))
    return fail(r, "tolerance negative or not finite");

  // Bounding boxes: the pair's size (EPA tolerance), the coordinates' magnitude (round-off), the first direction.
  // (cwiseMin/Max may drop a NaN, so finiteness is checked per vertex.)
  Vec2 lo_a = a[0], hi_a = a[0], lo_b = b[0], hi_b = b[0];
  bool finite = true;
  for (const Vec2& p : a) {
    finite = finite && p.allFinite();
    lo_a = lo_a.cwiseMin(p);
    hi_a = hi_a.cwiseMax(p);
  }
  for (const Vec2& p : b) {
    finite = finite && p.allFinite();
    lo_b = lo_b.cwiseMin(p);
    hi_b = hi_b.cwiseMax(p);
  }
  if (!finite) return fail(r, "non-finite vertex");
  const Vec2 lo = lo_a.cwiseMin(lo_b), hi = hi_a.cwiseMax(hi_b);
  const double size = (hi - lo).maxCoeff();                                               // [m]
  const double magnitude = std::max(lo.cwiseAbs().maxCoeff(), hi.cwiseAbs().maxCoeff());  // [m]
  // Products of two coordinates (dots, crosses, squared lengths) must not overflow.
  if (!(size > 0.0) || !(magnitude < 1e100)) return fail(r, "zero extent or coordinates beyond 1e100 m");
  const double extend_tol = settings.tolerance * size;  // EPA stops when the best edge moves out by less [m]
  // Depths at round-off level of the coordinates are touching: D's points carry errors of about eps * magnitude.
  const double touch = 64.0 * std::numeric_limits<double>::epsilon() * magnitude;  // [m]

  // ---- GJK: is the origin inside D? Simplex s[0..m), newest last; d points from the simplex toward the origin.
  // Each support evaluation counts as one iteration. The loop ends with a triangle holding the origin (interior
  // or on an edge) or with a support line along d that does not pass the origin (separated or touching).
  Support s[3];
  int m = 0;
  int gjk_it = 0;
  Vec2 d = 0.5 * ((lo_b + hi_b) - (lo_a + hi_a));  // from the centre of D's bounding box toward the origin
  if (!(d.squaredNorm() > 0.0)) d = Vec2(1.0, 0.0);
  bool degenerate_segment = false;  // origin on the line of the segment s[0] s[1] (so on the segment)
  for (;;) {
    if (gjk_it >= settings.max_gjk_iterations) {
      r.iterations = gjk_it;
      return fail(r, "GJK iteration limit");
    }
    const Support w = support(a, b, d);
    ++gjk_it;
    // No point of D lies strictly beyond the origin along d: the origin is outside D or on its boundary.
    if (!(w.w.dot(d) > 0.0)) {
      r.iterations = gjk_it;
      return r;  // separated
    }
    s[m++] = w;
    if (m == 1) {
      d = -w.w;  // nonzero: w·d > 0 above
      continue;
    }
    if (m == 2) {
      // s[0] lies behind the origin along d = -s[0] and s[1] strictly beyond it, so the origin projects inside the
      // segment: the new direction is the segment's normal toward the origin.
      const Vec2 e = s[0].w - s[1].w;
      const double side = cross(e, -s[1].w);
      if (side == 0.0) {
        degenerate_segment = true;
        break;
      }
      d = side > 0.0 ? perp_left(e) : perp_right(e);
      continue;
    }
    // m == 3: the newest point lies strictly beyond the line of the other two (its support value beats theirs
    // along d), so the triangle has area. The origin can only leave it through one of the two new edges.
    const Vec2 p = s[2].w, ab = s[1].w - p, ac = s[0].w - p, ao = -p;
    const double area2 = cross(ab, ac);
    if (!(area2 != 0.0) || !std::isfinite(area2)) {
      r.iterations = gjk_it;
      return fail(r, "degenerate GJK triangle");
    }
    const Vec2 ab_out = area2 > 0.0 ? perp_right(ab) : perp_left(ab);  // away from s[0]
    const Vec2 ac_out = area2 > 0.0 ? perp_left(ac) : perp_right(ac);  // away from s[1]
    if (ab_out.dot(ao) > 0.0) {
      s[0] = s[1];  // keep the edge (s[1], s[2]), order kept: newest last
      s[1] = s[2];
      m = 2;
      d = ab_out;
    } else if (ac_out.dot(ao) > 0.0) {
      s[1] = s[2];  // keep the edge (s[0], s[2])
      m = 2;
      d = ac_out;
    } else {
      break;  // origin inside the triangle or on one of its edges
    }
  }

  if (degenerate_segment) {
    // Origin on the segment s[0] s[1] (inside D or on ∂D): a third point off the segment's line on either side
    // makes a triangle with the origin on its edge, which EPA accepts. None on either side: D is flat.
    const Vec2 e = s[1].w - s[0].w;
    bool found = false;
    for (const Vec2& dir : {perp_left(e), perp_right(e)}) {
      if (gjk_it >= settings.max_gjk_iterations) {
        r.iterations = gjk_it;
        return fail(r, "GJK iteration limit");
      }
      const Support w = support(a, b, dir);
      ++gjk_it;
      if (w.w.dot(dir) - s[0].w.dot(dir) > 0.0) {
        s[2] = w;
        found = true;
        break;
      }
    }
    if (!found) {
      r.iterations = gjk_it;
      return fail(r, "degenerate Minkowski difference (zero area)");
    }
  }

  // ---- EPA: grow a counter-clockwise polygon inside D from the triangle until the edge nearest the origin is
  // an edge of D to within extend_tol. Its points are on ∂D in boundary order, so it stays convex: each new point
  // is the support along an edge's outward normal, which lies on the arc of ∂D that the edge cuts off.
  EpaPolygon poly;
  {
    const bool ccw = cross(s[1].w - s[0].w, s[2].w - s[0].w) > 0.0;
    poly.v[0] = s[0];
    poly.v[1] = ccw ? s[1] : s[2];
    poly.v[2] = ccw ? s[2] : s[1];
    poly.n = 3;
    for (int k = 0; k < 3; ++k)
      if (!poly.set_edge(k)) {
        r.iterations = gjk_it;
        return fail(r, "degenerate EPA start triangle");
      }
  }
  int epa_it = 0;
  int best = 0;
  for (;;) {
    best = 0;
    for (int k = 1; k < poly.n; ++k)
      if (poly.dist[k] < poly.dist[best]) best = k;
    if (epa_it >= settings.max_epa_iterations) {
      r.iterations = gjk_it + epa_it;
      return fail(r, "EPA iteration limit");
    }
    const Vec2 nrm = poly.normal[best];
    const Support w = support(a, b, nrm);
    ++epa_it;
    const int next = best + 1 == poly.n ? 0 : best + 1;
    const bool repeat =
        (w.i == poly.v[best].i && w.j == poly.v[best].j) || (w.i == poly.v[next].i && w.j == poly.v[next].j);
    // The true depth lies in [dist, w·n]: P ⊂ D, and D's support along n bounds the distance to ∂D.
    if (repeat || !(w.w.dot(nrm) - poly.dist[best] > extend_tol)) break;
    if (poly.n == kMaxEpaVertices) {
      r.iterations = gjk_it + epa_it;
      return fail(r, "EPA vertex limit");
    }
    // Insert w after v[best]: shift the tail one slot up.
    for (int k = poly.n; k > best + 1; --k) {
      poly.v[k] = poly.v[k - 1];
      poly.normal[k] = poly.normal[k - 1];
      poly.dist[k] = poly.dist[k - 1];
    }
    poly.v[best + 1] = w;
    ++poly.n;
    if (!poly.set_edge(best) || !poly.set_edge(best + 1)) {
      r.iterations = gjk_it + epa_it;
      return fail(r, "degenerate EPA edge");
    }
  }
  r.iterations = gjk_it + epa_it;

  const double depth = poly.dist[best];
  if (std::isnan(depth)) return fail(r, "non-finite EPA depth");
  if (depth <= touch) return r;  // touching (or round-off overlap): separated

  // Contact point. A's deepest feature along n (its vertices within feature_tol of A's support value: a vertex or
  // a face) and B's along -n face each other over a range of the tangent coordinate (both hold the witnesses of
  // the origin's foot on D's edge). The witness points are taken at the middle of that range, one on each
  // feature, and the point is their midpoint: halfway between the two support lines, at the vertex for a vertex
  // against a face, at the middle of the faces' common part for parallel faces (where rebuilding the witnesses
  // from the EPA edge's barycentric weight could land anywhere along it).
  const Vec2 nrm = poly.normal[best], tan = perp_left(nrm);
  const Vec2 o = a[0];  // coordinates relative to a point of the pair: precision far from the origin
  const double feature_tol = extend_tol + touch;                    // [m]
  double proj_a[kMaxPolygonVertices], proj_b[kMaxPolygonVertices];  // along nrm, relative to o [m]
  double ha = -std::numeric_limits<double>::infinity(), lb = std::numeric_limits<double>::infinity();
  for (std::size_t k = 0; k < a.size(); ++k) ha = std::max(ha, proj_a[k] = nrm.dot(a[k] - o));
  for (std::size_t k = 0; k < b.size(); ++k) lb = std::min(lb, proj_b[k] = nrm.dot(b[k] - o));
  double a_lo = std::numeric_limits<double>::infinity(), a_hi = -a_lo, b_lo = a_lo, b_hi = -a_lo;  // tangent [m]
  for (std::size_t k = 0; k < a.size(); ++k)
    if (proj_a[k] >= ha - feature_tol) {
      const double t = tan.dot(a[k] - o);
      a_lo = std::min(a_lo, t);
      a_hi = std::max(a_hi, t);
    }
  for (std::size_t k = 0; k < b.size(); ++k)
    if (proj_b[k] <= lb + feature_tol) {
      const double t = tan.dot(b[k] - o);
      b_lo = std::min(b_lo, t);
      b_hi = std::max(b_hi, t);
    }
  // The ranges share at least the foot's coordinate (up to feature_tol); if round-off parts them, their gap's middle.
  const double t_mid = 0.5 * (std::max(a_lo, b_lo) + std::min(a_hi, b_hi));
  r.status = Gjk2dStatus::contact;
  r.depth = depth;
  r.normal = nrm;
  r.point = o + t_mid * tan + (0.5 * (ha + lb)) * nrm;
  if (!std::isfinite(r.depth) || !r.normal.allFinite() || !r.point.allFinite()) return fail(r, "non-finite contact");
  return r;
}

}  // namespace polyfloe::contact
