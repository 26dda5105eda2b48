// libFuzzer target: polygon validation (geometry::ConvexPolygon) and the planar narrow phase.
//
// The input bytes choose two polygons and how they are placed. A polygon is made one of four ways: raw vertices
// (every coordinate any double: NaN, +-Inf, huge, denormal, -0, repeated, nudged by one ulp), points on an ellipse
// at fuzzer-chosen angles (mostly valid, with near-collinear and near-repeated corners), ConvexPolygon::regular()
// or ConvexPolygon::rectangle(). Whatever is rejected must be rejected with a GeometryError; whatever is accepted
// must have sound properties:
//   every vertex, the offset, area, perimeter, polar moment and circumradius finite, the last four > 0;
//   circularity in (0, 1] (isoperimetric inequality); polar moment >= area^2 / (2 pi) (the disc's is the least);
//   circumradius >= equivalent radius; the stored vertices centred on their area centroid.
// Two accepted polygons (at most kMaxPolygonVertices corners) are placed at fuzzer-chosen positions and yaws; when
// both placed outlines are still valid (the narrow phase's precondition) planar_overlap() must give, both ways:
//   finite outputs (with and without the gradient terms, and depth_gradient(); the foundation terms, with the same
//   area and depth); a unit normal; area > 0 and at most the smaller polygon's area; the overlap centroid inside both
//   bounding boxes; the same area A-B and B-A;
//   no contact when the bounding boxes are apart; a contact when a point lies well inside both polygons;
//   the same bits when given a kept topology - a fuzzer-chosen one, or the one the call itself returned.
// A violated check prints what failed and aborts (a crash for libFuzzer, which saves the input).
#include <fuzzer/FuzzedDataProvider.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <numbers>
#include <optional>
#include <utility>
#include <vector>

#include "contact/narrow_phase_planar.h"
#include "geometry/polygon.h"

namespace {

using polyfloe::geometry::ConvexPolygon;
using polyfloe::geometry::GeometryError;
using polyfloe::geometry::Vec2;
namespace geometry = polyfloe::geometry;
namespace contact = polyfloe::contact;

constexpr double kEps = std::numeric_limits<double>::epsilon();

// The outlines of the current input, printed when a check fails (hexadecimal: exact).
std::vector<std::pair<const char*, std::vector<Vec2>>> g_outlines;
const contact::PlanarContact* g_contact = nullptr;  // the contact being checked, if any

[[noreturn]] void violated(const char* what, int line, double got, double bound) {
  std::fprintf(stderr, "fuzz_polygon: check failed at line %d: %s (value %.17g, bound %.17g)\n", line, what, got,
               bound);
  for (const auto& [label, v] : g_outlines) {
    std::fprintf(stderr, "%s (%zu vertices):", label, v.size());
    for (const Vec2& x : v) std::fprintf(stderr, " [%a, %a]", x.x(), x.y());
    std::fprintf(stderr, "\n");
  }
  if (const contact::PlanarContact* c = g_contact)
    std::fprintf(stderr, "contact: area %a point [%a, %a] normal [%a, %a] depth %a chord %a\n", c->area, c->point.x(),
                 c->point.y(), c->normal.x(), c->normal.y(), c->depth, c->chord);
  std::abort();
}
#define CHECK(cond)                                   \
  do {                                                \
    if (!(cond)) violated(#cond, __LINE__, 0.0, 0.0); \
  } while (0)
#define CHECK_LE(a, b)                                         \
  do {                                                         \
    const double a_ = (a), b_ = (b);                           \
    if (!(a_ <= b_)) violated(#a " <= " #b, __LINE__, a_, b_); \
  } while (0)

bool finite(const Vec2& v) { return std::isfinite(v.x()) && std::isfinite(v.y()); }

// A double as the fuzzer likes it: raw bits, a special value, the previous one (repeated points), one ulp away from
// it, a small integer, or a moderate number.
double next_double(FuzzedDataProvider& in, double previous) {
  static constexpr double kSpecial[] = {0.0,
                                        -0.0,
                                        1.0,
                                        -1.0,
                                        0.5,
                                        1e-9,
                                        1e9,
                                        1e-154,
                                        1e154,
                                        1e-300,
                                        1e300,
                                        std::numeric_limits<double>::max(),
                                        -std::numeric_limits<double>::max(),
                                        std::numeric_limits<double>::min(),
                                        std::numeric_limits<double>::denorm_min(),
                                        -std::numeric_limits<double>::denorm_min(),
                                        std::numeric_limits<double>::infinity(),
                                        -std::numeric_limits<double>::infinity(),
                                        std::numeric_limits<double>::quiet_NaN(),
                                        1.0 + kEps,
                                        1e6,
                                        1e-6,
                                        std::numbers::pi};
  switch (in.ConsumeIntegralInRange<int>(0, 6)) {
    case 0: return std::bit_cast<double>(in.ConsumeIntegral<std::uint64_t>());
    case 1: return kSpecial[in.ConsumeIntegralInRange<std::size_t>(0, std::size(kSpecial) - 1)];
    case 2: return previous;
    case 3:
      return std::nextafter(previous, in.ConsumeBool() ? std::numeric_limits<double>::infinity()
                                                       : -std::numeric_limits<double>::infinity());
    case 4: return static_cast<double>(in.ConsumeIntegralInRange<int>(-16, 16));
    default: return in.ConsumeFloatingPointInRange<double>(-1000.0, 1000.0);
  }
}

// A candidate polygon; nullopt when the chosen constructor rejected it (with a GeometryError).
std::optional<ConvexPolygon> make_polygon(FuzzedDataProvider& in) {
  const int how = in.ConsumeIntegralInRange<int>(0, 3);
  std::vector<Vec2> v;
  try {
    if (how == 2) {
      const int sides = in.ConsumeIntegralInRange<int>(-2, 80);
      return ConvexPolygon::regular(sides, next_double(in, 1.0));
    }
    if (how == 3) {
      const double w = next_double(in, 1.0);
      return ConvexPolygon::rectangle(w, next_double(in, w));
    }
    const int n = in.ConsumeIntegralInRange<int>(0, 80);
    if (how == 0) {  // raw vertices
      double prev = 0.0;
      for (int i = 0; i < n; ++i) {
        const double x = next_double(in, prev);
        const double y = next_double(in, x);
        v.emplace_back(x, y);
        prev = y;
      }
    } else {  // on an ellipse at sorted fuzzer-chosen angles, then perhaps spoiled
      const double scale = next_double(in, 1.0);
      const double aspect = next_double(in, 1.0);
      const Vec2 centre{next_double(in, 0.0), next_double(in, 0.0)};
      const double turn = next_double(in, 0.0);
      std::vector<double> angle(static_cast<std::size_t>(n));
      for (double& a : angle) a = 2.0 * std::numbers::pi * in.ConsumeProbability<double>();
      std::sort(angle.begin(), angle.end());
      const double c = std::cos(turn), s = std::sin(turn);
      for (double a : angle)
        v.push_back(centre + scale * geometry::rotate(Vec2(aspect * std::cos(a), std::sin(a)), c, s));
      if (!v.empty()) {
        switch (in.ConsumeIntegralInRange<int>(0, 4)) {
          case 0: std::reverse(v.begin(), v.end()); break;  // clockwise
          case 1:
            v.insert(v.begin() + in.ConsumeIntegralInRange<std::ptrdiff_t>(0, std::ssize(v) - 1),
                     v[in.ConsumeIntegralInRange<std::size_t>(0, v.size() - 1)]);
            break;   // a repeat
          case 2: {  // one coordinate replaced
            Vec2& p = v[in.ConsumeIntegralInRange<std::size_t>(0, v.size() - 1)];
            (in.ConsumeBool() ? p.x() : p.y()) = next_double(in, p.x());
            break;
          }
          default: break;
        }
      }
    }
    g_outlines.emplace_back("input", v);
    Vec2 offset{std::numeric_limits<double>::quiet_NaN(), 0.0};
    ConvexPolygon p = ConvexPolygon::from_vertices(v, &offset);
    CHECK(p.size() == std::ssize(v));
    CHECK(finite(offset));
    // The stored vertices are centred on their area centroid (to round-off of the input's magnitude).
    double magnitude = 0.0;
    for (const Vec2& x : v) magnitude = std::max(magnitude, x.lpNorm<Eigen::Infinity>());
    const Vec2 c = geometry::polygon_properties(p.vertices()).centroid;
    CHECK_LE(c.norm(), 1e-9 * p.circumradius() + 64.0 * kEps * magnitude);
    return p;
  } catch (const GeometryError&) {
    // An empty message would leave the user guessing.
    if (how < 2) CHECK(!geometry::convexity_error(v).empty());
    return std::nullopt;
  }
}

void check_properties(const ConvexPolygon& p) {
  g_outlines.emplace_back("accepted, centred", p.vertices());
  CHECK(p.size() >= 3);
  for (const Vec2& x : p.vertices()) CHECK(finite(x));
  const double area = p.area(), perimeter = p.perimeter(), moment = p.polar_moment(), radius = p.circumradius();
  CHECK(std::isfinite(area) && area > 0.0);
  CHECK(std::isfinite(perimeter) && perimeter > 0.0);
  CHECK(std::isfinite(moment) && moment > 0.0);
  CHECK(std::isfinite(radius) && radius > 0.0);
  const double circ = p.circularity();
  CHECK(std::isfinite(circ) && circ > 0.0);
  CHECK_LE(circ, 1.0 + 1e-9);
  CHECK_LE(area / (2.0 * std::numbers::pi) * (1.0 - 1e-6), moment / area);  // J >= A^2 / (2 pi)
  CHECK_LE(p.equivalent_radius() * (1.0 - 1e-9), radius);
  const geometry::PrismMass m = geometry::prism_mass(p, 1.0, 920.0);
  CHECK(std::isfinite(m.mass) && std::isfinite(m.inertia_z));
}

struct Placed {
  std::vector<Vec2> v;
  double area = 0.0, perimeter = 0.0;
  geometry::Aabb box;
};

std::optional<Placed> place(const ConvexPolygon& p, const Vec2& at, double yaw) {
  if (!finite(at) || !std::isfinite(yaw)) return std::nullopt;
  Placed out;
  const double c = std::cos(yaw), s = std::sin(yaw);
  for (const Vec2& x : p.vertices()) out.v.push_back(at + geometry::rotate(x, c, s));
  // planar_overlap() requires valid outlines; placing can spoil a nearly degenerate one by round-off.
  if (!geometry::convexity_error(out.v).empty()) return std::nullopt;
  g_outlines.emplace_back("placed", out.v);
  const geometry::PolygonProperties props = geometry::polygon_properties(out.v);
  out.area = props.area;
  out.perimeter = props.perimeter;
  out.box.lo = out.box.hi = out.v.front();
  for (const Vec2& x : out.v) {
    out.box.lo = out.box.lo.cwiseMin(x);
    out.box.hi = out.box.hi.cwiseMax(x);
  }
  return out;
}

// Signed distance from x to the polygon's boundary, < 0 inside (the largest signed distance to an edge line).
double inside_distance(const std::vector<Vec2>& v, const Vec2& x) {
  double d = -std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < v.size(); ++i) {
    const Vec2 e = v[(i + 1) % v.size()] - v[i];
    d = std::max(d, geometry::cross(x - v[i], e) / e.norm());
  }
  return d;
}

// `area_tol`: the round-off allowed in areas; `point_tol`: how far outside a bounding box the centroid may lie.
void check_contact(const contact::PlanarContact& c, const Placed& a, const Placed& b, double area_tol,
                   double point_tol) {
  g_contact = &c;
  CHECK(std::isfinite(c.area) && c.area > 0.0);
  CHECK_LE(c.area, std::min(a.area, b.area) + area_tol);
  CHECK(finite(c.point) && finite(c.normal));
  CHECK_LE(std::abs(c.normal.norm() - 1.0), 1e-9);
  CHECK(std::isfinite(c.depth) && c.depth >= 0.0);
  CHECK(std::isfinite(c.chord) && c.chord >= 0.0);
  for (const geometry::Aabb* box : {&a.box, &b.box}) {
    CHECK_LE(box->lo.x() - point_tol, c.point.x());
    CHECK_LE(box->lo.y() - point_tol, c.point.y());
    CHECK_LE(c.point.x(), box->hi.x() + point_tol);
    CHECK_LE(c.point.y(), box->hi.y() + point_tol);
  }
  CHECK(std::isfinite(c.moment) && finite(c.ga) && finite(c.gb) && std::isfinite(c.ha) && std::isfinite(c.hb));
  g_contact = nullptr;
}

void check_pair(const Placed& a, const Placed& b, bool with_gradient, const contact::OverlapTopology& kept) {
  // Round-off: the narrow phase works in coordinates relative to one vertex, so a coordinate is known to about
  // epsilon x (the pair's extent + the coordinates' magnitude). An area to that times the perimeters, and the
  // centroid of an overlap to its size times the relative error of its area (a polygon thinner than the round-off
  // has an area, and so a centroid, made of round-off: the centroid check then lapses).
  double magnitude = 0.0, extent = 0.0;
  for (const auto* p : {&a, &b})
    magnitude = std::max({magnitude, p->box.lo.lpNorm<Eigen::Infinity>(), p->box.hi.lpNorm<Eigen::Infinity>()});
  extent = (a.box.hi.cwiseMax(b.box.hi) - a.box.lo.cwiseMin(b.box.lo)).maxCoeff();
  const double round = 64.0 * kEps * (extent + magnitude);
  const double min_area = std::min(a.area, b.area);
  const double small = std::min((a.box.hi - a.box.lo).maxCoeff(), (b.box.hi - b.box.lo).maxCoeff());
  const double area_tol = 1e-9 * min_area + round * (a.perimeter + b.perimeter);
  const double point_tol = small * (1e-9 + area_tol / min_area) + round;
  const double len_tol = 1e-9 * small + round;

  contact::PlanarContact ab, ba;
  const bool hit_ab = contact::planar_overlap(a.v, b.v, ab, with_gradient);
  const bool hit_ba = contact::planar_overlap(b.v, a.v, ba, with_gradient);
  if (hit_ab) check_contact(ab, a, b, area_tol, point_tol);
  // A kept topology changes nothing: neither a chosen one nor the one this overlap returns (passed back as the next
  // step would).
  auto same_with = [&](contact::OverlapTopology topology) {
    contact::PlanarContact again;
    CHECK(contact::planar_overlap(a.v, b.v, again, with_gradient, &topology) == hit_ab);
    if (hit_ab) CHECK(std::memcmp(&again, &ab, sizeof ab) == 0);
    return topology;
  };
  same_with(same_with(kept));
  if (hit_ba) check_contact(ba, b, a, area_tol, point_tol);
  CHECK_LE(std::abs((hit_ab ? ab.area : 0.0) - (hit_ba ? ba.area : 0.0)), area_tol);
  if (with_gradient && hit_ab) {
    const contact::DepthGradient g = contact::depth_gradient(ab, a.v.front(), b.v.front());
    CHECK(finite(g.grad_a) && finite(g.grad_b) && std::isfinite(g.grad_wa) && std::isfinite(g.grad_wb));
  }
  // The foundation force model's terms: the same contact, finite energy, load, moment and extents.
  contact::PlanarContact fd;
  CHECK(contact::planar_overlap(a.v, b.v, fd, contact::OverlapTerms::foundation) == hit_ab);
  if (hit_ab) {
    CHECK(fd.area == ab.area && fd.depth == ab.depth);
    CHECK(std::isfinite(fd.energy) && finite(fd.load) && std::isfinite(fd.load_moment));
    CHECK(std::isfinite(fd.extent) && fd.extent >= 0.0 && std::isfinite(fd.breadth) && fd.breadth >= 0.0);
  }
  // Boxes apart by more than round-off: no contact.
  const bool apart = a.box.hi.x() + len_tol < b.box.lo.x() || b.box.hi.x() + len_tol < a.box.lo.x() ||
                     a.box.hi.y() + len_tol < b.box.lo.y() || b.box.hi.y() + len_tol < a.box.lo.y();
  if (apart) CHECK(!hit_ab && !hit_ba);
  // A point well inside both (either vertex mean, or their midpoint): the interiors overlap.
  Vec2 ma{0.0, 0.0}, mb{0.0, 0.0};
  for (const Vec2& x : a.v) ma += x / static_cast<double>(a.v.size());
  for (const Vec2& x : b.v) mb += x / static_cast<double>(b.v.size());
  for (const Vec2& x : {ma, mb, Vec2(0.5 * (ma + mb))}) {
    if (finite(x) && inside_distance(a.v, x) < -1e3 * len_tol && inside_distance(b.v, x) < -1e3 * len_tol)
      CHECK(hit_ab && hit_ba);
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  FuzzedDataProvider in(data, size);
  g_outlines.clear();
  const std::optional<ConvexPolygon> pa = make_polygon(in);
  if (pa) check_properties(*pa);
  const std::optional<ConvexPolygon> pb = make_polygon(in);
  if (pb) check_properties(*pb);
  if (!pa || !pb || pa->size() > contact::kMaxPolygonVertices || pb->size() > contact::kMaxPolygonVertices) return 0;

  const Vec2 at_a{next_double(in, 0.0), next_double(in, 0.0)};
  const double yaw_a = next_double(in, 0.0);
  const Vec2 at_b{next_double(in, at_a.x()), next_double(in, at_a.y())};
  const double yaw_b = next_double(in, yaw_a);
  const bool with_gradient = in.ConsumeBool();
  contact::OverlapTopology kept;
  kept.a_first = in.ConsumeIntegralInRange<std::int8_t>(-1, 20);
  kept.a_last = in.ConsumeIntegralInRange<std::int8_t>(0, 20);
  kept.b_first = in.ConsumeIntegralInRange<std::int8_t>(0, 20);
  kept.b_last = in.ConsumeIntegralInRange<std::int8_t>(0, 20);
  kept.a_apart = in.ConsumeIntegralInRange<std::int8_t>(-1, 20);
  kept.b_apart = in.ConsumeIntegralInRange<std::int8_t>(-1, 20);
  const std::optional<Placed> a = place(*pa, at_a, yaw_a);
  const std::optional<Placed> b = place(*pb, at_b, yaw_b);
  if (a && b) check_pair(*a, *b, with_gradient, kept);
  if (a) check_pair(*a, *a, with_gradient, kept);  // a polygon on itself: full overlap
  return 0;
}
