// The failure map of the contact methods (docs/validation.md, "Failure map of the contact methods"): every narrow
// phase the code has, on random and on degenerate pairs of level floes, against the exact minimum translation
// distance (MTD). A benchmark driver, not Google Benchmark: it prints a table and writes JSON.
//
//   build-h3/tests/bench_failure_map [-o FILE.json] [--quick] [--random N] [--degenerate N] [--seed S]
//   (default FILE: failure_map.json; from the repository root: -o docs/data/failure_map.json;
//    --quick: 2,000 random pairs, 200 per degenerate set, 3 timed passes instead of 20,000, 1,000 and 11;
//    --random, --degenerate: other pair counts; --seed: added to every set's seed, for other draws of the sets)
//
// Methods (their headers are the only APIs used):
//   planar      contact::planar_overlap (exact overlap polygon; depth = area / chord and the chord normal by design,
//               so its deviations from the MTD are a definition, not a failure: listed all the same)
//   gjk2d       contact::gjk_epa_2d (own 2-D GJK-EPA on the polygons)
//   ccd_epa     contact::ccd_penetration, CcdMethod::gjk_epa (libccd GJK-EPA, its own support ties)
//   ccd_tie     CcdMethod::gjk_epa_tiebreak (libccd GJK-EPA, support ties broken)
//   ccd_mpr     CcdMethod::mpr (libccd MPR)
//   sat         contact::sat_penetration (exact 3-D separating axes)
// The planar methods get the polygons; the 3-D ones the prisms (the polygon extruded over the floe's z-range;
// shape: geometry::ConvexPolyhedron::prism, world vertices: the polygon's world vertices at the bottom and top
// levels, in the prism's order, rotation identity).
//
// Reference, per pair (brute force, independent of the code under test): the horizontal MTD is the 2-D separating-
// axis minimum over both polygons' edge normals (both signs) of the overlap along the axis, max_A n.x - min_B n.x.
// Two level prisms' Minkowski difference is a prism too (the polygons' difference times the z-ranges' difference),
// whose face normals are those edge normals and +-z, so the 3-D MTD is that horizontal one unless the vertical
// overlap of the z-ranges, min(topA - botB, topB - botA), is smaller, in which case it is vertical (the "deep"
// set; with equal z-ranges +z and -z tie and both count as right). The planar methods are compared with the
// horizontal MTD, the 3-D methods with the 3-D one.
//
// Cases (fixed seeds; polygons: 5-20 points at random angles on ellipses of width 5-100 m, log-uniform, and
// aspect 0.3-1, random yaw, counter-clockwise, validated with geometry::convexity_error; thickness h = 1 m at the
// floating level z in [-0.8976 h, 0.1024 h] (rho 920 / 1025), the same for both floes unless stated):
//   random     B moved out of a deep overlap along A - B's exact MTD direction until the MTD is 1 mm - 10 cm
//              (log-uniform), near the origin;
//   far        the random set shifted by (1e4, 1e4) m;
//   touching   exact zero overlap: an edge of B on an edge of A (partly), a vertex of B on an edge of A (both with
//              the contact line snapped to one y value, then the pair turned by 0, 90, 180, 270 degrees: exact in
//              floating point), a vertex of B on a vertex of A (the same double coordinates, cones apart);
//   separated  as random, but B moved on until the gap along that direction is 1 mm - 10 cm;
//   vertex     the sharpest vertex of B pushed 1 mm - 10 cm into the sharpest vertex of A along A's bisector;
//   parallel   B's longest edge flush against A's (antiparallel normals, B's midpoint on A's edge between 25 and
//              75 %), then pushed in 1 mm - 10 cm;
//   deep       as random with a horizontal MTD of 1.2-3 m (uniform): deeper than the thickness, so the true 3-D MTD
//              is vertical (1 m), which is physically wrong for floes; the column "vert" counts vertical answers;
//   mixed      as random with h = 1 m and 3 m, each at its floating level (A thin on even pairs, thick on odd).
//
// Counts per method and case: failed (status failed), missed (no contact where the reference overlaps), false
// (a contact on a touching or separated pair), nonfinite (any non-finite number in a contact, or a failure
// without a reason: must be 0), malformed (a contact with depth <= 0 or a normal off unit length by > 1e-9),
// wrong normal (> 1 degree from the reference direction; "ties": of those, the ones whose own direction needs no
// longer a translation than the MTD + 1e-6 L, L the pair's half-diagonal), vert (normals within 1 degree of
// vertical; "horizontal" in the JSON: within 1 degree of horizontal), the relative depth error |depth - ref| / ref
// over contacts on overlapping pairs (median, 90th percentile, max), ns per pair (std::chrono::steady_clock, single
// thread, median of the timed passes over the case's pairs, each result folded into a sum that is written to a
// volatile) and the slowest single query [us] (each query timed alone 3 times, per pair the least: a preempted
// query does not count, a near-hang would).
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <limits>
#include <map>
#include <memory>
#include <numbers>
#include <random>
#include <span>
#include <string>
#include <vector>

#include "contact/narrow_phase_ccd.h"
#include "contact/narrow_phase_gjk2d.h"
#include "contact/narrow_phase_planar.h"
#include "contact/narrow_phase_sat3d.h"
#include "geometry/polygon.h"
#include "contact_methods.h"
#include "geometry/polyhedron.h"
#include "test_support.h"

using namespace polyfloe;
using geometry::Vec2;
using geometry::Vec3;
using Mat3 = geometry::Mat3;
using Clock = std::chrono::steady_clock;

namespace {

volatile double g_sink = 0.0;  // every timed result ends up here

constexpr double kRhoIce = 920.0, kRhoWater = 1025.0;  // [kg/m^3], the scenes' defaults
constexpr double kTieTol = 1e-6;                        // ties of the normal: 1e-6 x the pair's half-diagonal
const double kCos1deg = std::cos(std::numbers::pi / 180.0);

struct Slab {
  double lo, hi;  // z-range [m]
  double thickness() const { return hi - lo; }
};
Slab floating(double h) {
  const double d = geometry::floating_draft(h, kRhoIce, kRhoWater);
  return {-d, h - d};
}

double uniform(std::mt19937_64& rng, double lo, double hi) {
  return lo + (hi - lo) * std::uniform_real_distribution<double>(0.0, 1.0)(rng);
}
double log_uniform(std::mt19937_64& rng, double lo, double hi) { return lo * std::pow(hi / lo, uniform(rng, 0, 1)); }

double angle_of(const Vec2& v) { return std::atan2(v.y(), v.x()); }

std::vector<Vec2> moved(const std::vector<Vec2>& v, double yaw, const Vec2& t) {
  return tsupport::transform(v, yaw, t);
}

bool valid(const std::vector<Vec2>& v) { return geometry::convexity_error(v).empty(); }

// 5-20 points at random angles on an ellipse of width 5-100 m (log-uniform), aspect 0.3-1, random yaw, centred
// near the origin, counter-clockwise.
std::vector<Vec2> random_floe(std::mt19937_64& rng) {
  const int n = 5 + static_cast<int>(uniform(rng, 0.0, 16.0));
  const double rx = 0.5 * log_uniform(rng, 5.0, 100.0), ry = rx * uniform(rng, 0.3, 1.0);
  for (;;) {
    auto v = moved(tsupport::random_convex(rng, std::min(n, 20), rx, ry), uniform(rng, 0.0, 2.0 * std::numbers::pi),
                   Vec2::Zero());
    if (valid(v)) return v;
  }
}

int next(int i, int n) { return i + 1 == n ? 0 : i + 1; }
int prev(int i, int n) { return i == 0 ? n - 1 : i - 1; }
Vec2 outward_normal(const std::vector<Vec2>& v, int i) {  // of edge i -> i + 1
  return geometry::perp_right(v[next(i, static_cast<int>(v.size()))] - v[i]).normalized();
}
int longest_edge(const std::vector<Vec2>& v) {
  const int n = static_cast<int>(v.size());
  int best = 0;
  for (int i = 1; i < n; ++i)
    if ((v[next(i, n)] - v[i]).norm() > (v[next(best, n)] - v[best]).norm()) best = i;
  return best;
}
Vec2 inward_bisector(const std::vector<Vec2>& v, int i) {
  const int n = static_cast<int>(v.size());
  return ((v[prev(i, n)] - v[i]).normalized() + (v[next(i, n)] - v[i]).normalized()).normalized();
}
double interior_angle(const std::vector<Vec2>& v, int i) {
  const int n = static_cast<int>(v.size());
  const Vec2 e0 = v[prev(i, n)] - v[i], e1 = v[next(i, n)] - v[i];
  return std::atan2(std::abs(geometry::cross(e1, e0)), e0.dot(e1));
}
int sharpest_vertex(const std::vector<Vec2>& v) {
  int best = 0;
  for (int i = 1; i < static_cast<int>(v.size()); ++i)
    if (interior_angle(v, i) < interior_angle(v, best)) best = i;
  return best;
}

// ---- Reference ----

// How far B must move along unit n to separate from A: the support of A - B along n (<= 0: n separates them).
// Coordinates relative to o keep the digits far from the origin.
template <class V>
double overlap_along(std::span<const V> a, std::span<const V> b, const V& n, const V& o) {
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
Mtd2 mtd2(const std::vector<Vec2>& a, const std::vector<Vec2>& b) {
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
  Vec3 ca, cb;               // centroids
  bool touching = false;     // zero overlap by construction
  double ref2 = 0.0;         // horizontal MTD [m] (<= 0: no overlap)
  Vec2 n2{1.0, 0.0};
  double ref3 = 0.0;         // 3-D MTD [m]
  Vec3 n3{1.0, 0.0, 0.0};
  bool vertical = false;     // the 3-D MTD is vertical
  bool vertical_tie = false; // ... and +z, -z tie
  double half_diagonal = 0.0;  // L of the pair's joint 3-D bounding box [m]
  double ref2_computed = 0.0;  // what the brute force says for a touching pair (0 up to round-off)
};

std::vector<Vec3> extrude(const std::vector<Vec2>& p, const Slab& z) {
  std::vector<Vec3> v;
  for (const Vec2& q : p) v.emplace_back(q.x(), q.y(), z.lo);
  for (const Vec2& q : p) v.emplace_back(q.x(), q.y(), z.hi);
  return v;
}

Pair make_pair(std::vector<Vec2> a, std::vector<Vec2> b, const Slab& za, const Slab& zb, bool touching) {
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
bool shifted_pair(std::mt19937_64& rng, double target, bool separated, std::vector<Vec2>& a, std::vector<Vec2>& b) {
  const Vec2 centre(uniform(rng, -50.0, 50.0), uniform(rng, -50.0, 50.0));
  a = moved(random_floe(rng), 0.0, centre);
  b = moved(random_floe(rng), 0.0, centre + Vec2(uniform(rng, -2.0, 2.0), uniform(rng, -2.0, 2.0)));
  const Mtd2 m0 = mtd2(a, b);
  if (!(m0.depth > target)) return false;
  const Vec2 shift = (m0.depth + (separated ? target : -target)) * m0.n;
  for (Vec2& q : b) q += shift;
  return valid(a) && valid(b);
}

Case random_case(int n, std::uint64_t seed) {
  Case c{"random", "horizontal MTD 1 mm - 10 cm (log-uniform), near the origin", {}};
  std::mt19937_64 rng(seed);
  std::vector<Vec2> a, b;
  while (static_cast<int>(c.pairs.size()) < n)
    if (shifted_pair(rng, log_uniform(rng, 1e-3, 0.1), false, a, b))
      c.pairs.push_back(make_pair(a, b, floating(1.0), floating(1.0), false));
  return c;
}

Case far_case(const Case& random) {
  Case c{"far", "the random set shifted by (1e4, 1e4) m", {}};
  const Vec2 t(1e4, 1e4);
  for (const Pair& p : random.pairs)
    c.pairs.push_back(make_pair(moved(p.a, 0.0, t), moved(p.b, 0.0, t), floating(1.0), floating(1.0), false));
  return c;
}

Case separated_case(int n, std::uint64_t seed) {
  Case c{"separated", "gap 1 mm - 10 cm along A - B's exact MTD direction", {}};
  std::mt19937_64 rng(seed);
  std::vector<Vec2> a, b;
  while (static_cast<int>(c.pairs.size()) < n)
    if (shifted_pair(rng, log_uniform(rng, 1e-3, 0.1), true, a, b))
      c.pairs.push_back(make_pair(a, b, floating(1.0), floating(1.0), false));
  return c;
}

Case deep_case(int n, std::uint64_t seed) {
  Case c{"deep", "horizontal MTD 1.2 - 3 m with h = 1 m: the 3-D MTD is vertical", {}};
  std::mt19937_64 rng(seed);
  std::vector<Vec2> a, b;
  while (static_cast<int>(c.pairs.size()) < n)
    if (shifted_pair(rng, uniform(rng, 1.2, 3.0), false, a, b))
      c.pairs.push_back(make_pair(a, b, floating(1.0), floating(1.0), false));
  return c;
}

Case mixed_case(int n, std::uint64_t seed) {
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

Case parallel_case(int n, std::uint64_t seed) {
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
bool vertex_pair(std::mt19937_64& rng, double push, std::vector<Vec2>& a, std::vector<Vec2>& b) {
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

Case vertex_case(int n, std::uint64_t seed) {
  Case c{"vertex", "B's sharpest vertex pushed 1 mm - 10 cm into A's along A's bisector", {}};
  std::mt19937_64 rng(seed);
  std::vector<Vec2> a, b;
  while (static_cast<int>(c.pairs.size()) < n)
    if (vertex_pair(rng, log_uniform(rng, 1e-3, 0.1), a, b))
      c.pairs.push_back(make_pair(a, b, floating(1.0), floating(1.0), false));
  return c;
}

std::vector<Vec2> turned90(const std::vector<Vec2>& v, int quarter_turns) {  // exact in floating point
  std::vector<Vec2> out = v;
  for (int q = 0; q < quarter_turns; ++q)
    for (Vec2& p : out) p = Vec2(-p.y(), p.x());
  return out;
}

// Kind 0: B's longest edge on A's longest edge (partly); kind 1: a vertex of B on A's longest edge; both with the
// contact line at one y value (snapped), A below and B above it. Kind 2: vertex on vertex (vertex_pair, no push).
bool touching_pair(std::mt19937_64& rng, int kind, std::vector<Vec2>& a, std::vector<Vec2>& b) {
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

Case touching_case(int n, std::uint64_t seed) {
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

// ---- Methods ----

using tsupport::kCcdEpa;
using tsupport::kCcdMpr;
using tsupport::kCcdTie;
using tsupport::kGjk2d;
using tsupport::kPlanar;
using tsupport::kSat;
constexpr int kMethods = tsupport::kContactMethods;
const char* kMethodName[kMethods] = {"planar", "gjk2d", "ccd_epa", "ccd_tie", "ccd_mpr", "sat"};
const char* kMethodLabel[kMethods] = {"exact planar (area/chord)", "own 2-D GJK-EPA", "libccd GJK-EPA",
                                      "libccd GJK-EPA tie-break", "libccd MPR", "exact 3-D SAT"};
bool is_planar(int m) { return tsupport::is_planar_method(m); }

using Status = tsupport::MethodStatus;
using Result = tsupport::MethodResult;

Result run(int m, const Pair& p) {
  return tsupport::run_contact_method(m, {p.a, p.b, p.a3, p.b3, p.sa.get(), p.sb.get(), p.ca, p.cb});
}

// One timed pass over the pairs [ns per pair]; the results are summed into g_sink.
template <class F>
double timed(const std::vector<Pair>& pairs, F&& f) {
  double acc = 0.0;
  const auto t0 = Clock::now();
  for (const Pair& p : pairs) acc += f(p);
  const auto t1 = Clock::now();
  g_sink = g_sink + acc;
  return std::chrono::duration<double, std::nano>(t1 - t0).count() / static_cast<double>(pairs.size());
}

double timed_pass(int m, const std::vector<Pair>& pairs) {
  return timed(pairs, [m](const Pair& p) {
    const Result r = run(m, p);
    return r.depth + static_cast<double>(r.status);
  });
}

// ---- Statistics ----

struct Stats {
  int pairs = 0, overlapping = 0, contacts = 0;
  int failed = 0, missed = 0, false_contact = 0, nonfinite = 0, malformed = 0;
  int wrong_normal = 0, wrong_normal_ties = 0, vertical = 0, horizontal = 0;
  std::vector<double> depth_error;  // relative, contacts on overlapping pairs
  std::vector<double> ns_passes;
  double max_us = 0.0;              // slowest single query (per pair the least of 3 timings) [us]
  int slowest = -1;                 // its pair
  double false_depth_max = 0.0;     // deepest false contact [m]
  std::map<std::string, int> reasons;
  // The first pair of each kind of bug, for the report.
  int first_nonfinite = -1, first_missed = -1, first_false = -1;
};

using tsupport::percentile;

void classify(int m, const Pair& p, int index, const Result& r, Stats& s) {
  const bool planar = is_planar(m);
  const double ref = planar ? p.ref2 : p.ref3;
  const bool overlaps = !p.touching && ref > 0.0;
  ++s.pairs;
  s.overlapping += overlaps;
  if (r.status == Status::failed) {
    ++s.failed;
    ++s.reasons[r.reason ? r.reason : ""];
    if (!r.reason || !*r.reason) {
      ++s.nonfinite;  // a failure must say why
      if (s.first_nonfinite < 0) s.first_nonfinite = index;
    }
    return;
  }
  if (r.status == Status::separated) {
    if (overlaps) {
      ++s.missed;
      if (s.first_missed < 0) s.first_missed = index;
    }
    return;
  }
  ++s.contacts;
  if (!std::isfinite(r.depth) || !r.normal.allFinite() || !r.point.allFinite()) {
    ++s.nonfinite;
    if (s.first_nonfinite < 0) s.first_nonfinite = index;
    return;
  }
  if (!(r.depth > 0.0) || !(std::abs(r.normal.norm() - 1.0) <= 1e-9)) ++s.malformed;
  if (!overlaps) {
    ++s.false_contact;
    s.false_depth_max = std::max(s.false_depth_max, r.depth);
    if (s.first_false < 0) s.first_false = index;
    return;
  }
  if (std::abs(r.normal.z()) > kCos1deg) ++s.vertical;
  if (std::abs(r.normal.z()) < std::sin(std::numbers::pi / 180.0)) ++s.horizontal;
  const Vec3 ref_n = planar ? Vec3(p.n2.x(), p.n2.y(), 0.0) : p.n3;
  const double c = r.normal.normalized().dot(ref_n);
  const bool right = c >= kCos1deg || (p.vertical_tie && !planar && -c >= kCos1deg);
  if (!right) {
    ++s.wrong_normal;
    const Vec3 n = r.normal.normalized();
    const double along = planar ? overlap_along<Vec2>(p.a, p.b, Vec2(n.x(), n.y()), p.a[0])
                                : overlap_along<Vec3>(p.a3, p.b3, n, p.a3[0]);
    if (along <= ref + kTieTol * p.half_diagonal) ++s.wrong_normal_ties;
  }
  s.depth_error.push_back(std::abs(r.depth - ref) / ref);
}

std::string json_string(const std::string& s) {
  std::string o = "\"";
  for (char ch : s) {
    if (ch == '"' || ch == '\\') o += '\\';
    o += ch;
  }
  return o + "\"";
}

std::string num(double v) {
  if (!std::isfinite(v)) return "null";
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.6g", v);
  return buf;
}

void print_polygon(const char* name, const std::vector<Vec2>& v) {
  std::printf("    %s = {", name);
  for (std::size_t i = 0; i < v.size(); ++i) std::printf("%s{%.17g, %.17g}", i ? ", " : "", v[i].x(), v[i].y());
  std::printf("}\n");
}

}  // namespace

int main(int argc, char** argv) {
  std::string out_file = "failure_map.json";
  bool quick = false;
  int n_random = -1, n_degenerate = -1;
  std::uint64_t seed = 0;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    auto count = [&](int& n) {
      n = std::atoi(argv[++i]);
      return n > 0;
    };
    if (arg == "-o" && i + 1 < argc) {
      out_file = argv[++i];
    } else if (arg == "--quick") {
      quick = true;
    } else if (arg == "--random" && i + 1 < argc && count(n_random)) {
    } else if (arg == "--degenerate" && i + 1 < argc && count(n_degenerate)) {
    } else if (arg == "--seed" && i + 1 < argc) {
      seed = std::strtoull(argv[++i], nullptr, 10);
    } else {
      std::fprintf(stderr, "usage: %s [-o FILE.json] [--quick] [--random N] [--degenerate N] [--seed S]\n",
                   argv[0]);
      return 2;
    }
  }
  const auto t_start = Clock::now();
  if (n_random < 0) n_random = quick ? 2000 : 20000;
  if (n_degenerate < 0) n_degenerate = quick ? 200 : 1000;
  const int passes = quick ? 3 : 11;

  std::vector<Case> cases;
  cases.push_back(random_case(n_random, 20261201u + seed));
  cases.push_back(far_case(cases.front()));
  cases.push_back(touching_case(n_degenerate, 20261202u + seed));
  cases.push_back(separated_case(n_degenerate, 20261203u + seed));
  cases.push_back(vertex_case(n_degenerate, 20261204u + seed));
  cases.push_back(parallel_case(n_degenerate, 20261205u + seed));
  cases.push_back(deep_case(n_degenerate, 20261206u + seed));
  cases.push_back(mixed_case(n_degenerate, 20261207u + seed));
  const double gen_s = std::chrono::duration<double>(Clock::now() - t_start).count();
  std::printf("Failure map of the contact methods: %d random pairs, %d per degenerate set, %d timed passes "
              "(pairs generated in %.1f s)\n",
              n_random, n_degenerate, passes, gen_s);
  std::printf("Floes at the floating level: z in [%.4f h, %.4f h] (rho_ice / rho_water = %.0f / %.0f)\n\n",
              floating(1.0).lo, floating(1.0).hi, kRhoIce, kRhoWater);

  std::string json = "{\n  \"settings\": {\"random_pairs\": " + std::to_string(n_random) +
                     ", \"degenerate_pairs\": " + std::to_string(n_degenerate) +
                     ", \"timed_passes\": " + std::to_string(passes) + ", \"seed_offset\": " + std::to_string(seed) +
                     ", \"draft_fraction\": " +
                     num(-floating(1.0).lo) + ", \"wrong_normal_degrees\": 1, \"tie_tolerance\": " + num(kTieTol) +
                     "},\n  \"methods\": [";
  for (int m = 0; m < kMethods; ++m)
    json += std::string(m ? ", " : "") + "{\"name\": " + json_string(kMethodName[m]) +
            ", \"label\": " + json_string(kMethodLabel[m]) + ", \"planar\": " + (is_planar(m) ? "true" : "false") +
            "}";
  json += "],\n  \"cases\": [";
  bool first_case = true;
  std::string json_results;
  bool first_result = true;
  int bugs = 0;

  for (const Case& c : cases) {
    // Reference summary.
    double ref_lo = std::numeric_limits<double>::infinity(), ref_hi = -ref_lo, touch_residual = 0.0;
    int vertical = 0, overlapping = 0;
    for (const Pair& p : c.pairs) {
      if (p.touching) {
        touch_residual = std::max(touch_residual, std::abs(p.ref2_computed) / p.half_diagonal);
        continue;
      }
      if (p.ref2 > 0.0) ++overlapping;
      ref_lo = std::min(ref_lo, p.ref2);
      ref_hi = std::max(ref_hi, p.ref2);
      vertical += p.vertical;
    }
    std::printf("case %-9s %d pairs (%d overlapping): %s\n", c.name.c_str(), static_cast<int>(c.pairs.size()),
                overlapping, c.description.c_str());
    if (!c.pairs.front().touching)
      std::printf("  reference horizontal MTD %.4g .. %.4g m; 3-D MTD vertical in %d pairs\n", ref_lo, ref_hi,
                  vertical);
    else
      std::printf("  brute-force MTD of the touching pairs: |MTD| / L <= %.2g (zero by construction)\n",
                  touch_residual);
    json += std::string(first_case ? "\n" : ",\n") + "    {\"name\": " + json_string(c.name) +
            ", \"description\": " + json_string(c.description) +
            ", \"pairs\": " + std::to_string(c.pairs.size()) + ", \"overlapping\": " + std::to_string(overlapping) +
            ", \"ref_mtd_min\": " + num(c.pairs.front().touching ? 0.0 : ref_lo) +
            ", \"ref_mtd_max\": " + num(c.pairs.front().touching ? 0.0 : ref_hi) +
            ", \"ref_vertical\": " + std::to_string(vertical) + ", \"touch_residual\": " + num(touch_residual) + "}";
    first_case = false;

    std::printf("  %-9s %7s %7s %7s %7s %7s %7s %7s %7s %10s %10s %10s %9s %8s\n", "method", "contact", "failed",
                "missed", "false", "nonfin", "wrongN", "(ties)", "vert", "dErr p50", "dErr p90", "dErr max",
                "ns/pair", "max us");
    Stats stats[kMethods];
    for (int m = 0; m < kMethods; ++m) {
      // Each query timed on its own 3 times (the first also classified); per pair the least of the 3, so that a
      // preempted query does not count but a really slow one (a near-hang) does.
      std::vector<double> us(c.pairs.size(), std::numeric_limits<double>::infinity());
      for (int rep = 0; rep < 3; ++rep)
        for (std::size_t k = 0; k < c.pairs.size(); ++k) {
          const auto t0 = Clock::now();
          const Result r = run(m, c.pairs[k]);
          us[k] = std::min(us[k], std::chrono::duration<double, std::micro>(Clock::now() - t0).count());
          if (rep == 0) classify(m, c.pairs[k], static_cast<int>(k), r, stats[m]);
          g_sink = g_sink + r.depth;
        }
      const auto worst = std::max_element(us.begin(), us.end());
      stats[m].max_us = *worst;
      stats[m].slowest = static_cast<int>(worst - us.begin());
    }
    for (int pass = 0; pass < passes; ++pass)
      for (int m = 0; m < kMethods; ++m) stats[m].ns_passes.push_back(timed_pass(m, c.pairs));

    for (int m = 0; m < kMethods; ++m) {
      const Stats& s = stats[m];
      const double p50 = percentile(s.depth_error, 0.5), p90 = percentile(s.depth_error, 0.9),
                   mx = s.depth_error.empty() ? std::nan("")
                                              : *std::max_element(s.depth_error.begin(), s.depth_error.end());
      const double ns = percentile(s.ns_passes, 0.5);
      std::printf("  %-9s %7d %7d %7d %7d %7d %7d %7d %7d %10.2e %10.2e %10.2e %9.0f %8.1f\n", kMethodName[m],
                  s.contacts, s.failed, s.missed, s.false_contact, s.nonfinite, s.wrong_normal, s.wrong_normal_ties,
                  s.vertical, p50, p90, mx, ns, s.max_us);
      for (const auto& [reason, count] : s.reasons) std::printf("      failed %5d x \"%s\"\n", count, reason.c_str());
      // Bugs: anything non-finite, a contact that is not well formed, a miss or a false contact (a libccd
      // "separated" or "contact" is trusted by its callers: only "failed" falls back to the exact method).
      auto report = [&](const char* what, int index) {
        if (index < 0) return;
        ++bugs;
        const Pair& p = c.pairs[static_cast<std::size_t>(index)];
        const Result r = run(m, p);
        std::printf("    BUG %s: %s, pair %d (reference MTD %.17g): status %d, depth %.17g, normal (%.17g, %.17g, "
                    "%.17g)\n",
                    kMethodName[m], what, index, is_planar(m) ? p.ref2 : p.ref3, static_cast<int>(r.status), r.depth,
                    r.normal.x(), r.normal.y(), r.normal.z());
        print_polygon("A", p.a);
        print_polygon("B", p.b);
      };
      report("non-finite output", s.first_nonfinite);
      report("missed an overlap", s.first_missed);
      report("contact on a touching/separated pair", s.first_false);
      if (s.malformed) {
        ++bugs;
        std::printf("    BUG %s: %d malformed contacts\n", kMethodName[m], s.malformed);
      }

      std::string reasons = "{";
      bool first_reason = true;
      for (const auto& [reason, count] : s.reasons) {
        reasons += std::string(first_reason ? "" : ", ") + json_string(reason) + ": " + std::to_string(count);
        first_reason = false;
      }
      reasons += "}";
      std::string passes_json = "[";
      for (std::size_t k = 0; k < s.ns_passes.size(); ++k) passes_json += (k ? ", " : "") + num(s.ns_passes[k]);
      passes_json += "]";
      json_results += std::string(first_result ? "\n" : ",\n") + "    {\"case\": " + json_string(c.name) +
                      ", \"method\": " + json_string(kMethodName[m]) + ", \"pairs\": " + std::to_string(s.pairs) +
                      ", \"overlapping\": " + std::to_string(s.overlapping) +
                      ", \"contacts\": " + std::to_string(s.contacts) + ", \"failed\": " + std::to_string(s.failed) +
                      ", \"missed\": " + std::to_string(s.missed) +
                      ", \"false_contact\": " + std::to_string(s.false_contact) +
                      ", \"false_depth_max\": " + num(s.false_depth_max) +
                      ", \"nonfinite\": " + std::to_string(s.nonfinite) +
                      ", \"malformed\": " + std::to_string(s.malformed) +
                      ", \"wrong_normal\": " + std::to_string(s.wrong_normal) +
                      ", \"wrong_normal_ties\": " + std::to_string(s.wrong_normal_ties) +
                      ", \"vertical\": " + std::to_string(s.vertical) +
                      ", \"horizontal\": " + std::to_string(s.horizontal) + ",\n     \"depth_error_median\": " +
                      num(p50) + ", \"depth_error_p90\": " + num(p90) + ", \"depth_error_max\": " + num(mx) +
                      ", \"ns_per_pair\": " + num(ns) + ", \"ns_passes\": " + passes_json +
                      ", \"max_us_one_pair\": " + num(s.max_us) + ", \"slowest_pair\": " + std::to_string(s.slowest) + ",\n     \"failure_reasons\": " + reasons + "}";
      first_result = false;
    }
    std::printf("\n");
  }
  json += "\n  ],\n  \"results\": [" + json_results + "\n  ]\n}\n";
  std::ofstream(out_file) << json;
  const double secs = std::chrono::duration<double>(Clock::now() - t_start).count();
  std::printf("%d bug(s) found (non-finite, malformed, a missed or a false contact)\n", bugs);
  std::printf("wrote %s (%.0f s)\n", out_file.c_str(), secs);
  return 0;
}
