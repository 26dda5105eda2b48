// Contact manifold between two convex polyhedra, from a contact normal (GJK-EPA or MPR give one point; a face lying
// on a face needs several, or the contact point wanders over the face and its force makes a spurious torque).
//
// Face clipping: the reference face is the face of A whose outward normal is closest to n (or of B closest to -n,
// whichever is closer); the incident face is the face of the other body most opposed to the reference normal. The
// incident face is clipped by the side planes of the reference face; the clipped points below the reference plane are
// the manifold, with their depths below it. More than kMaxManifoldPoints are reduced to the deepest point, the point
// farthest from it, and the two points that span the largest area with them.
// When no face is within kMaxFaceAngle of the normal (edge-edge contacts) the manifold is empty and the caller keeps
// the narrow phase's single point.
#pragma once

#include <array>
#include <span>

#include "geometry/polyhedron.h"

namespace polyfloe::contact {

using geometry::Mat3;
using geometry::Vec3;

inline constexpr int kMaxManifoldPoints = 4;
inline constexpr double kMaxFaceAngle = 0.1745329251994330;  // 10 degrees [rad]

struct ContactManifold {
  int count = 0;
  Vec3 normal{0.0, 0.0, 1.0};                       // unit, from A to B: the reference face's normal (sign for A -> B)
  std::array<Vec3, kMaxManifoldPoints> points{};    // midway between the reference plane and the incident point [m]
  std::array<double, kMaxManifoldPoints> depths{};  // below the reference plane, > 0 [m]
  double max_depth() const;
  // The depth-weighted centre of the points: where one equivalent normal force acts (no torque from a face lying
  // flat on a face) [m].
  Vec3 centre() const;
};

// `rot_a`, `rot_b`: body-to-world rotations; `world_a`, `world_b`: world-frame vertices (same order as the shapes').
// `normal`: unit, from A to B.
ContactManifold clip_manifold(const geometry::ConvexPolyhedron& a, const Mat3& rot_a, std::span<const Vec3> world_a,
                              const geometry::ConvexPolyhedron& b, const Mat3& rot_b, std::span<const Vec3> world_b,
                              const Vec3& normal);

}  // namespace polyfloe::contact
