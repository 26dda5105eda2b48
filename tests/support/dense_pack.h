// A jammed pack of ~12-vertex floes built geometrically (no DEM compaction), shared by the step and stability
// benchmarks: see bench_step.cpp's header for how it is built.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <random>
#include <vector>

#include "dynamics/world.h"
#include "test_support.h"

namespace polyfloe::tsupport {

struct PackSpec {
  double spacing = 9.0;  // lattice spacing s [m]
  double jitter = 0.03;  // generator jitter, fraction of s
  double rho = 0.56;     // circumradius of the 10-gon, fraction of s
  int corners = 10;      // corners of that polygon
  double eps = 2e-4;     // relative scaling about the generator (> 0: neighbours overlap)
  double speed = 0.0;    // random initial speed, uniform in [0, speed] in a random direction [m/s]
  bool walls = true;
  bool shuffle = true;  // body order unrelated to position, as in a generated field (largest floe first)
};

struct Pack {
  std::vector<dynamics::BodyDesc> bodies;  // floes, then walls
  int floes = 0;
  double area_fraction = 0.0;
  double mean_vertices = 0.0;
};

// Keeps the part of `poly` where n.(x - p) <= 0.
inline std::vector<Vec2> clip(const std::vector<Vec2>& poly, const Vec2& n, const Vec2& p) {
  std::vector<Vec2> out;
  const std::size_t m = poly.size();
  for (std::size_t k = 0; k < m; ++k) {
    const Vec2& a = poly[k];
    const Vec2& b = poly[(k + 1) % m];
    const double sa = n.dot(a - p), sb = n.dot(b - p);
    if (sa <= 0.0) out.push_back(a);
    if ((sa <= 0.0) != (sb <= 0.0)) out.push_back(a + sa / (sa - sb) * (b - a));
  }
  return out;
}

// Drops repeated and collinear vertices left by clipping (tolerances relative to the size).
inline std::vector<Vec2> clean(std::vector<Vec2> v, double size) {
  bool changed = true;
  while (changed && v.size() >= 3) {
    changed = false;
    for (std::size_t k = 0; k < v.size() && v.size() >= 3; ++k) {
      const std::size_t n = v.size();
      const Vec2& a = v[(k + n - 1) % n];
      const Vec2& b = v[k];
      const Vec2& c = v[(k + 1) % n];
      if ((b - a).norm() < 1e-6 * size || geometry::cross(b - a, c - b) < 1e-7 * size * size) {
        v.erase(v.begin() + static_cast<std::ptrdiff_t>(k));
        changed = true;
      }
    }
  }
  return v;
}

inline Pack make_pack(int n_target, const PackSpec& ps, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  const double s = ps.spacing;
  const int nx = std::max(2, static_cast<int>(std::lround(std::sqrt(static_cast<double>(n_target)))));
  const int ny = std::max(2, static_cast<int>(std::lround(static_cast<double>(n_target) / nx)));
  const double lx = nx * s, ly = ny * s;
  std::vector<Vec2> gen(static_cast<std::size_t>(nx) * ny);
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i)
      gen[static_cast<std::size_t>(j) * nx + i] =
          Vec2{(i + 0.5) * s, (j + 0.5) * s} + ps.jitter * s * Vec2{2.0 * u(rng) - 1.0, 2.0 * u(rng) - 1.0};

  std::vector<std::vector<Vec2>> polys;
  for (int j = 0; j < ny; ++j) {
    for (int i = 0; i < nx; ++i) {
      const Vec2 g = gen[static_cast<std::size_t>(j) * nx + i];
      std::vector<Vec2> poly;
      const double phase = 2.0 * std::numbers::pi * u(rng);
      for (int k = 0; k < ps.corners; ++k) {
        const double a = phase + 2.0 * std::numbers::pi * (k + 0.35 * (u(rng) - 0.5)) / ps.corners;
        poly.push_back(g + ps.rho * s * Vec2{std::cos(a), std::sin(a)});
      }
      for (int dj = -2; dj <= 2; ++dj)
        for (int di = -2; di <= 2; ++di) {
          const int ii = i + di, jj = j + dj;
          if ((di == 0 && dj == 0) || ii < 0 || jj < 0 || ii >= nx || jj >= ny) continue;
          const Vec2 h = gen[static_cast<std::size_t>(jj) * nx + ii];
          poly = clip(poly, h - g, 0.5 * (g + h));
        }
      poly = clip(poly, {-1.0, 0.0}, {0.0, 0.0});
      poly = clip(poly, {1.0, 0.0}, {lx, 0.0});
      poly = clip(poly, {0.0, -1.0}, {0.0, 0.0});
      poly = clip(poly, {0.0, 1.0}, {0.0, ly});
      for (Vec2& p : poly) p = g + (1.0 + ps.eps) * (p - g);
      poly = clean(std::move(poly), s);
      if (poly.size() < 3 || !geometry::convexity_error(poly).empty()) continue;  // never seen; skip rather than fail
      polys.push_back(std::move(poly));
    }
  }
  // Shuffled before the shapes are allocated, so that shapes lie in memory in body order, as in a real field.
  if (ps.shuffle) std::shuffle(polys.begin(), polys.end(), rng);

  Pack pack;
  double ice_area = 0.0, vertices = 0.0;
  dynamics::BodyId id = 1;
  for (const auto& poly : polys) {
    dynamics::BodyDesc d;
    d.id = id++;
    Vec2 centroid;
    d.shape = std::make_shared<const geometry::ConvexPolygon>(geometry::ConvexPolygon::from_vertices(poly, &centroid));
    d.position = centroid;
    d.thickness = 1.0;
    const double ang = 2.0 * std::numbers::pi * u(rng);
    d.velocity = ps.speed * u(rng) * Vec2{std::cos(ang), std::sin(ang)};
    ice_area += d.shape->area();
    vertices += d.shape->size();
    pack.bodies.push_back(std::move(d));
  }
  pack.floes = static_cast<int>(pack.bodies.size());
  pack.area_fraction = ice_area / (lx * ly);
  pack.mean_vertices = vertices / pack.floes;
  if (ps.walls) {
    const double t = 20.0;  // wall thickness [m]
    auto wall = [&](double x0, double y0, double x1, double y1) {
      dynamics::BodyDesc d;
      d.id = id++;
      d.motion = dynamics::Motion::fixed;
      d.shape = tsupport::shape_of({{x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}});
      d.position = {0.5 * (x0 + x1), 0.5 * (y0 + y1)};
      d.thickness = 1.0;
      pack.bodies.push_back(std::move(d));
    };
    wall(-t, -t, lx + t, 0.0);     // bottom
    wall(-t, ly, lx + t, ly + t);  // top
    wall(-t, 0.0, 0.0, ly);        // left
    wall(lx, 0.0, lx + t, ly);     // right
  }
  return pack;
}

}  // namespace polyfloe::tsupport
