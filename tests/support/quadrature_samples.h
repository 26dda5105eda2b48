// Quadrature samples of a floe's bottom as world-frame levers from its centre, and a refined reference rule: shared
// by the drift benchmarks (bench_drift: the rules in analytic fields; bench_field_sampling: in OpenFOAM fields).
#pragma once

#include <array>
#include <vector>

#include "forcing/quadrature.h"
#include "geometry/vec2.h"

namespace polyfloe::tsupport {

struct Samples {
  std::vector<double> rx, ry, w;  // lever from the centre [m], area carried [m^2]
};

// Appends the rule `q` on polygon `poly`, levers from `centre`.
inline void add_rule(const std::vector<geometry::Vec2>& poly, const geometry::Vec2& centre, forcing::Quadrature q,
                     Samples& s) {
  std::vector<forcing::QuadraturePoint> pts;
  forcing::polygon_quadrature(poly, q, pts);
  for (const auto& p : pts) {
    s.rx.push_back(p.point.x() - centre.x());
    s.ry.push_back(p.point.y() - centre.y());
    s.w.push_back(p.weight);
  }
}

// The degree-5 rule on each fan triangle (from `centre`) of the world-frame polygon `v`, cut into 4^levels pieces.
inline Samples refined(const std::vector<geometry::Vec2>& v, const geometry::Vec2& centre, int levels) {
  using geometry::Vec2;
  std::vector<std::array<Vec2, 3>> tris;
  for (std::size_t i = 0; i < v.size(); ++i) tris.push_back({centre, v[i], v[(i + 1) % v.size()]});
  for (int l = 0; l < levels; ++l) {
    std::vector<std::array<Vec2, 3>> next;
    for (const auto& t : tris) {
      const Vec2 a = 0.5 * (t[0] + t[1]), b = 0.5 * (t[1] + t[2]), c = 0.5 * (t[2] + t[0]);
      next.push_back({t[0], a, c});
      next.push_back({a, t[1], b});
      next.push_back({c, b, t[2]});
      next.push_back({a, b, c});
    }
    tris.swap(next);
  }
  Samples s;
  for (const auto& t : tris) add_rule({t[0], t[1], t[2]}, centre, forcing::Quadrature::degree5, s);
  return s;
}

}  // namespace polyfloe::tsupport
