// Convex polygons and the prisms made by extruding them (a floe of thickness h).
//
// A ConvexPolygon is validated once and is immutable afterwards: at least 3 vertices, all finite, no repeated
// points, counter-clockwise, strictly convex, of a size in [1e-60, 1e60] m. Its vertices are stored in the body
// frame, with the area centroid at the origin, so a body's position is its centre of mass.
#pragma once

#include <span>
#include <stdexcept>
#include <string>
#include <vector>

#include "geometry/vec2.h"

namespace polyfloe::geometry {

class GeometryError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct PolygonProperties {
  double area = 0.0;          // signed area, > 0 for counter-clockwise [m^2]
  Vec2 centroid{0.0, 0.0};    // area centroid [m]
  double perimeter = 0.0;     // [m]
  double polar_moment = 0.0;  // integral of |r - centroid|^2 dA [m^4]
};

// Properties of a simple polygon given by its vertices in order (no validation).
PolygonProperties polygon_properties(std::span<const Vec2> v);

// Circularity C = D_s / D_p (paper Eq. 17): perimeter of the area-equivalent circle over the polygon's perimeter.
double circularity(double area, double perimeter);

// Returns an empty string if `v` is a valid strictly convex counter-clockwise polygon, else a message that says
// what is wrong (and which vertex). Tolerances are relative to the polygon's size. The size (the largest coordinate
// difference from the first vertex) must lie in [kMinPolygonSize, kMaxPolygonSize], where the area and the polar
// moment (~ size^4) are normal, finite doubles.
inline constexpr double kMinPolygonSize = 1e-60;  // [m]
inline constexpr double kMaxPolygonSize = 1e60;   // [m]
std::string convexity_error(std::span<const Vec2> v);

class ConvexPolygon {
 public:
  // Validates and recentres on the centroid; throws GeometryError with the reason. `offset` (if given) receives the
  // centroid of the input vertices, i.e. where the body frame's origin sits in the input frame.
  static ConvexPolygon from_vertices(std::span<const Vec2> vertices, Vec2* offset = nullptr);
  // Regular n-gon with the given circumradius [m], one vertex on the +x axis.
  static ConvexPolygon regular(int sides, double circumradius);
  // Axis-aligned rectangle of width x height [m].
  static ConvexPolygon rectangle(double width, double height);

  const std::vector<Vec2>& vertices() const { return vertices_; }
  int size() const { return static_cast<int>(vertices_.size()); }
  double area() const { return area_; }                  // [m^2]
  double perimeter() const { return perimeter_; }        // [m]
  double polar_moment() const { return polar_moment_; }  // integral of r^2 dA about the centroid [m^4]
  double circumradius() const { return circumradius_; }  // max vertex distance from the centroid [m]
  double equivalent_radius() const;                      // sqrt(area / pi) [m]
  double circularity() const { return geometry::circularity(area_, perimeter_); }

 private:
  std::vector<Vec2> vertices_;
  double area_ = 0.0;
  double perimeter_ = 0.0;
  double polar_moment_ = 0.0;
  double circumradius_ = 0.0;
};

// Mass properties of a prism: the polygon extruded to thickness h with uniform density.
struct PrismMass {
  double mass = 0.0;       // [kg]
  double inertia_z = 0.0;  // moment of inertia about the vertical axis through the centroid [kg m^2]
};
PrismMass prism_mass(const ConvexPolygon& shape, double thickness, double density);

// Floating draft of a freely floating prism: h * rho_ice / rho_water [m].
double floating_draft(double thickness, double density_ice, double density_water);

}  // namespace polyfloe::geometry
