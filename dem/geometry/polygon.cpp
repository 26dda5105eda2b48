#include "geometry/polygon.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <sstream>

namespace polyfloe::geometry {

PolygonProperties polygon_properties(std::span<const Vec2> v) {
  PolygonProperties p;
  const std::size_t n = v.size();
  if (n < 3) return p;
  // Shoelace sums about the first vertex to limit cancellation far from the origin.
  const Vec2 o = v[0];
  double a2 = 0.0;  // twice the area
  Vec2 c{0.0, 0.0};
  double j = 0.0;  // polar moment about o, times 12
  for (std::size_t i = 0; i < n; ++i) {
    const Vec2 p0 = v[i] - o;
    const Vec2 p1 = v[(i + 1) % n] - o;
    const double w = cross(p0, p1);
    a2 += w;
    c += w * (p0 + p1);
    j += w * (p0.squaredNorm() + p0.dot(p1) + p1.squaredNorm());
    p.perimeter += (v[(i + 1) % n] - v[i]).norm();
  }
  p.area = 0.5 * a2;
  if (a2 != 0.0) {
    const Vec2 cl = c / (3.0 * a2);
    p.centroid = o + cl;
    p.polar_moment = j / 12.0 - p.area * cl.squaredNorm();
  } else {
    p.centroid = o;
  }
  return p;
}

double circularity(double area, double perimeter) {
  if (perimeter <= 0.0) return 0.0;
  return 2.0 * std::sqrt(std::numbers::pi * area) / perimeter;
}

std::string convexity_error(std::span<const Vec2> v) {
  std::ostringstream msg;
  const std::size_t n = v.size();
  if (n < 3) {
    msg << "a polygon needs at least 3 vertices, got " << n;
    return msg.str();
  }
  for (std::size_t i = 0; i < n; ++i) {
    if (!std::isfinite(v[i].x()) || !std::isfinite(v[i].y())) {
      msg << "vertex " << i << " is not finite";
      return msg.str();
    }
  }
  double scale = 0.0;
  for (std::size_t i = 1; i < n; ++i) scale = std::max(scale, (v[i] - v[0]).lpNorm<Eigen::Infinity>());
  if (scale <= 0.0) return "all vertices coincide";
  // The polar moment grows as size^4: outside this range it (or the area, or the centroid's sums) would overflow or
  // underflow to zero, which the validation below cannot see.
  if (scale < kMinPolygonSize || scale > kMaxPolygonSize) {
    msg << "the polygon's size " << scale << " m is outside the range [" << kMinPolygonSize << ", " << kMaxPolygonSize
        << "] m";
    return msg.str();
  }
  const double len_tol = 1e-9 * scale;
  for (std::size_t i = 0; i < n; ++i) {
    for (std::size_t k = i + 1; k < n; ++k) {
      if ((v[i] - v[k]).norm() <= len_tol) {
        msg << "vertices " << i << " and " << k << " repeat the same point";
        return msg.str();
      }
    }
  }
  const PolygonProperties props = polygon_properties(v);
  if (props.area < 0.0) return "vertices are clockwise; list them counter-clockwise";
  const double turn_tol = 1e-10 * scale * scale;
  double total_turn = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    const Vec2 e0 = v[i] - v[(i + n - 1) % n];
    const Vec2 e1 = v[(i + 1) % n] - v[i];
    const double c = cross(e0, e1);
    if (c <= turn_tol) {
      msg << "not strictly convex at vertex " << i << " (" << v[i].x() << ", " << v[i].y() << ")"
          << (c < -turn_tol ? ": it turns clockwise" : ": it is collinear with its neighbours");
      return msg.str();
    }
    total_turn += std::atan2(c, e0.dot(e1));
  }
  // All left turns but winding more than once (a star) is not a simple polygon.
  if (std::abs(total_turn - 2.0 * std::numbers::pi) > 1e-6)
    return "polygon winds around more than once (self-intersecting)";
  return {};
}

ConvexPolygon ConvexPolygon::from_vertices(std::span<const Vec2> vertices, Vec2* offset) {
  if (std::string err = convexity_error(vertices); !err.empty()) throw GeometryError(err);
  const PolygonProperties props = polygon_properties(vertices);
  ConvexPolygon p;
  p.vertices_.reserve(vertices.size());
  for (const Vec2& x : vertices) p.vertices_.push_back(x - props.centroid);
  p.area_ = props.area;
  p.perimeter_ = props.perimeter;
  p.polar_moment_ = props.polar_moment;
  for (const Vec2& x : p.vertices_) p.circumradius_ = std::max(p.circumradius_, x.norm());
  if (offset) *offset = props.centroid;
  return p;
}

ConvexPolygon ConvexPolygon::regular(int sides, double circumradius) {
  if (sides < 3) throw GeometryError("a regular polygon needs at least 3 sides");
  if (!(circumradius > 0.0) || !std::isfinite(circumradius))
    throw GeometryError("circumradius must be positive and finite");
  std::vector<Vec2> v;
  v.reserve(static_cast<std::size_t>(sides));
  for (int i = 0; i < sides; ++i) {
    const double a = 2.0 * std::numbers::pi * i / sides;
    v.emplace_back(circumradius * std::cos(a), circumradius * std::sin(a));
  }
  return from_vertices(v);
}

ConvexPolygon ConvexPolygon::rectangle(double width, double height) {
  const double hx = 0.5 * width, hy = 0.5 * height;
  const Vec2 v[4] = {{-hx, -hy}, {hx, -hy}, {hx, hy}, {-hx, hy}};
  return from_vertices(v);
}

double ConvexPolygon::equivalent_radius() const { return std::sqrt(area_ / std::numbers::pi); }

PrismMass prism_mass(const ConvexPolygon& shape, double thickness, double density) {
  return {density * thickness * shape.area(), density * thickness * shape.polar_moment()};
}

double floating_draft(double thickness, double density_ice, double density_water) {
  return thickness * density_ice / density_water;
}

}  // namespace polyfloe::geometry
