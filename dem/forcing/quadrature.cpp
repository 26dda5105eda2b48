#include "forcing/quadrature.h"

#include <array>

namespace polyfloe::forcing {

std::string_view to_string(Quadrature q) {
  switch (q) {
    case Quadrature::centroid: return "centroid";
    case Quadrature::degree1: return "degree1";
    case Quadrature::degree2: return "degree2";
    case Quadrature::degree4: return "degree4";
    case Quadrature::degree5: return "degree5";
  }
  return "?";
}

namespace {

// A symmetric triangle rule: barycentric coordinates and weights (fractions of the triangle's area).
struct TrianglePoint {
  double l1, l2, l3, w;
};

// Dunavant's 6-point rule (degree 4), Int. J. Numer. Meth. Eng. 21 (1985) 1129-1148, table entry p = 4.
constexpr double kA4 = 0.445948490915965, kB4 = 0.108103018168070, kW4a = 0.223381589678011;
constexpr double kC4 = 0.091576213509771, kD4 = 0.816847572980459, kW4b = 0.109951743655322;
constexpr std::array<TrianglePoint, 6> kDegree4{{
    {kB4, kA4, kA4, kW4a},
    {kA4, kB4, kA4, kW4a},
    {kA4, kA4, kB4, kW4a},
    {kD4, kC4, kC4, kW4b},
    {kC4, kD4, kC4, kW4b},
    {kC4, kC4, kD4, kW4b},
}};

// Radon's 7-point rule (degree 5).
constexpr double kA5 = 0.470142064105115, kB5 = 0.059715871789770, kW5a = 0.132394152788506;
constexpr double kC5 = 0.101286507323456, kD5 = 0.797426985353087, kW5b = 0.125939180544827;
constexpr std::array<TrianglePoint, 7> kDegree5{{
    {1.0 / 3.0, 1.0 / 3.0, 1.0 / 3.0, 0.225},
    {kB5, kA5, kA5, kW5a},
    {kA5, kB5, kA5, kW5a},
    {kA5, kA5, kB5, kW5a},
    {kD5, kC5, kC5, kW5b},
    {kC5, kD5, kC5, kW5b},
    {kC5, kC5, kD5, kW5b},
}};

std::span<const TrianglePoint> triangle_rule(Quadrature q) {
  static constexpr std::array<TrianglePoint, 1> kDegree1{{{1.0 / 3.0, 1.0 / 3.0, 1.0 / 3.0, 1.0}}};
  switch (q) {
    case Quadrature::centroid:
    case Quadrature::degree1:
    case Quadrature::degree2: return kDegree1;  // (degree2 is built apart: shared edge midpoints)
    case Quadrature::degree4: return kDegree4;
    case Quadrature::degree5: return kDegree5;
  }
  return kDegree1;
}

}  // namespace

int quadrature_points(Quadrature q, int n) {
  if (q == Quadrature::centroid) return 1;
  if (q == Quadrature::degree2) return 2 * n;
  return n * static_cast<int>(triangle_rule(q).size());
}

void polygon_quadrature(std::span<const Vec2> v, Quadrature q, std::vector<QuadraturePoint>& out) {
  const std::size_t n = v.size();
  // Area and centroid from the shoelace triangles about v[0]'s frame origin, shifted to v[0] for rounding.
  double area2 = 0.0;
  Vec2 c{0.0, 0.0};
  for (std::size_t i = 0; i < n; ++i) {
    const Vec2 a = v[i] - v[0], b = v[(i + 1) % n] - v[0];
    const double w = geometry::cross(a, b);
    area2 += w;
    c += w * (a + b);
  }
  const double area = 0.5 * area2;
  c = v[0] + c / (3.0 * area2);
  if (q == Quadrature::centroid) {
    out.push_back({c, area});
    return;
  }
  if (q == Quadrature::degree2) {
    // The edge-midpoint rule on each fan triangle (weight 1/3 at each edge's midpoint, exact for degree 2): the
    // midpoints of the spokes are shared by neighbouring triangles, so the n-gon needs 2n points, not 3n.
    for (std::size_t i = 0; i < n; ++i) {
      const Vec2& a = v[i];
      const Vec2& b = v[(i + 1) % n];
      const Vec2& prev = v[(i + n - 1) % n];
      const double tri = 0.5 * geometry::cross(a - c, b - c), tri_prev = 0.5 * geometry::cross(prev - c, a - c);
      out.push_back({0.5 * (c + a), (tri_prev + tri) / 3.0});  // spoke c-a, shared by triangles i-1 and i
      out.push_back({0.5 * (a + b), tri / 3.0});               // outer edge a-b
    }
    return;
  }
  const std::span<const TrianglePoint> rule = triangle_rule(q);
  for (std::size_t i = 0; i < n; ++i) {
    const Vec2& a = v[i];
    const Vec2& b = v[(i + 1) % n];
    const double tri = 0.5 * geometry::cross(a - c, b - c);
    for (const TrianglePoint& p : rule) out.push_back({p.l1 * c + p.l2 * a + p.l3 * b, p.w * tri});
  }
}

}  // namespace polyfloe::forcing
