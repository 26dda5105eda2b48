#include "contact/narrow_phase_planar.h"

#include <algorithm>
#include <cmath>
#include <limits>

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
// pointing from A to B: > 0 is a lower bound of their distance, <= 0 minus the least penetration.
double max_separation(std::span<const Vec2> a, std::span<const Vec2> b, Vec2& axis) {
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

}  // namespace

bool planar_overlap(std::span<const Vec2> a, std::span<const Vec2> b, PlanarContact& out, bool with_gradient) {
  const int na = static_cast<int>(a.size());
  const int nb = static_cast<int>(b.size());
  // Work relative to A's first vertex: keeps precision for floes far from the origin.
  const Vec2 origin = a[0];

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
    if (hi_a <= lo_b && axis != Vec2::Zero()) return false;
  }

  ClipPolygon buf[2];
  ClipPolygon* cur = &buf[0];
  ClipPolygon* nxt = &buf[1];
  cur->n = na;
  for (int i = 0; i < na; ++i) {
    cur->p[i] = a[i] - origin;
    cur->edge[i] = i;
  }
  // A's edge i runs from a[i] to a[i+1]; B's edge j from b[j-1] to b[j] (the order the clipping visits them).
  auto a_normal = [&](int i) { return perp_right(a[(i + 1 == na) ? 0 : i + 1] - a[i]); };
  auto b_normal = [&](int j) { return perp_right(b[j] - b[(j == 0) ? nb - 1 : j - 1]); };

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
      if (s[k] > 0.0) any_out = true; else any_in = true;
    }
    if (!any_out) continue;      // this edge of B does not cut the polygon
    if (!any_in) return false;   // the polygon lies wholly outside: separated (or touching)
    int m = 0;
    for (int k = 0; k < cur->n; ++k) {
      const int k1 = (k + 1 == cur->n) ? 0 : k + 1;
      const bool in0 = s[k] <= 0.0, in1 = s[k1] <= 0.0;
      // At most na + nb vertices in exact arithmetic (< kMaxClipped); this only guards the buffer.
      if (m + 2 > kMaxClipped) return false;
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
    if (jj + 1 < nb) bound();
  }

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
  if (!with_gradient) return true;
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

double separation_lower_bound(std::span<const Vec2> a, std::span<const Vec2> b) {
  Vec2 axis;
  return max_separation(a, b, axis);
}

DepthGradient depth_gradient(const PlanarContact& g, const Vec2& x_a, const Vec2& x_b) {
  DepthGradient d;
  const Vec2 da = x_a - g.point, db = x_b - g.point;  // body centres relative to the centroid
  if (g.chord > 0.0) {
    // depth = S/L: d(depth) = dS/L - S/L^2 dL, with dS/dv_b = -N and dS/dw_b = -(M - cross(x_b - c, N)).
    const double inv_l = 1.0 / g.chord, s_l2 = g.area * inv_l * inv_l;
    const Vec2 n_vec = g.chord * g.normal;
    d.grad_b = -g.normal - s_l2 * g.gb;
    d.grad_wb = -(g.moment - cross(db, n_vec)) * inv_l - s_l2 * (g.hb - cross(db, g.gb));
  } else {
    d.grad_b = -g.normal;
    d.grad_wb = cross(db, g.normal);
  }
  d.grad_a = -d.grad_b;
  d.grad_wa = -d.grad_wb + cross(da - db, d.grad_b);
  return d;
}

}  // namespace polyfloe::contact
