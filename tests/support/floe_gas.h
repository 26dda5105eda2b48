// A gas of random convex floes for the conservation tests: placed on a jittered grid without overlapping, with
// random velocities and spins.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "contact/narrow_phase_planar.h"
#include "dynamics/world.h"
#include "test_support.h"

namespace polyfloe::tsupport {

struct Field {
  std::vector<dynamics::BodyDesc> bodies;
  double area_fraction = 0.0;  // floe area over the area of the placement grid
};

// The floes' shapes: corners, size across [m] and aspect (minor / major axis of the ellipse the corners lie on).
struct FloeShapes {
  int corners_min = 5, corners_max = 12;
  double size_min = 5.0, size_max = 15.0;
  double aspect_min = 0.6, aspect_max = 1.0;
};

inline std::vector<Vec2> scaled(const std::vector<Vec2>& v, double f) {
  std::vector<Vec2> out;
  for (const Vec2& p : v) out.push_back(f * p);
  return out;
}

// `n` random convex floes (`shapes`, h = 1 m) on a jittered square grid of spacing `spacing` centred on the origin,
// none overlapping (checked with a 3 % margin), with random velocities up to v_max and angular velocities up to
// w_max. A floe that does not fit at its site is shrunk (not below size_min) or re-jittered.
inline Field make_field(std::uint64_t seed, int n, double spacing, double v_max, double w_max,
                        const FloeShapes& shapes = {}) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  const int nx = static_cast<int>(std::ceil(std::sqrt(static_cast<double>(n))));
  const int ny = (n + nx - 1) / nx;
  Field f;
  std::vector<std::vector<Vec2>> placed;  // world vertices, inflated by 3 %, of the floes placed so far
  std::vector<Vec2> centres;
  std::vector<double> radii;
  double area = 0.0;
  for (int k = 0; k < n; ++k) {
    const Vec2 site{(k % nx - 0.5 * (nx - 1)) * spacing, (k / nx - 0.5 * (ny - 1)) * spacing};
    const int nv = shapes.corners_min + static_cast<int>(u(rng) * (shapes.corners_max - shapes.corners_min + 1));
    double size = shapes.size_min + (shapes.size_max - shapes.size_min) * u(rng);
    const double aspect = shapes.aspect_min + (shapes.aspect_max - shapes.aspect_min) * u(rng);
    const double yaw = 2.0 * std::numbers::pi * u(rng);
    const std::vector<Vec2> unit = random_convex(rng, nv, 0.5, 0.5 * aspect);
    bool ok = false;
    for (int attempt = 0; attempt < 500 && !ok; ++attempt) {
      if (attempt % 5 == 4) size = std::max(shapes.size_min, 0.9 * size);
      const Vec2 centre = site + Vec2{(u(rng) - 0.5) * 0.3 * spacing, (u(rng) - 0.5) * 0.3 * spacing};
      const auto local = scaled(unit, size);
      const auto shape = shape_of(local);
      const auto world = transform(scaled(shape->vertices(), 1.03), yaw, centre);
      const double r = 1.03 * shape->circumradius();
      ok = true;
      for (std::size_t j = 0; j < placed.size() && ok; ++j) {
        if ((centres[j] - centre).norm() > r + radii[j]) continue;
        contact::PlanarContact c;
        if (contact::planar_overlap(world, placed[j], c)) ok = false;
      }
      if (!ok) continue;
      placed.push_back(world);
      centres.push_back(centre);
      radii.push_back(r);
      area += shape->area();
      const double va = 2.0 * std::numbers::pi * u(rng), vm = v_max * std::sqrt(u(rng));
      f.bodies.push_back({.id = static_cast<dynamics::BodyId>(100 + 7 * k),
                          .shape = shape,
                          .position = centre,
                          .yaw = yaw,
                          .velocity = {vm * std::cos(va), vm * std::sin(va)},
                          .angular_velocity = w_max * (2.0 * u(rng) - 1.0),
                          .thickness = 1.0});
    }
    EXPECT_TRUE(ok) << "floe " << k << " could not be placed";
  }
  f.area_fraction = area / (nx * spacing * ny * spacing);
  return f;
}

}  // namespace polyfloe::tsupport
