// The failure map's pair sets (bench_failure_map.cpp): random convex floes, the reference minimum translation
// distance (brute-force separating axes, independent of the code under test), and the cases of the map - random,
// far, separated, deep, mixed, parallel, vertex, touching - each a fixed-seed set of pairs with its reference.
// The cases are described in bench_failure_map.cpp's header.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <memory>
#include <numbers>
#include <random>
#include <span>
#include <string>
#include <vector>

#include "geometry/polygon.h"
#include "geometry/polyhedron.h"
#include "test_support.h"

namespace failure_map {

using polyfloe::geometry::Vec2;
using polyfloe::geometry::Vec3;
namespace geometry = polyfloe::geometry;
namespace tsupport = polyfloe::tsupport;

constexpr double kRhoIce = 920.0, kRhoWater = 1025.0;  // [kg/m^3], the scenes' defaults

struct Slab {
  double lo, hi;  // z-range [m]
  double thickness() const { return hi - lo; }
};
inline Slab floating(double h) {
  const double d = geometry::floating_draft(h, kRhoIce, kRhoWater);
  return {-d, h - d};
}

inline double uniform(std::mt19937_64& rng, double lo, double hi) {
  return lo + (hi - lo) * std::uniform_real_distribution<double>(0.0, 1.0)(rng);
}
inline double log_uniform(std::mt19937_64& rng, double lo, double hi) {
  return lo * std::pow(hi / lo, uniform(rng, 0, 1));
}

inline double angle_of(const Vec2& v) { return std::atan2(v.y(), v.x()); }

inline std::vector<Vec2> moved(const std::vector<Vec2>& v, double yaw, const Vec2& t) {
  return tsupport::transform(v, yaw, t);
}

inline bool valid(const std::vector<Vec2>& v) { return geometry::convexity_error(v).empty(); }

// 5-20 points at random angles on an ellipse of width 5-100 m (log-uniform), aspect 0.3-1, random yaw, centred
// near the origin, counter-clockwise.
inline std::vector<Vec2> random_floe(std::mt19937_64& rng) {
  const int n = 5 + static_cast<int>(uniform(rng, 0.0, 16.0));
  const double rx = 0.5 * log_uniform(rng, 5.0, 100.0), ry = rx * uniform(rng, 0.3, 1.0);
  for (;;) {
    auto v = moved(tsupport::random_convex(rng, std::min(n, 20), rx, ry), uniform(rng, 0.0, 2.0 * std::numbers::pi),
                   Vec2::Zero());
    if (valid(v)) return v;
  }
}

inline int next(int i, int n) { return i + 1 == n ? 0 : i + 1; }
inline int prev(int i, int n) { return i == 0 ? n - 1 : i - 1; }
inline Vec2 outward_normal(const std::vector<Vec2>& v, int i) {  // of edge i -> i + 1
  return geometry::perp_right(v[next(i, static_cast<int>(v.size()))] - v[i]).normalized();
}
inline int longest_edge(const std::vector<Vec2>& v) {
  const int n = static_cast<int>(v.size());
  int best = 0;
  for (int i = 1; i < n; ++i)
    if ((v[next(i, n)] - v[i]).norm() > (v[next(best, n)] - v[best]).norm()) best = i;
  return best;
}
inline Vec2 inward_bisector(const std::vector<Vec2>& v, int i) {
  const int n = static_cast<int>(v.size());
  return ((v[prev(i, n)] - v[i]).normalized() + (v[next(i, n)] - v[i]).normalized()).normalized();
}
inline double interior_angle(const std::vector<Vec2>& v, int i) {
  const int n = static_cast<int>(v.size());
  const Vec2 e0 = v[prev(i, n)] - v[i], e1 = v[next(i, n)] - v[i];
  return std::atan2(std::abs(geometry::cross(e1, e0)), e0.dot(e1));
}
inline int sharpest_vertex(const std::vector<Vec2>& v) {
  int best = 0;
  for (int i = 1; i < static_cast<int>(v.size()); ++i)
    if (interior_angle(v, i) < interior_angle(v, best)) best = i;
  return best;
}

// ---- Reference ----

// How far B must move along unit n to separate from A: the support of A - B along n (<= 0: n separates them).
// Coordinates relative to o keep the digits far from the origin.
template <class V>
inline double overlap_along(std::span<const V> a, std::span<const V> b, const V& n, const V& o) {
  double hi_a = -std::numeric_limits<double>::infinity(), lo_b = std::numeric_limits<double>::infinity();
  for (const V& p : a) hi_a = std::max(hi_a, n.dot(p - o));
  for (const V& q : b) lo_b = std::min(lo_b, n.dot(q - o));
  return hi_a - lo_b;
}

struct Mtd2 {
  double depth;  // <= 0: separated or touching
  Vec2 n;        // from A to B
};
// 2-D separating axes over both polygons' edge normals, both signs: the least overlap and its axis.
inline Mtd2 mtd2(const std::vector<Vec2>& a, const std::vector<Vec2>& b) {
  Mtd2 best{std::numeric_limits<double>::infinity(), Vec2(1.0, 0.0)};
  const Vec2 o = a[0];
  for (const auto* poly : {&a, &b})
    for (int i = 0; i < static_cast<int>(poly->size()); ++i) {
      const Vec2 axis = outward_normal(*poly, i);
      for (const Vec2& n : {axis, Vec2(-axis)}) {
        const double d = overlap_along<Vec2>(a, b, n, o);
        if (d < best.depth) best = {d, n};
      }
    }
  return best;
}

struct Pair {
  std::vector<Vec2> a, b;    // world polygons, counter-clockwise
  std::vector<Vec3> a3, b3;  // world prism vertices: bottom ring, then top ring (ConvexPolyhedron::prism's order)
  std::shared_ptr<const geometry::ConvexPolyhedron> sa, sb;
  Vec3 ca, cb;            // centroids
  bool touching = false;  // zero overlap by construction
  double ref2 = 0.0;      // horizontal MTD [m] (<= 0: no overlap)
  Vec2 n2{1.0, 0.0};
  double ref3 = 0.0;  // 3-D MTD [m]
  Vec3 n3{1.0, 0.0, 0.0};
  bool vertical = false;       // the 3-D MTD is vertical
  bool vertical_tie = false;   // ... and +z, -z tie
  double half_diagonal = 0.0;  // L of the pair's joint 3-D bounding box [m]
  double ref2_computed = 0.0;  // what the brute force says for a touching pair (0 up to round-off)
};

inline std::vector<Vec3> extrude(const std::vector<Vec2>& p, const Slab& z) {
  std::vector<Vec3> v;
  for (const Vec2& q : p) v.emplace_back(q.x(), q.y(), z.lo);
  for (const Vec2& q : p) v.emplace_back(q.x(), q.y(), z.hi);
  return v;
}

inline Pair make_pair(std::vector<Vec2> a, std::vector<Vec2> b, const Slab& za, const Slab& zb, bool touching) {
  Pair p;
  Vec2 oa, ob;
  const auto pa = geometry::ConvexPolygon::from_vertices(a, &oa);  // throws on a bad polygon: a bug here
  const auto pb = geometry::ConvexPolygon::from_vertices(b, &ob);
  p.sa = std::make_shared<const geometry::ConvexPolyhedron>(geometry::ConvexPolyhedron::prism(pa, za.thickness()));
  p.sb = std::make_shared<const geometry::ConvexPolyhedron>(geometry::ConvexPolyhedron::prism(pb, zb.thickness()));
  p.ca = Vec3(oa.x(), oa.y(), 0.5 * (za.lo + za.hi));
  p.cb = Vec3(ob.x(), ob.y(), 0.5 * (zb.lo + zb.hi));
  p.a3 = extrude(a, za);
  p.b3 = extrude(b, zb);
  Vec3 lo = p.a3[0], hi = p.a3[0];
  for (const auto* s : {&p.a3, &p.b3})
    for (const Vec3& x : *s) lo = lo.cwiseMin(x), hi = hi.cwiseMax(x);
  p.half_diagonal = 0.5 * (hi - lo).norm();
  p.a = std::move(a);
  p.b = std::move(b);
  p.touching = touching;

  const Mtd2 m = mtd2(p.a, p.b);
  p.ref2_computed = m.depth;
  p.ref2 = touching ? 0.0 : m.depth;
  p.n2 = m.n;
  const double up = za.hi - zb.lo, down = zb.hi - za.lo;  // B up / down out of A
  const double vert = std::min(up, down);
  if (p.ref2 <= 0.0 || p.ref2 <= vert) {
    p.ref3 = p.ref2;
    p.n3 = Vec3(m.n.x(), m.n.y(), 0.0);
  } else {
    p.ref3 = vert;
    p.vertical = true;
    p.vertical_tie = up == down;
    p.n3 = up <= down ? Vec3::UnitZ() : Vec3(-Vec3::UnitZ());
  }
  return p;
}

// ---- Cases ----

struct Case {
  std::string name, description;
  std::vector<Pair> pairs;
};

// B out of a deep overlap along the exact MTD direction until the MTD is `target` (or the gap is `target` when
// `separated`): every other axis keeps an overlap >= target (it shrinks by at most the shift), so the MTD is
// the target along that direction.
inline bool shifted_pair(std::mt19937_64& rng, double target, bool separated, std::vector<Vec2>& a,
                         std::vector<Vec2>& b) {
  const Vec2 centre(uniform(rng, -50.0, 50.0), uniform(rng, -50.0, 50.0));
  a = moved(random_floe(rng), 0.0, centre);
  b = moved(random_floe(rng), 0.0, centre + Vec2(uniform(rng, -2.0, 2.0), uniform(rng, -2.0, 2.0)));
  const Mtd2 m0 = mtd2(a, b);
  if (!(m0.depth > target)) return false;
  const Vec2 shift = (m0.depth + (separated ? target : -target)) * m0.n;
  for (Vec2& q : b) q += shift;
  return valid(a) && valid(b);
}

inline Case random_case(int n, std::uint64_t seed) {
  Case c{"random", "horizontal MTD 1 mm - 10 cm (log-uniform), near the origin", {}};
  std::mt19937_64 rng(seed);
  std::vector<Vec2> a, b;
  while (static_cast<int>(c.pairs.size()) < n)
    if (shifted_pair(rng, log_uniform(rng, 1e-3, 0.1), false, a, b))
      c.pairs.push_back(make_pair(a, b, floating(1.0), floating(1.0), false));
  return c;
}

inline Case far_case(const Case& random) {
  Case c{"far", "the random set shifted by (1e4, 1e4) m", {}};
  const Vec2 t(1e4, 1e4);
  for (const Pair& p : random.pairs)
    c.pairs.push_back(make_pair(moved(p.a, 0.0, t), moved(p.b, 0.0, t), floating(1.0), floating(1.0), false));
  return c;
}

inline Case separated_case(int n, std::uint64_t seed) {
  Case c{"separated", "gap 1 mm - 10 cm along A - B's exact MTD direction", {}};
  std::mt19937_64 rng(seed);
  std::vector<Vec2> a, b;
  while (static_cast<int>(c.pairs.size()) < n)
    if (shifted_pair(rng, log_uniform(rng, 1e-3, 0.1), true, a, b))
      c.pairs.push_back(make_pair(a, b, floating(1.0), floating(1.0), false));
  return c;
}

inline Case deep_case(int n, std::uint64_t seed) {
  Case c{"deep", "horizontal MTD 1.2 - 3 m with h = 1 m: the 3-D MTD is vertical", {}};
  std::mt19937_64 rng(seed);
  std::vector<Vec2> a, b;
  while (static_cast<int>(c.pairs.size()) < n)
    if (shifted_pair(rng, uniform(rng, 1.2, 3.0), false, a, b))
      c.pairs.push_back(make_pair(a, b, floating(1.0), floating(1.0), false));
  return c;
}

inline Case mixed_case(int n, std::uint64_t seed) {
  Case c{"mixed", "as random, h = 1 m and 3 m each at its floating level", {}};
  std::mt19937_64 rng(seed);
  std::vector<Vec2> a, b;
  while (static_cast<int>(c.pairs.size()) < n)
    if (shifted_pair(rng, log_uniform(rng, 1e-3, 0.1), false, a, b)) {
      const bool a_thin = c.pairs.size() % 2 == 0;
      c.pairs.push_back(make_pair(a, b, floating(a_thin ? 1.0 : 3.0), floating(a_thin ? 3.0 : 1.0), false));
    }
  return c;
}

inline Case parallel_case(int n, std::uint64_t seed) {
  Case c{"parallel", "B's longest edge flush on A's, pushed in 1 mm - 10 cm", {}};
  std::mt19937_64 rng(seed);
  while (static_cast<int>(c.pairs.size()) < n) {
    const auto a = moved(random_floe(rng), 0.0, Vec2(uniform(rng, -50.0, 50.0), uniform(rng, -50.0, 50.0)));
    const int k = longest_edge(a);
    const Vec2 na = outward_normal(a, k);
    const auto b0 = random_floe(rng);
    const int j = longest_edge(b0);
    const auto b1 = moved(b0, angle_of(-na) - angle_of(outward_normal(b0, j)), Vec2::Zero());
    const int nb = static_cast<int>(b1.size());
    const Vec2 mid_b = 0.5 * (b1[j] + b1[next(j, nb)]);
    const Vec2 on_a = a[k] + uniform(rng, 0.25, 0.75) * (a[next(k, static_cast<int>(a.size()))] - a[k]);
    const auto b = moved(b1, 0.0, on_a - mid_b - log_uniform(rng, 1e-3, 0.1) * na);
    if (valid(a) && valid(b)) c.pairs.push_back(make_pair(a, b, floating(1.0), floating(1.0), false));
  }
  return c;
}

// A and B with their sharpest vertices on one point, B's turned so that the two corners' cones are apart (B's
// inward bisector at +-80 % of the largest angle from A's outward bisector that keeps them apart). `push` moves
// B into A along A's inward bisector; 0 leaves the shared vertex bitwise the same in both.
inline bool vertex_pair(std::mt19937_64& rng, double push, std::vector<Vec2>& a, std::vector<Vec2>& b) {
  a = moved(random_floe(rng), 0.0, Vec2(uniform(rng, -50.0, 50.0), uniform(rng, -50.0, 50.0)));
  const int i = sharpest_vertex(a);
  const Vec2 ua = -inward_bisector(a, i);
  const auto b0 = random_floe(rng);
  const int j = sharpest_vertex(b0);
  const double theta_max = std::numbers::pi - 0.5 * (interior_angle(a, i) + interior_angle(b0, j));
  const double theta = uniform(rng, -0.8, 0.8) * theta_max;
  const Vec2 want = geometry::rotate(ua, std::cos(theta), std::sin(theta));
  const auto b1 = moved(b0, angle_of(want) - angle_of(inward_bisector(b0, j)), Vec2::Zero());
  b = moved(b1, 0.0, a[i] - b1[j] - push * ua);
  if (push == 0.0) b[static_cast<std::size_t>(j)] = a[static_cast<std::size_t>(i)];
  return valid(a) && valid(b);
}

inline Case vertex_case(int n, std::uint64_t seed) {
  Case c{"vertex", "B's sharpest vertex pushed 1 mm - 10 cm into A's along A's bisector", {}};
  std::mt19937_64 rng(seed);
  std::vector<Vec2> a, b;
  while (static_cast<int>(c.pairs.size()) < n)
    if (vertex_pair(rng, log_uniform(rng, 1e-3, 0.1), a, b))
      c.pairs.push_back(make_pair(a, b, floating(1.0), floating(1.0), false));
  return c;
}

inline std::vector<Vec2> turned90(const std::vector<Vec2>& v, int quarter_turns) {  // exact in floating point
  std::vector<Vec2> out = v;
  for (int q = 0; q < quarter_turns; ++q)
    for (Vec2& p : out) p = Vec2(-p.y(), p.x());
  return out;
}

// Kind 0: B's longest edge on A's longest edge (partly); kind 1: a vertex of B on A's longest edge; both with the
// contact line at one y value (snapped), A below and B above it. Kind 2: vertex on vertex (vertex_pair, no push).
inline bool touching_pair(std::mt19937_64& rng, int kind, std::vector<Vec2>& a, std::vector<Vec2>& b) {
  if (kind == 2) return vertex_pair(rng, 0.0, a, b);
  const auto a0 = random_floe(rng);
  const int k = longest_edge(a0), na = static_cast<int>(a0.size());
  // A's edge k along -x (a top edge: outward normal +y), then snapped level.
  a = moved(a0, std::numbers::pi - angle_of(a0[next(k, na)] - a0[k]),
            Vec2(uniform(rng, -50.0, 50.0), uniform(rng, -50.0, 50.0)));
  a[static_cast<std::size_t>(next(k, na))].y() = a[static_cast<std::size_t>(k)].y();
  const double y0 = a[static_cast<std::size_t>(k)].y();
  const double x_lo = a[static_cast<std::size_t>(next(k, na))].x(), x_hi = a[static_cast<std::size_t>(k)].x();
  const auto b0 = random_floe(rng);
  const int nb = static_cast<int>(b0.size());
  if (kind == 0) {
    const int j = longest_edge(b0);  // along +x: a bottom edge
    b = moved(b0, -angle_of(b0[next(j, nb)] - b0[j]), Vec2::Zero());
    const double len = b[static_cast<std::size_t>(next(j, nb))].x() - b[static_cast<std::size_t>(j)].x();
    const double x0 = x_lo - len + uniform(rng, 0.1, 0.9) * (x_hi - x_lo + len);
    b = moved(b, 0.0, Vec2(x0, y0) - b[static_cast<std::size_t>(j)]);
    b[static_cast<std::size_t>(j)].y() = y0;
    b[static_cast<std::size_t>(next(j, nb))].y() = y0;
  } else {
    const int j = static_cast<int>(uniform(rng, 0.0, nb - 1e-9));  // inward bisector along +y: the lowest vertex
    b = moved(b0, 0.5 * std::numbers::pi - angle_of(inward_bisector(b0, j)), Vec2::Zero());
    const Vec2 at(x_lo + uniform(rng, 0.1, 0.9) * (x_hi - x_lo), y0);
    b = moved(b, 0.0, at - b[static_cast<std::size_t>(j)]);
    b[static_cast<std::size_t>(j)] = at;
    for (int m = 0; m < nb; ++m)
      if (m != j && !(b[static_cast<std::size_t>(m)].y() > y0 + 1e-6)) return false;
  }
  return valid(a) && valid(b);
}

inline Case touching_case(int n, std::uint64_t seed) {
  Case c{"touching",
         "exact zero overlap: edge on edge, vertex on edge (contact line snapped level, turned by k x 90 deg), "
         "vertex on vertex",
         {}};
  std::mt19937_64 rng(seed);
  std::vector<Vec2> a, b;
  while (static_cast<int>(c.pairs.size()) < n) {
    const int index = static_cast<int>(c.pairs.size());
    const int kind = index % 3, turns = (index / 3) % 4;
    if (touching_pair(rng, kind, a, b))
      c.pairs.push_back(make_pair(turned90(a, turns), turned90(b, turns), floating(1.0), floating(1.0), true));
  }
  return c;
}

}  // namespace failure_map
