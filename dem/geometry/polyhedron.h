// Convex polyhedra for spatial (6-DOF) bodies: prisms (a floe polygon extruded between two levels) and boxes.
//
// A ConvexPolyhedron is validated once and immutable: vertices in the body frame with the centre of volume at the
// origin, faces as counter-clockwise (seen from outside) vertex loops with outward unit normals. Its mass
// properties per unit density (volume, inertia tensor about the centroid) come from the divergence theorem.
#pragma once

#include <span>
#include <utility>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>  // cross products

#include "geometry/polygon.h"

namespace polyfloe::geometry {

using Vec3 = Eigen::Vector3d;
using Mat3 = Eigen::Matrix3d;

struct PolyhedronFace {
  std::vector<int> loop;       // vertex indices, counter-clockwise seen from outside
  Vec3 normal{0.0, 0.0, 1.0};  // outward unit normal
  double offset = 0.0;         // plane: normal . x = offset [m]
};

class ConvexPolyhedron {
 public:
  // The polygon (body frame, recentred) extruded from z = -h/2 to z = +h/2: a floe of thickness h [m].
  static ConvexPolyhedron prism(const ConvexPolygon& base, double thickness);
  // Box of edge lengths (lx, ly, lz) [m], centred, edges along the axes.
  static ConvexPolyhedron box(const Vec3& size);

  const std::vector<Vec3>& vertices() const { return vertices_; }
  const std::vector<PolyhedronFace>& faces() const { return faces_; }
  // Each edge once, as a pair of vertex indices (lower first).
  const std::vector<std::pair<int, int>>& edges() const { return edges_; }
  // Unit edge directions, one per set of parallel edges (the separating-axis test's edge x edge candidates).
  const std::vector<Vec3>& edge_directions() const { return edge_directions_; }
  double volume() const { return volume_; }                   // [m^3]
  const Mat3& unit_inertia() const { return unit_inertia_; }  // inertia tensor about the centroid / density [m^5]
  double circumradius() const { return circumradius_; }       // max vertex distance from the centroid [m]
  // Radius of the sphere of equal volume [m] (the Hertz contact radius of a spatial body).
  double equivalent_radius() const;

 private:
  void finish();  // recentres, computes normals, mass properties; throws GeometryError if not a closed convex solid
  std::vector<Vec3> vertices_;
  std::vector<PolyhedronFace> faces_;
  std::vector<std::pair<int, int>> edges_;
  std::vector<Vec3> edge_directions_;
  double volume_ = 0.0;
  Mat3 unit_inertia_ = Mat3::Zero();
  double circumradius_ = 0.0;
};

// Volume and centre of the part of a convex polyhedron (world-frame vertices `v`, faces of `shape`) below the plane
// z = level: the displaced water of a floating body. Faces are clipped at the plane; the cap on the plane adds
// nothing to either integral (divergence theorem with x.n = 0 ... see polyhedron.cpp). Zero volume above water.
struct SubmergedPart {
  double volume = 0.0;           // [m^3]
  Vec3 centroid{0.0, 0.0, 0.0};  // centre of buoyancy [m]
};
SubmergedPart submerged_part(const ConvexPolyhedron& shape, std::span<const Vec3> world_vertices, double level);

}  // namespace polyfloe::geometry
