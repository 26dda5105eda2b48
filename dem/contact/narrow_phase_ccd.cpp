// libccd adapter (see narrow_phase_ccd.h). The only file that includes <ccd/ccd.h>.
//
// Coordinates handed to libccd are normalised: x' = (x - o) / L with o the centre and L the half-diagonal of the
// pair's joint bounding box, so |x'| <= 1. libccd's hard-coded absolute epsilon (CCD_EPS = DBL_EPSILON) then acts
// relative to the pair's size, world coordinates far from the origin lose no digits, and the relative tolerances
// of CcdSettings are used as they are (EPA's squared, since libccd compares squared lengths there).
#include "contact/narrow_phase_ccd.h"

#include <ccd/ccd.h>

#include <algorithm>
#include <climits>
#include <cmath>
#include <limits>
#include <type_traits>

#if !defined(CCD_DOUBLE) || defined(CCD_SINGLE)
#error "libccd must be built in double precision (CCD_DOUBLE)"
#endif
static_assert(std::is_same_v<ccd_real_t, double>, "libccd must be built in double precision (ccd_real_t = double)");

namespace polyfloe::contact {

const char* to_string(CcdMethod m) {
  switch (m) {
    case CcdMethod::gjk_epa: return "gjk_epa";
    case CcdMethod::gjk_epa_tiebreak: return "gjk_epa_tiebreak";
    case CcdMethod::mpr: return "mpr";
  }
  return "unknown";
}

namespace {

// Tie-break of gjk_epa_tiebreak: vertices whose dot with the search direction d is within kTieEps * L * |d| of the
// maximum (every vertex lies within L of o, so this is relative to the pair's size) count as tied; among them the
// one farthest along kSkew wins for A, along -kSkew for B (B's support is asked along -d). The Minkowski support
// a - b then maximises (d, then kSkew) lexicographically: one vertex of A - B, whichever body's vertices tie.
// kSkew = (1, √2, √3)/√6 has no zero component and irrational ratios: no axis-aligned or integer difference of
// vertices is orthogonal to it (boxes, prisms never tie along it), and its z component > 0 takes A's top and B's
// bottom on level floes. Choosing a tied vertex moves the support value by at most kTieEps * L, far below the
// EPA tolerance (1e-6 * L by default).
constexpr double kTieEps = 1e-9;
const Vec3 kSkew = Vec3(1.0, std::sqrt(2.0), std::sqrt(3.0)) / std::sqrt(6.0);

struct Body {
  std::span<const Vec3> v;  // world frame
  Vec3 origin;              // o: subtracted before scaling
  double scale;             // L
  double inv_scale;         // 1 / L
  Vec3 skew;                // tie-break direction (tiebreak only)
  bool tiebreak;
  int max_calls;
  Vec3 centre;            // vertex mean, normalised (MPR's interior point)
  mutable int calls = 0;  // support evaluations so far (frozen ones included)
  mutable Vec3 last;      // last returned support vertex, normalised; vertex 0 before the first call

  Vec3 local(std::size_t i) const { return (v[i] - origin) * inv_scale; }
  bool frozen() const { return calls > max_calls; }
};

Vec3 to_eigen(const ccd_vec3_t& c) { return {c.v[0], c.v[1], c.v[2]}; }
void to_ccd(const Vec3& e, ccd_vec3_t* c) { ccdVec3Set(c, e.x(), e.y(), e.z()); }

// Support over the vertex list. Past `max_calls` evaluations it returns the vertex it returned last (the EPA bound,
// see narrow_phase_ccd.h): a point of the polytope already built, which fails EPA's expansion test.
void support(const void* obj, const ccd_vec3_t* dir, ccd_vec3_t* out) {
  const Body& b = *static_cast<const Body*>(obj);
  if (b.calls < INT_MAX) ++b.calls;
  if (b.frozen()) {
    to_ccd(b.last, out);
    return;
  }
  const Vec3 d = to_eigen(*dir);
  // Dots in world units about o: L times the normalised ones, the same order, and no scaling per vertex.
  const auto dot = [&](std::size_t i) { return (b.v[i] - b.origin).dot(d); };
  std::size_t best = 0;
  double best_dot = dot(0);
  for (std::size_t i = 1; i < b.v.size(); ++i) {  // plain: the first vertex with the maximum dot wins
    const double t = dot(i);
    if (t > best_dot) best_dot = t, best = i;
  }
  if (b.tiebreak) {  // among the near-ties, the farthest along the skew (b.skew is ±kSkew)
    const double tie_floor = best_dot - kTieEps * b.scale * d.norm();
    double best_skew = (b.v[best] - b.origin).dot(b.skew);
    for (std::size_t i = 0; i < b.v.size(); ++i) {
      if (dot(i) < tie_floor) continue;
      const double s = (b.v[i] - b.origin).dot(b.skew);
      if (s > best_skew) best_skew = s, best = i;
    }
  }
  b.last = b.local(best);
  to_ccd(b.last, out);
}

void centre(const void* obj, ccd_vec3_t* c) { to_ccd(static_cast<const Body*>(obj)->centre, c); }

// GJK's first search direction: the centre of A - B (any nonzero direction is valid; this one finds a far point).
void first_dir(const void* o1, const void* o2, ccd_vec3_t* dir) {
  const Vec3 d = static_cast<const Body*>(o1)->centre - static_cast<const Body*>(o2)->centre;
  to_ccd(d.squaredNorm() > 1e-24 ? d : Vec3(1.0, 0.0, 0.0), dir);
}

CcdContact failed(const char* reason, int calls = 0) {
  CcdContact r;
  r.status = CcdStatus::failed;
  r.reason = reason;
  r.support_calls = calls;
  return r;
}

// Overlap of the bodies along unit n (normalised): how far B must move along n to separate, the support of A - B.
double overlap_along(const Body& a, const Body& b, const Vec3& n) {
  double max_a = -std::numeric_limits<double>::infinity(), min_b = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < a.v.size(); ++i) max_a = std::max(max_a, a.local(i).dot(n));
  for (std::size_t i = 0; i < b.v.size(); ++i) min_b = std::min(min_b, b.local(i).dot(n));
  return max_a - min_b;
}

Vec3 vertex_mean(std::span<const Vec3> v, const Vec3& origin, double inv_scale) {
  Vec3 s = Vec3::Zero();
  for (const Vec3& p : v) s += p - origin;
  return s * (inv_scale / static_cast<double>(v.size()));
}

}  // namespace

CcdContact ccd_penetration(std::span<const Vec3> a, std::span<const Vec3> b, CcdMethod method,
                           const CcdSettings& settings) {
  if (a.empty() || b.empty()) return failed("empty vertex set");
  // Tolerances <= 0 or NaN would also defeat the frozen support's exit test (dist < tolerance).
  if (!(settings.epa_tolerance > 0.0) || !(settings.mpr_tolerance > 0.0) || !std::isfinite(settings.epa_tolerance) ||
      !std::isfinite(settings.mpr_tolerance))
    return failed("invalid tolerance");

  Vec3 lo = Vec3::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
  for (const auto set : {a, b})
    for (const Vec3& p : set) {
      if (!p.allFinite()) return failed("non-finite vertex");
      lo = lo.cwiseMin(p);
      hi = hi.cwiseMax(p);
    }
  const Vec3 origin = 0.5 * (lo + hi);
  const double scale = 0.5 * (hi - lo).norm();  // L
  if (!(scale > 0.0) || !std::isfinite(scale)) return failed("degenerate vertex sets");
  const double inv_scale = 1.0 / scale;

  const bool tiebreak = method == CcdMethod::gjk_epa_tiebreak;
  const Body body_a{a,
                    origin,
                    scale,
                    inv_scale,
                    kSkew,
                    tiebreak,
                    settings.max_support_calls,
                    vertex_mean(a, origin, inv_scale),
                    0,
                    (a[0] - origin) * inv_scale};
  const Body body_b{b,
                    origin,
                    scale,
                    inv_scale,
                    -kSkew,
                    tiebreak,
                    settings.max_support_calls,
                    vertex_mean(b, origin, inv_scale),
                    0,
                    (b[0] - origin) * inv_scale};

  ccd_t ccd;
  CCD_INIT(&ccd);
  ccd.first_dir = first_dir;
  ccd.support1 = support;
  ccd.support2 = support;
  ccd.center1 = centre;
  ccd.center2 = centre;
  ccd.max_iterations = settings.max_iterations;
  ccd.epa_tolerance = settings.epa_tolerance * settings.epa_tolerance;  // EPA compares squared lengths
  ccd.mpr_tolerance = settings.mpr_tolerance;                           // MPR compares lengths
  ccd.dist_tolerance = settings.epa_tolerance;                          // unused by the penetration queries

  // NaN until libccd writes them: an output it leaves unset fails the checks below.
  constexpr double nan = std::numeric_limits<double>::quiet_NaN();
  ccd_real_t depth = nan;
  ccd_vec3_t dir, pos;
  ccdVec3Set(&dir, nan, nan, nan);
  ccdVec3Set(&pos, nan, nan, nan);
  const int ret = method == CcdMethod::mpr ? ccdMPRPenetration(&body_a, &body_b, &ccd, &depth, &dir, &pos)
                                           : ccdGJKPenetration(&body_a, &body_b, &ccd, &depth, &dir, &pos);
  const int calls = body_a.calls;  // support1 and support2 are called in pairs

  // A frozen support makes any verdict, "separated" included, an artefact of the bound.
  if (body_a.frozen() || body_b.frozen())
    return failed(method == CcdMethod::mpr ? "MPR iteration bound reached" : "EPA iteration bound reached", calls);
  if (ret == -2) return failed("libccd memory allocation failed", calls);
  if (ret == -1) {
    CcdContact r;
    r.support_calls = calls;
    return r;  // separated
  }
  if (ret != 0) return failed("libccd returned an unknown code", calls);

  if (!std::isfinite(depth)) return failed("non-finite depth", calls);
  if (depth < 0.0) return failed("negative depth", calls);
  // Zero depth by libccd's own test (ccdIsZero on the squared distance, as its EPA does): depth < √ε · L, where its
  // exits leave depth ~1e-16 and the direction arbitrary (EPA) or zero (MPR). It is a true touch, or EPA's false
  // exit on coplanar support ties (level floes, a face falling flat on a face: overlaps of centimetres reported as
  // nothing). The result cannot tell them apart, so it is a failure: the caller asks an exact method.
  if (ccdIsZero(depth * depth)) return failed("zero depth on an intersection (a touch, or EPA's tie exit)", calls);
  // libccd's `dir` is the Minkowski difference A - B's boundary point nearest the origin, normalised: translating
  // B (obj2) by depth * dir separates the bodies, so it already points from A to B.
  Vec3 n = to_eigen(dir);
  if (!n.allFinite()) return failed("non-finite normal", calls);
  const double len = n.norm();
  if (!(std::abs(len - 1.0) <= 1e-6)) return failed("non-unit normal", calls);
  n /= len;
  // A converged answer lies on the boundary of A - B: its depth is the bodies' overlap along its normal (measured
  // within 1e-11 L on level floes). A mismatch is a polytope that stopped short.
  const double tol = method == CcdMethod::mpr ? settings.mpr_tolerance : settings.epa_tolerance;  // relative to L
  if (std::abs(overlap_along(body_a, body_b, n) - depth) > tol)
    return failed("depth disagrees with the overlap along the normal", calls);
  const Vec3 point = to_eigen(pos);
  if (!point.allFinite()) return failed("non-finite point", calls);

  CcdContact r;
  r.status = CcdStatus::contact;
  r.depth = depth * scale;
  r.normal = n;
  r.point = origin + point * scale;
  r.support_calls = calls;
  return r;
}

}  // namespace polyfloe::contact
