// Cost of the planar narrow phase, contact::planar_overlap: the whole test (does it overlap), the overlap polygon,
// its area and centroid, the chord normal, the depth (and whatever else planar_overlap fills in, such as the
// depth-gradient terms), per candidate pair, on one core.
//
//   BM_PlanarOverlap/<n>    overlapping pairs of n-vertex random convex polygons: sizes log-uniform in 5-100 m
//                           (each floe drawn independently), overlap (penetration along the approach direction)
//                           log-uniform from 1 mm to 10 % of the smaller size, random orientations, and placed up
//                           to 5 km from the origin as in a real domain.
//   BM_PlanarSeparated/<n>  candidate pairs the broad phase would pass on (bounding boxes overlap) whose polygons are
//                           separated by a gap log-uniform from 1 mm to 10 % of the smaller size: the rejection cost.
//   BM_PlanarOverlapKept/<n> the overlapping pairs again, each with the topology planar_overlap returned one time
//                           step earlier (B 1 mm back along a random direction and turned by 1e-4 rad about its
//                           centre): what a persisting contact costs in the World, which keeps the topology per pair.
//                           Counter kept_fraction: the pairs whose kept topology passed its check (the rest were
//                           clipped anew, included in the time).
//
//   BM_Method/<m>/12        the same overlapping 12-vertex pairs through every contact method, as level prisms
//                           (h = 1 m, z in [-0.5, 0.5]) for the 3-D ones: m = 0 exact planar, 1 own 2-D GJK-EPA,
//                           2 exact 3-D separating axes (sat), 3 libccd GJK-EPA, 4 libccd GJK-EPA with support
//                           ties broken, 5 libccd MPR (through the adapter, whose checks are part of the cost).
//
// The pairs are generated before timing (kPairs of them, stored contiguously) and cycled through, one pair per
// benchmark iteration, so "Time" (wall) and "CPU" are per pair; the counter ns_per_pair is the CPU ns per pair. Every
// "overlapping" pair is checked to overlap, and every "separated" pair to be rejected, before the timed loop.
#include <benchmark/benchmark.h>

#include <time.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <map>
#include <numbers>
#include <random>
#include <span>
#include <string>
#include <vector>

#include "contact/narrow_phase_ccd.h"
#include "contact/narrow_phase_gjk2d.h"
#include "contact/narrow_phase_planar.h"
#include "contact/narrow_phase_sat3d.h"
#include "geometry/polyhedron.h"
#include "test_support.h"
#include "thread_clock.h"

using namespace polyfloe;
using geometry::Vec2;

namespace {

using tsupport::thread_cpu_seconds;

constexpr int kPairs = 4096;  // a power of two: the pair index is cycled with a mask

struct PairSet {
  std::vector<Vec2> xy;     // all vertices, pair after pair: A's then B's
  std::vector<int> offset;  // 2 * kPairs + 1 offsets into xy
  std::span<const Vec2> poly(int k) const {
    return {xy.data() + offset[k], static_cast<std::size_t>(offset[k + 1] - offset[k])};
  }
};

double log_uniform(std::mt19937_64& rng, double lo, double hi) {
  std::uniform_real_distribution<double> u(0.0, 1.0);
  return lo * std::pow(hi / lo, u(rng));
}

// A random convex polygon of `n` vertices with diameter about `size` [m], centroid at the origin, random yaw.
std::vector<Vec2> random_floe(std::mt19937_64& rng, int n, double size) {
  std::uniform_real_distribution<double> u(0.0, 1.0);
  const double rx = 0.5 * size, ry = rx * (0.6 + 0.4 * u(rng));
  const auto shape = tsupport::shape_of(tsupport::random_convex(rng, n, rx, ry));
  return tsupport::transform(shape->vertices(), 2.0 * std::numbers::pi * u(rng), Vec2{0.0, 0.0});
}

// Largest t such that A and B + t u still share a point: the ray t u leaving the Minkowski difference A - B
// (both contain the origin, their centroid). Computed from the hull of all a_i - b_j, independently of the code
// under test.
double touching_distance(const std::vector<Vec2>& a, const std::vector<Vec2>& b, const Vec2& u) {
  std::vector<Vec2> diff;
  diff.reserve(a.size() * b.size());
  for (const Vec2& p : a)
    for (const Vec2& q : b) diff.push_back(p - q);
  const auto m = tsupport::convex_hull(diff);
  double t = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < m.size(); ++i) {
    const Vec2 nrm = geometry::perp_right(m[(i + 1) % m.size()] - m[i]);  // outward
    const double den = nrm.dot(u);
    if (den > 0.0) t = std::min(t, nrm.dot(m[i]) / den);
  }
  return t;
}

geometry::Aabb box_of(const std::vector<Vec2>& v) {
  geometry::Aabb b{v[0], v[0]};
  for (const Vec2& p : v) {
    b.lo = b.lo.cwiseMin(p);
    b.hi = b.hi.cwiseMax(p);
  }
  return b;
}

// kPairs pairs of n-vertex floes; overlapping (B moved in by the overlap) or separated (B moved out by the gap,
// with the bounding boxes still overlapping).
PairSet make_pairs(int n, bool overlapping, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  PairSet s;
  s.offset.push_back(0);
  for (int k = 0; k < kPairs; ++k) {
    for (;;) {
      const double size_a = log_uniform(rng, 5.0, 100.0), size_b = log_uniform(rng, 5.0, 100.0);
      const auto a0 = random_floe(rng, n, size_a), b0 = random_floe(rng, n, size_b);
      const double amount = log_uniform(rng, 1e-3, 0.1 * std::min(size_a, size_b));
      // Separated pairs: retry directions until the boxes overlap (near-diagonal approaches for large gaps).
      bool placed = false;
      std::vector<Vec2> a, b;
      for (int tries = 0; tries < 50 && !placed; ++tries) {
        const double ang = 2.0 * std::numbers::pi * u(rng);
        const Vec2 dir{std::cos(ang), std::sin(ang)};
        const double t = touching_distance(a0, b0, dir) + (overlapping ? -amount : amount);
        const Vec2 where{5000.0 * (2.0 * u(rng) - 1.0), 5000.0 * (2.0 * u(rng) - 1.0)};
        a = tsupport::transform(a0, 0.0, where);
        b = tsupport::transform(b0, 0.0, where + t * dir);
        placed = overlapping || box_of(a).overlaps(box_of(b));
      }
      if (!placed) continue;
      s.xy.insert(s.xy.end(), a.begin(), a.end());
      s.offset.push_back(static_cast<int>(s.xy.size()));
      s.xy.insert(s.xy.end(), b.begin(), b.end());
      s.offset.push_back(static_cast<int>(s.xy.size()));
      break;
    }
  }
  return s;
}

const PairSet& pairs_for(int n, bool overlapping) {
  // Generated once per (n, kind) and kept: repetitions do not pay for it again (std::map: references stay valid).
  static std::map<std::pair<int, bool>, PairSet> cache;
  auto it = cache.find({n, overlapping});
  if (it == cache.end())
    it = cache.emplace(std::pair{n, overlapping}, make_pairs(n, overlapping, 1000u * n + (overlapping ? 1 : 2))).first;
  return it->second;
}

// Checks every pair outside timing; returns an error message, or "" when all pairs behave as labelled.
std::string check_pairs(const PairSet& s, bool overlapping) {
  for (int k = 0; k < kPairs; ++k) {
    contact::PlanarContact c;
    const bool hit = contact::planar_overlap(s.poly(2 * k), s.poly(2 * k + 1), c);
    if (hit != overlapping)
      return "pair " + std::to_string(k) + (overlapping ? " should overlap but was rejected" : " should be rejected");
    if (hit && !(c.area > 0.0 && c.depth > 0.0 && std::isfinite(c.normal.x())))
      return "pair " + std::to_string(k) + ": degenerate contact";
  }
  return "";
}

// Spans built up front so the timed loop is the call alone.
std::vector<std::span<const Vec2>> spans_of(const PairSet& s) {
  std::vector<std::span<const Vec2>> polys;
  for (int k = 0; k < 2 * kPairs; ++k) polys.push_back(s.poly(k));
  return polys;
}

// Each polygon's edge lines, as a World keeps them per body (computed once per body and step, outside the pairs'
// timing).
struct PolygonLines {
  std::vector<double> nx, ny, offset;
  std::vector<contact::EdgeLines> lines;
};
PolygonLines lines_of(const std::vector<std::span<const Vec2>>& polys) {
  PolygonLines l;
  std::size_t total = 0;
  for (const auto& p : polys) total += p.size();
  l.nx.resize(total);
  l.ny.resize(total);
  l.offset.resize(total);
  std::size_t at = 0;
  for (const auto& p : polys) {
    contact::edge_lines(p, l.nx.data() + at, l.ny.data() + at, l.offset.data() + at);
    l.lines.push_back({l.nx.data() + at, l.ny.data() + at, l.offset.data() + at, p[0]});
    at += p.size();
  }
  return l;
}

// The timed loop: planar_overlap on pair after pair (with each pair's kept topology, when given; with the
// polygons' edge lines for the foundation terms).
void time_pairs(benchmark::State& state, const std::vector<std::span<const Vec2>>& polys,
                const std::vector<contact::OverlapTopology>* kept,
                contact::OverlapTerms terms = contact::OverlapTerms::basic) {
  const PolygonLines lines = lines_of(polys);
  const bool with_lines = terms == contact::OverlapTerms::foundation;
  contact::PlanarContact c;
  std::uint32_t k = 0;
  std::int64_t hits = 0;
  const double cpu0 = thread_cpu_seconds();
  for (auto _ : state) {
    contact::OverlapTopology t = kept ? (*kept)[k] : contact::OverlapTopology{};
    const bool hit = contact::planar_overlap(polys[2 * k], polys[2 * k + 1], c, terms, kept ? &t : nullptr,
                                             with_lines ? &lines.lines[2 * k] : nullptr,
                                             with_lines ? &lines.lines[2 * k + 1] : nullptr);
    benchmark::DoNotOptimize(hit);
    benchmark::DoNotOptimize(c);
    benchmark::DoNotOptimize(t);
    hits += hit;
    k = (k + 1) & (kPairs - 1);
  }
  const double cpu_ns = 1e9 * (thread_cpu_seconds() - cpu0);
  benchmark::DoNotOptimize(hits);
  state.SetItemsProcessed(state.iterations());
  // CPU ns per pair over the timed loop (the CPU column, spelled out for readers of the JSON).
  state.counters["ns_per_pair"] = cpu_ns / static_cast<double>(state.iterations());
  state.counters["vertices"] = static_cast<double>(state.range(0));
}

void run(benchmark::State& state, bool overlapping, contact::OverlapTerms terms = contact::OverlapTerms::basic) {
  const int n = static_cast<int>(state.range(0));
  const PairSet& s = pairs_for(n, overlapping);
  if (const std::string err = check_pairs(s, overlapping); !err.empty()) {
    state.SkipWithError(err.c_str());
    return;
  }
  time_pairs(state, spans_of(s), nullptr, terms);
}

void BM_PlanarOverlap(benchmark::State& state) { run(state, true); }
void BM_PlanarSeparated(benchmark::State& state) { run(state, false); }
// The same with the foundation force model's terms (its energy, load and moment, and the overlap's extent).
void BM_PlanarOverlapFoundation(benchmark::State& state) { run(state, true, contact::OverlapTerms::foundation); }

void kept_pairs(benchmark::State& state, contact::OverlapTerms terms) {
  const int n = static_cast<int>(state.range(0));
  const PairSet& s = pairs_for(n, true);
  if (const std::string err = check_pairs(s, true); !err.empty()) {
    state.SkipWithError(err.c_str());
    return;
  }
  const std::vector<std::span<const Vec2>> polys = spans_of(s);
  // Each pair's topology one step earlier: B moved back by 1 mm and turned back by 1e-4 rad about its centre.
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::vector<contact::OverlapTopology> kept(kPairs);
  int accepted = 0;
  for (int k = 0; k < kPairs; ++k) {
    const std::span<const Vec2> b = polys[2 * k + 1];
    Vec2 centre{0.0, 0.0};
    for (const Vec2& q : b) centre += q;
    centre /= static_cast<double>(b.size());
    const double ang = 2.0 * std::numbers::pi * u(rng), c = std::cos(1e-4), sn = std::sin(1e-4);
    const Vec2 back = 1e-3 * Vec2{std::cos(ang), std::sin(ang)};
    std::vector<Vec2> earlier;
    for (const Vec2& q : b) {
      const Vec2 r = q - centre;
      earlier.push_back(centre + back + Vec2{c * r.x() + sn * r.y(), -sn * r.x() + c * r.y()});
    }
    contact::PlanarContact g;
    contact::planar_overlap(polys[2 * k], earlier, g, false, &kept[k]);
    // Whether the check passes now, and that it changes nothing.
    contact::OverlapTopology t = kept[k];
    contact::PlanarContact fresh, reused;
    contact::planar_overlap(polys[2 * k], b, fresh);
    contact::planar_overlap(polys[2 * k], b, reused, false, &t);
    if (std::memcmp(&fresh, &reused, sizeof fresh) != 0) {
      state.SkipWithError(("pair " + std::to_string(k) + ": the kept topology changed the result").c_str());
      return;
    }
    accepted += t.reused;
  }
  time_pairs(state, polys, &kept, terms);
  state.counters["kept_fraction"] = static_cast<double>(accepted) / kPairs;
}

void BM_PlanarOverlapKept(benchmark::State& state) { kept_pairs(state, contact::OverlapTerms::basic); }
void BM_PlanarOverlapKeptFoundation(benchmark::State& state) { kept_pairs(state, contact::OverlapTerms::foundation); }

const char* kMethodNames[] = {"planar", "gjk2d", "sat3d", "ccd_gjk_epa", "ccd_gjk_epa_tiebreak", "ccd_mpr"};

// One method over the overlapping n-vertex pairs as level prisms (3-D methods) or polygons (planar ones).
void BM_Method(benchmark::State& state) {
  const int m = static_cast<int>(state.range(0)), n = static_cast<int>(state.range(1));
  const PairSet& s = pairs_for(n, true);
  std::vector<geometry::ConvexPolyhedron> shapes;
  std::vector<std::vector<geometry::Vec3>> world;
  std::vector<geometry::Vec3> centre;
  for (int k = 0; k < 2 * kPairs; ++k) {
    const auto poly = s.poly(k);
    Vec2 offset{0.0, 0.0};
    const auto shape = geometry::ConvexPolygon::from_vertices(poly, &offset);
    shapes.push_back(geometry::ConvexPolyhedron::prism(shape, 1.0));
    const geometry::Vec3 c{offset.x(), offset.y(), 0.0};
    centre.push_back(c);
    std::vector<geometry::Vec3> w;
    for (const auto& v : shapes.back().vertices()) w.push_back(v + c);
    world.push_back(std::move(w));
  }
  const geometry::Mat3 id = geometry::Mat3::Identity();
  const contact::CcdMethod ccd[] = {contact::CcdMethod::gjk_epa, contact::CcdMethod::gjk_epa_tiebreak,
                                    contact::CcdMethod::mpr};
  std::uint32_t k = 0;
  std::int64_t hits = 0;
  double depth_sum = 0.0;
  const double cpu0 = thread_cpu_seconds();
  for (auto _ : state) {
    const int a = static_cast<int>(2 * k), b = a + 1;
    if (m == 0) {
      contact::PlanarContact c;
      const bool hit = contact::planar_overlap(s.poly(a), s.poly(b), c);
      hits += hit ? 1 : 0;
      depth_sum += c.depth;
    } else if (m == 1) {
      const auto c = contact::gjk_epa_2d(s.poly(a), s.poly(b));
      hits += c.status == contact::Gjk2dStatus::contact;
      depth_sum += c.depth;
    } else if (m == 2) {
      const auto c = contact::sat_penetration(shapes[a], id, world[a], centre[a], shapes[b], id, world[b], centre[b]);
      hits += c.hit;
      depth_sum += c.depth;
    } else {
      const auto c = contact::ccd_penetration(world[a], world[b], ccd[m - 3]);
      hits += c.status == contact::CcdStatus::contact;
      depth_sum += c.depth;
    }
    k = (k + 1) & (kPairs - 1);
  }
  const double cpu_ns = 1e9 * (thread_cpu_seconds() - cpu0);
  // (hits and depth_sum stay live through the counters; GCC 12 miscompiles a DoNotOptimize(int64&) that is read
  // afterwards: its "+m,r" constraint hands back the bits of another value)
  state.SetLabel(kMethodNames[m]);
  state.counters["ns_per_pair"] = cpu_ns / static_cast<double>(state.iterations());
  state.counters["contact_fraction"] = static_cast<double>(hits) / static_cast<double>(state.iterations());
  state.counters["mean_depth"] = depth_sum / static_cast<double>(state.iterations());
}

}  // namespace

BENCHMARK(BM_Method)->ArgsProduct({{0, 1, 2, 3, 4, 5}, {12}})->MinTime(0.3);
BENCHMARK(BM_PlanarOverlap)->Arg(4)->Arg(8)->Arg(12)->Arg(20)->MinTime(0.3);
BENCHMARK(BM_PlanarSeparated)->Arg(4)->Arg(8)->Arg(12)->Arg(20)->MinTime(0.3);
BENCHMARK(BM_PlanarOverlapKept)->Arg(4)->Arg(8)->Arg(12)->Arg(20)->MinTime(0.3);
BENCHMARK(BM_PlanarOverlapFoundation)->Arg(4)->Arg(12)->Arg(20)->MinTime(0.3);
BENCHMARK(BM_PlanarOverlapKeptFoundation)->Arg(4)->Arg(12)->Arg(20)->MinTime(0.3);

BENCHMARK_MAIN();
