// The one door to libccd (GJK-EPA and MPR on convex polyhedra): the only file that includes <ccd/ccd.h> is
// narrow_phase_ccd.cpp.
//
// libccd 2.1 has failure modes on level floes (docs/validation.md, "Failure map of the contact methods"): with both
// prisms spanning the same z-range the support points tie, and EPA can exit as "touching" with depth ~0 and an
// arbitrary normal; its GJK can call a few overlapping pairs separated (no check of the answer sees that: the
// spatial world confirms every separation exactly); its EPA loop has no iteration cap; its contact point is a
// heuristic; MPR's depth is not the minimum translation. This adapter
//   - asserts at build time that libccd is built in double precision,
//   - checks every return code and every returned number (NaN, infinite, non-unit normal, negative depth),
//   - bounds EPA: after `max_support_calls` support evaluations the support functions freeze (return the vertex
//     they returned last), which makes EPA's expansion test fail and the loop end; a result reached that way is
//     reported as failed,
//   - in the `gjk_epa_tiebreak` method, breaks ties of the support function (vertices at the same height along the
//     search direction) towards the vertex farthest along a fixed skew direction, with the opposite skew for the
//     second body, so that the Minkowski-difference support is unique.
// A failed query never returns a number that reaches the integrator: status = failed with the reason.
//
// Details of the adapter (narrow_phase_ccd.cpp):
//   - libccd sees normalised coordinates (x - o) / L, o and L the centre and half-diagonal of the pair's joint
//     bounding box, so its hard-coded absolute epsilon (DBL_EPSILON) acts relative to the pair's size. Without
//     this, plain gjk_epa misses ~44% of 1 mm - 10 cm overlaps of 5-100 m level floes; with it ~1.4% of them fail
//     (the zero-depth exit below) and ~2e-5 are reported separated.
//   - Sign: libccd's `dir` is the point of A - B nearest the origin (normalised), the translation of B that
//     separates; `normal` is that direction, A to B.
//   - Tie-break: vertices within 1e-9 L of the maximum along the search direction tie; A takes the one farthest
//     along kSkew = (1, √2, √3)/√6, B along -kSkew, so the support of A - B maximises (direction, then kSkew).
//   - EPA bound: past `max_support_calls`, the support returns its last vertex, a vertex of the polytope; each EPA
//     step then either stops (a nearest element through that vertex fails the expansion test: distance 0) or
//     replaces elements not through it by elements through it, so the loop ends within the polytope's face count.
//     The same bound caps MPR's refinement loop (which libccd does not cap either): "MPR iteration bound reached".
//   - Zero depth: an intersection with depth below libccd's own zero (depth^2 < DBL_EPSILON in normalised units,
//     depth < 1.5e-8 L), where libccd leaves the direction arbitrary (EPA) or zero (MPR), is reported as failed: it
//     is a true touch or EPA's false exit on overlapping level floes, and the answer cannot tell them apart.
//   - A contact must be consistent: its depth equals the bodies' overlap along its normal (the support of A - B)
//     within the method's tolerance x L; else failed. This catches a polytope that stopped short, and MPR's false
//     intersections on separated level floes (~0.05-0.4%: depth = the gap, normal from B to A).
//   - `support_calls` counts support evaluations of A (those of B are the same number).
#pragma once

#include <span>

#include <Eigen/Core>

namespace polyfloe::contact {

using Vec3 = Eigen::Vector3d;

enum class CcdMethod {
  gjk_epa,           // libccd's ccdGJKPenetration with its own support ties (the default libccd behaviour)
  gjk_epa_tiebreak,  // the same with ties in the support function broken (see above)
  mpr,               // libccd's ccdMPRPenetration (Minkowski portal refinement)
};
const char* to_string(CcdMethod m);

struct CcdSettings {
  unsigned long max_iterations = 100;  // libccd's GJK/MPR iteration cap [-]
  double epa_tolerance = 1e-6;         // libccd's EPA tolerance, relative to the pair's size [-]
  double mpr_tolerance = 1e-6;         // libccd's MPR tolerance, relative to the pair's size [-]
  int max_support_calls = 2000;        // bound of EPA (see above) [-]
};

enum class CcdStatus {
  separated,  // no intersection
  contact,    // depth >= 0, unit normal, finite point
  failed,     // libccd returned an error or a result that failed the checks; `reason` says which
};

struct CcdContact {
  CcdStatus status = CcdStatus::separated;
  double depth = 0.0;          // penetration depth [m]
  Vec3 normal{0.0, 0.0, 1.0};  // unit, from A to B (moving B by depth x normal separates them)
  Vec3 point{0.0, 0.0, 0.0};   // libccd's contact point [m]
  const char* reason = "";     // why it failed (static string)
  int support_calls = 0;       // support evaluations used [-]
};

// `a`, `b`: world-frame vertices of two convex polyhedra (the convex hull of each set is the body).
CcdContact ccd_penetration(std::span<const Vec3> a, std::span<const Vec3> b, CcdMethod method,
                           const CcdSettings& settings = {});

}  // namespace polyfloe::contact
