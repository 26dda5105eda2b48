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
#include <limits>
#include <map>
#include <memory>
#include <numbers>
#include <optional>
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
#include "failure_map_cases.h"
#include "driver_args.h"
#include "json_out.h"
#include "test_support.h"

using namespace polyfloe;
using geometry::Vec2;
using geometry::Vec3;
using Mat3 = geometry::Mat3;
using Clock = std::chrono::steady_clock;

namespace {

using namespace failure_map;

volatile double g_sink = 0.0;  // every timed result ends up here

constexpr double kTieTol = 1e-6;  // ties of the normal: 1e-6 x the pair's half-diagonal
const double kCos1deg = std::cos(std::numbers::pi / 180.0);

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
                                      "libccd GJK-EPA tie-break",  "libccd MPR",      "exact 3-D SAT"};
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
  double max_us = 0.0;           // slowest single query (per pair the least of 3 timings) [us]
  int slowest = -1;              // its pair
  double false_depth_max = 0.0;  // deepest false contact [m]
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
  CLI::App app("The failure map of the contact methods over random and degenerate pairs of floes", "bench_failure_map");
  app.add_option("-o", out_file, "the JSON file written")->capture_default_str();
  app.add_flag("--quick", quick, "fewer pairs (2,000 random, 200 per degenerate set) and 3 timed passes");
  app.add_option("--random", n_random, "random pairs (default 20,000; --quick 2,000)")->check(CLI::Range(1, 10000000));
  app.add_option("--degenerate", n_degenerate, "pairs per degenerate set (default 1,000; --quick 200)")
      ->check(CLI::Range(1, 10000000));
  app.add_option("--seed", seed, "added to every set's seed")->capture_default_str();
  if (const std::optional<int> stop = tsupport::parse_args(app, argc, argv)) return *stop;
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
  std::printf(
      "Failure map of the contact methods: %d random pairs, %d per degenerate set, %d timed passes "
      "(pairs generated in %.1f s)\n",
      n_random, n_degenerate, passes, gen_s);
  std::printf("Floes at the floating level: z in [%.4f h, %.4f h] (rho_ice / rho_water = %.0f / %.0f)\n\n",
              floating(1.0).lo, floating(1.0).hi, kRhoIce, kRhoWater);

  // (a value without a number, a NaN or an infinity, is written as null)
  tsupport::Json json = {{"settings",
                          {{"random_pairs", n_random},
                           {"degenerate_pairs", n_degenerate},
                           {"timed_passes", passes},
                           {"seed_offset", seed},
                           {"draft_fraction", -floating(1.0).lo},
                           {"wrong_normal_degrees", 1},
                           {"tie_tolerance", kTieTol}}},
                         {"methods", tsupport::Json::array()},
                         {"cases", tsupport::Json::array()},
                         {"results", tsupport::Json::array()}};
  for (int m = 0; m < kMethods; ++m)
    json["methods"].push_back({{"name", kMethodName[m]}, {"label", kMethodLabel[m]}, {"planar", is_planar(m)}});
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
    json["cases"].push_back({{"name", c.name},
                             {"description", c.description},
                             {"pairs", c.pairs.size()},
                             {"overlapping", overlapping},
                             {"ref_mtd_min", c.pairs.front().touching ? 0.0 : ref_lo},
                             {"ref_mtd_max", c.pairs.front().touching ? 0.0 : ref_hi},
                             {"ref_vertical", vertical},
                             {"touch_residual", touch_residual}});

    std::printf("  %-9s %7s %7s %7s %7s %7s %7s %7s %7s %10s %10s %10s %9s %8s\n", "method", "contact", "failed",
                "missed", "false", "nonfin", "wrongN", "(ties)", "vert", "dErr p50", "dErr p90", "dErr max", "ns/pair",
                "max us");
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
        std::printf(
            "    BUG %s: %s, pair %d (reference MTD %.17g): status %d, depth %.17g, normal (%.17g, %.17g, "
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

      tsupport::Json reasons = tsupport::Json::object();
      for (const auto& [reason, count] : s.reasons) reasons[reason] = count;
      json["results"].push_back({{"case", c.name},
                                 {"method", kMethodName[m]},
                                 {"pairs", s.pairs},
                                 {"overlapping", s.overlapping},
                                 {"contacts", s.contacts},
                                 {"failed", s.failed},
                                 {"missed", s.missed},
                                 {"false_contact", s.false_contact},
                                 {"false_depth_max", s.false_depth_max},
                                 {"nonfinite", s.nonfinite},
                                 {"malformed", s.malformed},
                                 {"wrong_normal", s.wrong_normal},
                                 {"wrong_normal_ties", s.wrong_normal_ties},
                                 {"vertical", s.vertical},
                                 {"horizontal", s.horizontal},
                                 {"depth_error_median", p50},
                                 {"depth_error_p90", p90},
                                 {"depth_error_max", mx},
                                 {"ns_per_pair", ns},
                                 {"ns_passes", s.ns_passes},
                                 {"max_us_one_pair", s.max_us},
                                 {"slowest_pair", s.slowest},
                                 {"failure_reasons", reasons}});
    }
    std::printf("\n");
  }
  if (!tsupport::write_json(out_file, json)) return 1;
  const double secs = std::chrono::duration<double>(Clock::now() - t_start).count();
  std::printf("%d bug(s) found (non-finite, malformed, a missed or a false contact)\n", bugs);
  std::printf("wrote %s (%.0f s)\n", out_file.c_str(), secs);
  return 0;
}
