#include "contact/narrow_phase_sat3d.h"

#include <array>
#include <cmath>
#include <limits>

namespace polyfloe::contact {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

// The overlap of the two projections on n (any length: the overlap is in units of |n|), min(max_A - min_B,
// max_B - min_A), and which side is the shallower (`b_beyond`: B lies along +n of A). Scanning only widens the
// extents, so the overlap only grows: the scan stops as soon as it reaches `stop` (this axis cannot be the least).
// Vertices are taken from both ends of the list inwards (0, N-1, 1, N-2, ...): a prism's bottom and top rings are
// then both met at once, and most axes stop after a vertex or two of each body.
// `centres`: centre of B minus centre of A, which breaks an exact tie of the two sides (B's projection centred
// inside A's).
// `stop2`: the square of the stopping overlap (in units of |n|: no square root per axis).
double overlap_on(std::span<const Vec3> a, std::span<const Vec3> b, const Vec3& n, const Vec3& centres, double stop2,
                  bool& b_beyond) {
  double alo = kInf, ahi = -kInf, blo = kInf, bhi = -kInf;
  const std::size_t na = a.size(), nb = b.size(), m = std::max(na, nb);
  auto spread = [](std::size_t i, std::size_t size) { return (i & 1) ? size - 1 - i / 2 : i / 2; };
  for (std::size_t i = 0; i < m; ++i) {
    if (i < na) {
      const double d = n.dot(a[spread(i, na)]);
      alo = std::min(alo, d);
      ahi = std::max(ahi, d);
    }
    if (i < nb) {
      const double d = n.dot(b[spread(i, nb)]);
      blo = std::min(blo, d);
      bhi = std::max(bhi, d);
    }
    const double o = std::min(ahi - blo, bhi - alo);
    if (o > 0.0 && o * o >= stop2) return kInf;
  }
  const double fwd = ahi - blo, back = bhi - alo;
  b_beyond = fwd < back || (fwd == back && n.dot(centres) >= 0.0);
  return std::min(fwd, back);
}

// top - min over `v` of n . x, stopping once it reaches `stop` (same scan order as above).
double face_overlap(std::span<const Vec3> v, const Vec3& n, double top, double stop) {
  double lo = kInf;
  const std::size_t nv = v.size();
  for (std::size_t i = 0; i < nv; ++i) {
    lo = std::min(lo, n.dot(v[(i & 1) ? nv - 1 - i / 2 : i / 2]));
    if (top - lo >= stop) return stop;
  }
  return top - lo;
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
    // prefer edges parallel to the axis' edge direction (the criterion that merged the directions:
    // geometry/polyhedron.cpp), then the highest along n
    const bool parallel = (q - p).normalized().cross(dir).norm() < 1e-9;
    const double score = n.dot(p) + n.dot(q) - (parallel ? 0.0 : 1e300);
    if (score > best_score) {
      best_score = score;
      best = k;
    }
  }
  return best;
}

}  // namespace

double least_face_overlap(const geometry::ConvexPolyhedron& a, const Mat3& rot_a, std::span<const Vec3> world_a,
                          const geometry::ConvexPolyhedron& b, const Mat3& rot_b, std::span<const Vec3> world_b) {
  double best = kInf;
  for (const auto& f : a.faces()) {
    const Vec3 n = rot_a * f.normal;
    best = std::min(best, face_overlap(world_b, n, n.dot(world_a[f.loop[0]]), best));
    if (best <= 0.0) return best;
  }
  for (const auto& f : b.faces()) {
    const Vec3 n = rot_b * f.normal;
    best = std::min(best, face_overlap(world_a, n, n.dot(world_b[f.loop[0]]), best));
    if (best <= 0.0) return best;
  }
  return best;
}

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
    const double o = face_overlap(world_b, n, n.dot(world_a[f.loop[0]]), best);
    if (o <= 0.0) return out;
    if (o < best) best = o, best_n = n, feature = SatFeature::face_a;
  }
  for (const auto& f : b.faces()) {
    ++out.axes;
    const Vec3 n = rot_b * f.normal;  // out of B, towards A: the normal from A to B is -n
    const double o = face_overlap(world_a, n, n.dot(world_b[f.loop[0]]), best);
    if (o <= 0.0) return out;
    if (o < best) best = o, best_n = -n, feature = SatFeature::face_b;
  }
  // Edge x edge axes; a face axis wins ties (a tiny relative margin keeps the choice stable on flat contacts).
  const double margin = 1e-12 * (a.circumradius() + b.circumradius());
  // B's edge directions in the world frame, once (on the stack for up to kMaxDirections of them).
  constexpr std::size_t kMaxDirections = 128;
  std::array<Vec3, kMaxDirections> b_dirs;
  const auto& bd = b.edge_directions();
  const bool b_cached = bd.size() <= kMaxDirections;
  if (b_cached) {
    for (std::size_t j = 0; j < bd.size(); ++j) b_dirs[j] = rot_b * bd[j];
  }
  for (const Vec3& da : a.edge_directions()) {
    const Vec3 ua = rot_a * da;
    for (std::size_t j = 0; j < bd.size(); ++j) {
      const Vec3 ub = b_cached ? b_dirs[j] : Vec3(rot_b * bd[j]);
      const Vec3 n = ua.cross(ub);  // not normalised: overlaps below are in units of |n|
      const double len2 = n.squaredNorm();
      if (len2 < 1e-18) continue;  // parallel edges: their plane's normal is among the face axes
      ++out.axes;
      bool b_beyond = true;
      const double stop = best - margin;
      const double o_raw = overlap_on(world_a, world_b, n, centre_b - centre_a, stop * stop * len2, b_beyond);
      if (o_raw <= 0.0) return out;
      if (o_raw == kInf) continue;
      const double len = std::sqrt(len2);
      const double o = o_raw / len;
      if (o < best - margin) {
        best = o;
        best_n = b_beyond ? Vec3(n / len) : Vec3(-n / len);
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
