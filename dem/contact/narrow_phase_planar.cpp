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
  bool on_a[kMaxClipped];
  int n = 0;
};

// Separating-axis fallback for containment (no boundary crossing): the axis of least penetration.
void least_penetration(std::span<const Vec2> a, std::span<const Vec2> b, PlanarContact& out) {
  double best = -std::numeric_limits<double>::infinity();
  Vec2 best_n{1.0, 0.0};
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
        best_n = sign * u;
      }
    }
  };
  scan(a, b, 1.0);   // A's face normals point from A to B
  scan(b, a, -1.0);  // B's face normals point from B to A
  out.normal = best_n;
  out.depth = std::max(0.0, -best);
}

}  // namespace

bool planar_overlap(std::span<const Vec2> a, std::span<const Vec2> b, PlanarContact& out) {
  const int na = static_cast<int>(a.size());
  const int nb = static_cast<int>(b.size());
  // Work relative to A's first vertex: keeps precision for floes far from the origin.
  const Vec2 origin = a[0];

  ClipPolygon buf[2];
  ClipPolygon* cur = &buf[0];
  ClipPolygon* nxt = &buf[1];
  cur->n = na;
  for (int i = 0; i < na; ++i) {
    cur->p[i] = a[i] - origin;
    cur->on_a[i] = true;
  }

  double s[kMaxClipped];
  Vec2 b0 = b[nb - 1] - origin;
  for (int j = 0; j < nb; ++j) {
    const Vec2 b1 = b[j] - origin;
    const Vec2 nrm = perp_right(b1 - b0);  // outward normal of B's edge (b0 -> b1), unnormalised
    const double d = nrm.dot(b0);
    b0 = b1;
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
      if (in0) {
        nxt->p[m] = cur->p[k];
        nxt->on_a[m++] = cur->on_a[k];
      }
      if (in0 != in1) {
        const double t = s[k] / (s[k] - s[k1]);
        nxt->p[m] = cur->p[k] + t * (cur->p[k1] - cur->p[k]);
        // Leaving the half-plane: the new edge runs along B's line. Entering: it continues the old edge.
        nxt->on_a[m++] = in0 ? false : cur->on_a[k];
      }
    }
    nxt->n = m;
    std::swap(cur, nxt);
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
    (cur->on_a[k] ? chord_a : chord_b) += perp_right(e);
    const Vec2 q0 = cur->p[k] - p0, q1 = cur->p[k1] - p0;
    const double w = cross(q0, q1);
    a2 += w;
    c += w * (q0 + q1);
  }
  if (!(a2 > 0.0)) return false;  // touching along an edge or at a vertex: no overlap
  out.area = 0.5 * a2;
  out.point = origin + p0 + c / (3.0 * a2);
  // chord_a = -chord_b for a closed polygon; averaging keeps the result antisymmetric in A and B.
  const Vec2 chord = 0.5 * (chord_a - chord_b);
  const double len = chord.norm();
  double scale = 0.0;
  for (int k = 0; k < n; ++k) scale = std::max(scale, (cur->p[k] - p0).lpNorm<Eigen::Infinity>());
  if (len > 1e-9 * scale) {
    out.chord = len;
    out.normal = chord / len;
    out.depth = out.area / len;
  } else {
    // One polygon inside the other: no boundary crossing to define a chord.
    out.chord = 0.0;
    least_penetration(a, b, out);
  }
  return true;
}

}  // namespace polyfloe::contact
