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
#pragma once

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
  double chord = 0.0;     // chord length |N| [m]
};

// `a`, `b`: world-frame vertices, counter-clockwise, strictly convex, at most kMaxPolygonVertices each.
// Returns false when the interiors do not overlap; touching (zero overlap area) counts as no contact.
bool planar_overlap(std::span<const Vec2> a, std::span<const Vec2> b, PlanarContact& out);

}  // namespace polyfloe::contact
