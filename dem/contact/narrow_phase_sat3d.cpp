#include "contact/narrow_phase_sat3d.h"

#include <cmath>
#include <limits>

namespace polyfloe::contact {

namespace {

struct Extent {
  double lo = std::numeric_limits<double>::infinity(), hi = -std::numeric_limits<double>::infinity();
};

Extent project(std::span<const Vec3> v, const Vec3& n) {
  Extent e;
  for (const Vec3& x : v) {
    const double d = n.dot(x);
    e.lo = std::min(e.lo, d);
    e.hi = std::max(e.hi, d);
  }
  return e;
}

// Closest points of segments p0-p1 and q0-q1; returns their midpoint.
Vec3 segment_midpoint(const Vec3& p0, const Vec3& p1, const Vec3& q0, const Vec3& q1) {
  const Vec3 d1 = p1 - p0, d2 = q1 - q0, r = p0 - q0;
  const double a = d1.squaredNorm(), e = d2.squaredNorm(), f = d2.dot(r);
  const double c = d1.dot(r), b = d1.dot(d2);
  const double denom = a * e - b * b;
  double s = denom > 1e-300 ? std::clamp((b * f - c * e) / denom, 0.0, 1.0) : 0.0;
  double t = e > 0.0 ? (b * s + f) / e : 0.0;
  if (t < 0.0) {
    t = 0.0;
    s = a > 0.0 ? std::clamp(-c / a, 0.0, 1.0) : 0.0;
  } else if (t > 1.0) {
    t = 1.0;
    s = a > 0.0 ? std::clamp((b - c) / a, 0.0, 1.0) : 0.0;
  }
  return 0.5 * ((p0 + s * d1) + (q0 + t * d2));
}

// The edge of `s` (world vertices `w`) most nearly attaining the support along n: both ends within tol of the max.
int supporting_edge(const geometry::ConvexPolyhedron& s, std::span<const Vec3> w, const Vec3& n, const Vec3& dir) {
  int best = 0;
  double best_score = -std::numeric_limits<double>::infinity();
  const auto& edges = s.edges();
  for (int k = 0; k < static_cast<int>(edges.size()); ++k) {
    const Vec3& p = w[edges[k].first];
    const Vec3& q = w[edges[k].second];
    // prefer edges parallel to the axis' edge direction, then the highest along n
    const double along = std::abs((q - p).normalized().dot(dir));
    const double score = n.dot(p) + n.dot(q) - (along > 1.0 - 1e-9 ? 0.0 : 1e300);
    if (score > best_score) {
      best_score = score;
      best = k;
    }
  }
  return best;
}

}  // namespace

SatContact sat_penetration(const geometry::ConvexPolyhedron& a, const Mat3& rot_a, std::span<const Vec3> world_a,
                           const Vec3& centre_a, const geometry::ConvexPolyhedron& b, const Mat3& rot_b,
                           std::span<const Vec3> world_b, const Vec3& centre_b) {
  SatContact out;
  double best = std::numeric_limits<double>::infinity();
  Vec3 best_n = Vec3::UnitZ();
  SatFeature feature = SatFeature::face_a;
  Vec3 ea_dir = Vec3::Zero(), eb_dir = Vec3::Zero();
  // Face axes. A's face f: overlap = offset - min over B along n (n already points out of A, towards B).
  for (const auto& f : a.faces()) {
    ++out.axes;
    const Vec3 n = rot_a * f.normal;
    const double top = n.dot(world_a[f.loop[0]]);
    double lo = std::numeric_limits<double>::infinity();
    for (const Vec3& y : world_b) lo = std::min(lo, n.dot(y));
    const double o = top - lo;
    if (o <= 0.0) return out;
    if (o < best) best = o, best_n = n, feature = SatFeature::face_a;
  }
  for (const auto& f : b.faces()) {
    ++out.axes;
    const Vec3 n = rot_b * f.normal;  // out of B, towards A: the normal from A to B is -n
    const double top = n.dot(world_b[f.loop[0]]);
    double lo = std::numeric_limits<double>::infinity();
    for (const Vec3& x : world_a) lo = std::min(lo, n.dot(x));
    const double o = top - lo;
    if (o <= 0.0) return out;
    if (o < best) best = o, best_n = -n, feature = SatFeature::face_b;
  }
  // Edge x edge axes; a face axis wins ties (a tiny relative margin keeps the choice stable on flat contacts).
  const double margin = 1e-12 * (a.circumradius() + b.circumradius());
  for (const Vec3& da : a.edge_directions()) {
    const Vec3 ua = rot_a * da;
    for (const Vec3& db : b.edge_directions()) {
      const Vec3 ub = rot_b * db;
      Vec3 n = ua.cross(ub);
      const double len = n.norm();
      if (len < 1e-9) continue;  // parallel edges: their plane's normal is among the face axes
      ++out.axes;
      n /= len;
      if (n.dot(centre_b - centre_a) < 0.0) n = -n;
      const Extent pa = project(world_a, n), pb = project(world_b, n);
      const double o = std::min(pa.hi - pb.lo, pb.hi - pa.lo);
      if (o <= 0.0) return out;
      if (o < best - margin) {
        best = o;
        best_n = pa.hi - pb.lo <= pb.hi - pa.lo ? n : Vec3(-n);
        feature = SatFeature::edge_edge;
        ea_dir = ua;
        eb_dir = ub;
      }
    }
  }
  out.hit = true;
  out.depth = best;
  out.normal = best_n;
  out.feature = feature;
  const double tol = 1e-9 * (a.circumradius() + b.circumradius());
  if (feature == SatFeature::edge_edge) {
    const auto& ea = a.edges()[supporting_edge(a, world_a, best_n, ea_dir)];
    const auto& eb = b.edges()[supporting_edge(b, world_b, -best_n, eb_dir)];
    out.point = segment_midpoint(world_a[ea.first], world_a[ea.second], world_b[eb.first], world_b[eb.second]);
  } else {
    // the deepest vertices of the other body along the normal (their centroid when several tie), lifted by d/2
    const bool on_a = feature == SatFeature::face_a;
    const auto other = on_a ? world_b : world_a;
    const Vec3 n = on_a ? best_n : Vec3(-best_n);  // from the face's body towards the other
    double lo = std::numeric_limits<double>::infinity();
    for (const Vec3& y : other) lo = std::min(lo, n.dot(y));
    Vec3 sum = Vec3::Zero();
    int count = 0;
    for (const Vec3& y : other) {
      if (n.dot(y) <= lo + tol) sum += y, ++count;
    }
    out.point = sum / count + 0.5 * best * n;
  }
  return out;
}

}  // namespace polyfloe::contact
