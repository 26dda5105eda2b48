// Helpers shared by tests: random convex polygons and a brute-force polygon overlap reference.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <memory>
#include <numbers>
#include <random>
#include <vector>

#include "dynamics/world.h"
#include "geometry/polygon.h"

namespace polyfloe::tsupport {

using geometry::Vec2;

// Random strictly convex polygon: `n` points at sorted random angles on an ellipse with semi-axes (rx, ry),
// counter-clockwise, centred near the origin.
inline std::vector<Vec2> random_convex(std::mt19937_64& rng, int n, double rx, double ry) {
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (;;) {
    std::vector<double> ang(static_cast<std::size_t>(n));
    for (double& a : ang) a = 2.0 * std::numbers::pi * u(rng);
    std::sort(ang.begin(), ang.end());
    std::vector<Vec2> v;
    for (double a : ang) v.emplace_back(rx * std::cos(a), ry * std::sin(a));
    if (geometry::convexity_error(v).empty()) return v;
  }
}

inline std::vector<Vec2> transform(const std::vector<Vec2>& v, double yaw, const Vec2& t) {
  const double c = std::cos(yaw), s = std::sin(yaw);
  std::vector<Vec2> out;
  for (const Vec2& p : v) out.push_back(t + geometry::rotate(p, c, s));
  return out;
}

// Convex hull (Andrew's monotone chain), counter-clockwise, without collinear points.
inline std::vector<Vec2> convex_hull(std::vector<Vec2> pts) {
  std::sort(pts.begin(), pts.end(),
            [](const Vec2& a, const Vec2& b) { return a.x() < b.x() || (a.x() == b.x() && a.y() < b.y()); });
  if (pts.size() < 3) return pts;
  std::vector<Vec2> h(2 * pts.size());
  std::size_t k = 0;
  for (std::size_t i = 0; i < pts.size(); ++i) {
    while (k >= 2 && geometry::cross(h[k - 1] - h[k - 2], pts[i] - h[k - 2]) <= 0) --k;
    h[k++] = pts[i];
  }
  for (std::size_t i = pts.size() - 1, t = k + 1; i > 0; --i) {
    while (k >= t && geometry::cross(h[k - 1] - h[k - 2], pts[i - 1] - h[k - 2]) <= 0) --k;
    h[k++] = pts[i - 1];
  }
  h.resize(k - 1);
  return h;
}

inline bool inside_convex(const std::vector<Vec2>& poly, const Vec2& p, double tol) {
  const std::size_t n = poly.size();
  for (std::size_t i = 0; i < n; ++i) {
    const Vec2 e = poly[(i + 1) % n] - poly[i];
    if (geometry::cross(e, p - poly[i]) < -tol * e.norm()) return false;
  }
  return true;
}

// Overlap polygon of A and B by brute force: vertices of each inside the other plus all edge crossings, hulled.
inline std::vector<Vec2> brute_overlap(const std::vector<Vec2>& a, const std::vector<Vec2>& b) {
  std::vector<Vec2> pts;
  for (const Vec2& p : a)
    if (inside_convex(b, p, 1e-12)) pts.push_back(p);
  for (const Vec2& p : b)
    if (inside_convex(a, p, 1e-12)) pts.push_back(p);
  for (std::size_t i = 0; i < a.size(); ++i) {
    const Vec2 p = a[i], r = a[(i + 1) % a.size()] - p;
    for (std::size_t j = 0; j < b.size(); ++j) {
      const Vec2 q = b[j], s = b[(j + 1) % b.size()] - q;
      const double den = geometry::cross(r, s);
      if (den == 0.0) continue;
      const double t = geometry::cross(q - p, s) / den, u = geometry::cross(q - p, r) / den;
      if (t >= 0.0 && t <= 1.0 && u >= 0.0 && u <= 1.0) pts.push_back(p + t * r);
    }
  }
  return convex_hull(pts);
}

inline double brute_area(const std::vector<Vec2>& a, const std::vector<Vec2>& b) {
  const auto h = brute_overlap(a, b);
  return h.size() < 3 ? 0.0 : geometry::polygon_properties(h).area;
}

inline std::shared_ptr<const geometry::ConvexPolygon> shape_of(const std::vector<Vec2>& v) {
  return std::make_shared<const geometry::ConvexPolygon>(geometry::ConvexPolygon::from_vertices(v));
}

}  // namespace polyfloe::tsupport
