// Exact planar narrow phase for level prisms (floes at one level): the overlap of two convex polygons.
//
// The overlap polygon P = A ∩ B is found by clipping A against B's edge lines. From it:
//   area    |P|                                       [m^2]
//   point   the area centroid of P                     [m]
//   chord   N = sum over the edges of P that lie on ∂A of (edge length x outward normal of A);
//           for the usual two boundary crossings p, q this is the chord q - p turned by 90 degrees, and in
//           general it is -grad_t |A ∩ (B + t)|, so the normal is the direction in which moving B away
//           reduces the overlap fastest.
//   normal  N / |N|, pointing from A to B
//   depth   |P| / |N|: the mean thickness of the overlap measured across the chord [m]
// When A lies wholly inside B or B inside A the chord vanishes; the normal then falls back to the
// separating-axis direction of least penetration and the depth to that penetration.
//
// Energy consistency: the contact energy is a function of the depth, W(depth), so the contact force must be the
// gradient of depth = |P| / |N| with respect to both bodies' positions and rotations. The area part of that
// gradient is carried by N and the moment M of the ∂A part of the boundary; the chord-length part by how the
// boundary crossings slide along the edges they lie on. A crossing x of A's edge (normal n_a) and B's edge (n_b)
// moves with x' = [n_a·u_A(x) perp_right(n_b) + n_b·u_B(x) perp_left(n_a)] / cross(n_a, n_b), u_i the rigid
// velocity field of body i; summed over exits minus entries of the ∂A chains, projected on N/|N|, this gives
// d|N|/dt = ga·v_A + (ha - cross(x_A - c, ga)) w_A + gb·v_B + (hb - cross(x_B - c, gb)) w_B (c the centroid).
// dynamics/contact_stage.cpp assembles the generalised force from these terms.
#pragma once

#include <cstdint>
#include <span>

#include "geometry/vec2.h"

namespace polyfloe::contact {

using geometry::Vec2;

// Largest vertex count a polygon may have for the planar narrow phase (scratch space lives on the stack).
inline constexpr int kMaxPolygonVertices = 64;

struct PlanarContact {
  Vec2 normal{1.0, 0.0};  // unit normal from A to B
  Vec2 point{0.0, 0.0};   // centroid of the overlap polygon [m]
  double depth = 0.0;     // overlap area / chord length [m]
  double area = 0.0;      // overlap area [m^2]
  double chord = 0.0;     // chord length |N| [m]; 0 in the containment fallback
  // Gradient terms (see above), all about the centroid `point`:
  double moment = 0.0;  // M: sum over ∂A edges of cross(midpoint - point, edge normal x length) [m^2]
  Vec2 ga{0.0, 0.0};    // d|N|/dv_A [-]
  Vec2 gb{0.0, 0.0};    // d|N|/dv_B [-]
  double ha = 0.0;      // d|N|/dw_A about the centroid [m]
  double hb = 0.0;      // d|N|/dw_B about the centroid [m]
  // Elastic-foundation terms (OverlapTerms::foundation; contact/foundation.h), per unit foundation modulus
  // (laid out without padding: tests compare contacts bit for bit):
  Vec2 load{0.0, 0.0};       // -dI/dx_B: the force on B [m^2] (on A: its opposite)
  double energy = 0.0;       // I = ∫_P (d_A + d_B) dA [m^3]
  double load_moment = 0.0;  // the torque on B about `point` [m^3]
  double extent = 0.0;       // the overlap's extent along the load [m] (its thickness across the contact)
  double breadth = 0.0;      // its extent across the load [m] (the contact's length)
  // OverlapTerms::basic: d(depth)/d(approach), B moved against the normal, 1 - S/L^2 dL/d(approach): 1 for a
  // face on a face (the chord keeps its length), 1/2 for a corner in a face (S/L grows at half the corner's
  // penetration); 1 in the containment fallback [-]
  double slope = 1.0;
  double unused = 0.0;  // (an even count of doubles: no padding after the 16-byte aligned Vec2s)
};
static_assert(sizeof(PlanarContact) == 22 * sizeof(double), "PlanarContact has no padding");

// What planar_overlap measures beyond the area, centroid, chord and depth.
enum class OverlapTerms {
  basic,
  depth_gradient,  // moment, ga, gb, ha, hb (30-50 ns more per overlapping pair)
  foundation,      // energy, load, load_moment
};

// Gradient of the depth with respect to the velocities of two bodies whose centres are x_a, x_b:
// d(depth)/dt = grad_a·v_a + grad_wa w_a + grad_b·v_b + grad_wb w_b. grad_a = -grad_b and grad_wa follows from
// rotation invariance, so a force pair built from it conserves momentum and angular momentum exactly.
// In the containment fallback (chord = 0) it is the plain normal at the centroid.
struct DepthGradient {
  Vec2 grad_a{0.0, 0.0}, grad_b{0.0, 0.0};  // [-]
  double grad_wa = 0.0, grad_wb = 0.0;      // [m]
};
// `c` must come from planar_overlap(..., with_gradient = true).
DepthGradient depth_gradient(const PlanarContact& c, const Vec2& x_a, const Vec2& x_b);

// A lower bound of the distance between two convex polygons [m]: the largest separation along the outward normals
// of their edges (separating axes). Exact when the closest features are a vertex and an edge; <= 0 when they
// overlap or touch. `a`, `b` as for planar_overlap.
double separation_lower_bound(std::span<const Vec2> a, std::span<const Vec2> b);

// The combinatorial shape of an overlap whose boundaries cross exactly twice (the usual contact of two floes):
// going counter-clockwise round the overlap polygon, A's boundary runs inside B from the crossing X2 on A's edge
// a_first, through A's vertices a_first + 1 ... a_last, to the crossing X1 on A's edge a_last, where B's boundary
// takes over, on B's edge b_first, and runs through B's vertices b_first ... b_last - 1 to X2 on B's edge b_last.
// A's edge i runs from a[i] to a[i + 1]; B's edge j from b[j - 1] to b[j]. a_first < 0: none (a new pair, or an
// overlap of another shape: containment, four or more crossings).
// For a pair found apart: an edge whose line has all of the other polygon outside it (b_apart: an edge of B, with
// A outside; a_apart: an edge of A, with B outside; edge j runs from vertex j - 1 to vertex j; -1: none), which the
// next call tests first.
struct OverlapTopology {
  std::int8_t a_first = -1, a_last = -1, b_first = -1, b_last = -1;
  std::int8_t a_apart = -1, b_apart = -1;
  bool reused = false;  // set by planar_overlap: whether this call's answer came from what was passed in
  bool known() const { return a_first >= 0; }
};
static_assert(kMaxPolygonVertices <= 127, "OverlapTopology holds edge indices in int8");

// A convex polygon's edges as lines, for OverlapTerms::foundation: edge i runs from vertex i to vertex i + 1 (the
// last to vertex 0), (nx[i], ny[i]) is its unit inward normal m_i and offset[i] = m_i·(vertex i - ref), so that
// m_i·(x - ref) - offset[i] is the distance of x inside the edge's line [m]. A World keeps them per body beside its
// world-frame vertices (ref its first vertex), so that each pair does not compute them again; stored as separate
// arrays, so that a pair tests all of a polygon's edges at once (vectorised).
struct EdgeLines {
  const double* nx = nullptr;      // [-]
  const double* ny = nullptr;      // [-]
  const double* offset = nullptr;  // [m]
  Vec2 ref{0.0, 0.0};              // [m]
};
// The lines of the polygon `v` about ref = v[0] into nx, ny, offset [0..n).
void edge_lines(std::span<const Vec2> v, double* nx, double* ny, double* offset);

// `a`, `b`: world-frame vertices, counter-clockwise, strictly convex, at most kMaxPolygonVertices each.
// Returns false when the interiors do not overlap; touching (zero overlap area) counts as no contact.
// `with_gradient`: also fill moment, ga, gb, ha, hb (30-50 ns more per overlapping pair; only the gradient force
// model and depth_gradient() need them; otherwise they are left zero).
//
// `topology` (optional, in and out): a pair's overlap changes its shape rarely from one step to the next, so the
// caller may keep the topology this function returns and pass it back the next step. A known topology is first
// checked against the current vertices - both crossings strictly inside their edges, every vertex of both chains
// strictly inside the other polygon (then the two chains bound A ∩ B exactly: docs/model.md) - and the overlap is
// built from it in a few operations instead of clipping A by every edge of B. When the check fails, or none is
// known, A is clipped and the topology read off the result. Either way a two-crossing overlap is built from its
// topology by the same arithmetic, so the result does not depend on what was passed in (bit for bit: restarts and
// thread counts see the same contacts whatever the callers kept). Likewise a pair found apart keeps an edge of
// either polygon that shows it (a_apart, b_apart): the next call first tests whether the other polygon still lies
// wholly outside that edge's line, by a margin, and returns false at once (the clipping would reject it too). On
// return: the topology of this overlap, or unknown
// (no contact, with the separating edge where one was seen, or another shape).
// `lines_a`, `lines_b` (optional, OverlapTerms::foundation only): the polygons' edge lines, else computed here.
bool planar_overlap(std::span<const Vec2> a, std::span<const Vec2> b, PlanarContact& out, OverlapTerms terms,
                    OverlapTopology* topology = nullptr, const EdgeLines* lines_a = nullptr,
                    const EdgeLines* lines_b = nullptr);
inline bool planar_overlap(std::span<const Vec2> a, std::span<const Vec2> b, PlanarContact& out,
                           bool with_gradient = false, OverlapTopology* topology = nullptr) {
  return planar_overlap(a, b, out, with_gradient ? OverlapTerms::depth_gradient : OverlapTerms::basic, topology);
}

}  // namespace polyfloe::contact
