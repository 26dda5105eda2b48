// Exact separating-axis narrow phase for two convex polyhedra: the penetration depth is the least overlap of the
// two projections over every candidate axis (the face normals of both bodies and the cross products of their edge
// directions: the faces of the Minkowski difference), so depth and normal are exact to round-off, with no iteration
// and no failure mode. The reference for the libccd methods (narrow_phase_ccd.h) in the failure map.
//
// The contact point is the witness of that axis, the point where the potential W(depth) acts so that the force
// pair is exactly its gradient (energy-consistent):
//   face axis       the deepest vertex (vertices) of the other body, lifted half the depth onto the face
//   edge x edge     the midpoint of the closest points of the two supporting edges
// The depth is continuous as the minimising axis changes, so W(depth) is a continuous potential.
#pragma once

#include <span>

#include "geometry/polyhedron.h"

namespace polyfloe::contact {

using geometry::Mat3;
using geometry::Vec3;

enum class SatFeature : unsigned char { face_a, face_b, edge_edge };

struct SatContact {
  bool hit = false;            // depth > 0
  double depth = 0.0;          // [m]
  Vec3 normal{0.0, 0.0, 1.0};  // unit, from A to B
  Vec3 point{0.0, 0.0, 0.0};   // witness point [m]
  SatFeature feature = SatFeature::face_a;
  int axes = 0;  // candidate axes tested [-]
};

// `rot_*`: body-to-world rotations; `world_*`: world-frame vertices in the shapes' order; `centre_*`: centroids.
SatContact sat_penetration(const geometry::ConvexPolyhedron& a, const Mat3& rot_a, std::span<const Vec3> world_a,
                           const Vec3& centre_a, const geometry::ConvexPolyhedron& b, const Mat3& rot_b,
                           std::span<const Vec3> world_b, const Vec3& centre_b);

// The least overlap over the face axes of both bodies alone (no edge x edge axes) [m]; <= 0: separated. An upper
// bound of the penetration depth, and equal to it for two prisms extruded along one axis (level floes), whose
// Minkowski difference has only such faces. Checks another method's depth: one deeper than this is not the
// minimum translation.
double least_face_overlap(const geometry::ConvexPolyhedron& a, const Mat3& rot_a, std::span<const Vec3> world_a,
                          const geometry::ConvexPolyhedron& b, const Mat3& rot_b, std::span<const Vec3> world_b);

}  // namespace polyfloe::contact
