// The elastic-foundation contact potential (contact/foundation.h) against independent references:
// - I = ∫_{A∩B} (d_A + d_B) dA by quadrature over the brute-force overlap, with d the distance to the boundary;
// - its load as the exact gradient: central differences of I in B's translation and rotation;
// - closed forms: a flat strip (I = L δ^2, load 2 L δ), round bodies (Hertz: I = 16/15 sqrt(2R) δ^2.5);
// - continuity of the load through a corner entering the other polygon, and the work-energy identity along a path.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>

#include "contact/narrow_phase_planar.h"
#include "test_support.h"

using namespace polyfloe;
using contact::OverlapTerms;
using contact::PlanarContact;
using geometry::Vec2;
using tsupport::brute_overlap;
using tsupport::random_convex;
using tsupport::transform;

namespace {

PlanarContact measure(const std::vector<Vec2>& a, const std::vector<Vec2>& b) {
  PlanarContact c;
  if (!contact::planar_overlap(a, b, c, OverlapTerms::foundation)) c = PlanarContact{};
  return c;
}

// Distance from x to the boundary of the convex counter-clockwise polygon p (x inside).
double boundary_distance(const std::vector<Vec2>& p, const Vec2& x) {
  double d = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < p.size(); ++i) {
    const Vec2 e = p[(i + 1) % p.size()] - p[i];
    d = std::min(d, geometry::cross(e, x - p[i]) / e.norm());
  }
  return d;
}

// ∫ (d_A + d_B) over the overlap: the brute-force overlap hull fanned into triangles, each split m x m ways and
// sampled at the small triangles' centroids.
double quadrature(const std::vector<Vec2>& a, const std::vector<Vec2>& b, int m = 160) {
  const auto hull = brute_overlap(a, b);
  if (hull.size() < 3) return 0.0;
  double sum = 0.0;
  for (std::size_t t = 1; t + 1 < hull.size(); ++t) {
    const Vec2 p0 = hull[0], u = (hull[t] - p0) / m, v = (hull[t + 1] - p0) / m;
    const double area = 0.5 * std::abs(geometry::cross(u, v));
    for (int i = 0; i < m; ++i)
      for (int j = 0; i + j < m; ++j) {
        const Vec2 c1 = p0 + (i + 1.0 / 3.0) * u + (j + 1.0 / 3.0) * v;
        sum += area * (boundary_distance(a, c1) + boundary_distance(b, c1));
        if (i + j + 1 < m) {
          const Vec2 c2 = p0 + (i + 2.0 / 3.0) * u + (j + 2.0 / 3.0) * v;
          sum += area * (boundary_distance(a, c2) + boundary_distance(b, c2));
        }
      }
  }
  return sum;
}

std::vector<Vec2> rectangle(double w, double h, const Vec2& centre) {
  return {centre + Vec2(-w / 2, -h / 2), centre + Vec2(w / 2, -h / 2), centre + Vec2(w / 2, h / 2),
          centre + Vec2(-w / 2, h / 2)};
}

// B turned by `angle` about `pivot`.
std::vector<Vec2> turned(const std::vector<Vec2>& b, double angle, const Vec2& pivot) {
  std::vector<Vec2> o;
  const double c = std::cos(angle), s = std::sin(angle);
  for (const Vec2& p : b) o.push_back(pivot + geometry::rotate(p - pivot, c, s));
  return o;
}

std::vector<Vec2> shifted(const std::vector<Vec2>& v, const Vec2& d) {
  std::vector<Vec2> o;
  for (const Vec2& p : v) o.push_back(p + d);
  return o;
}

}  // namespace

TEST(Foundation, FlatStripIsLDeltaSquared) {
  // A 20 m x 2 m floe pressed 0.05 m into a wide plate below it: I = L δ^2 - δ^3/3 (within δ of the floe's ends
  // its side is nearer than its bottom), the load 2 L δ - δ^2 straight up, no moment.
  const auto plate = rectangle(100.0, 10.0, {0.0, -5.0});
  const double delta = 0.05, l = 20.0;
  const auto floe = rectangle(l, 2.0, {3.0, 1.0 - delta});
  const PlanarContact c = measure(plate, floe);
  EXPECT_NEAR(c.energy, l * delta * delta - delta * delta * delta / 3.0, 1e-12 * l);
  EXPECT_NEAR(c.load.x(), 0.0, 1e-12);
  EXPECT_NEAR(c.load.y(), 2.0 * l * delta - delta * delta, 1e-12 * l);
  EXPECT_NEAR(c.load_moment, 0.0, 1e-10);
  // Tilted by φ about its centre: I = L δ^2 + φ^2 L^3 / 12 (less the ends' δ^3 terms), so the torque about the
  // centre is -φ L^3 / 6 (it turns the floe back flat). About the overlap's centroid it nearly vanishes: the
  // foundation's pressure resultant passes there.
  const double phi = 1e-3;
  const Vec2 centre(3.0, 1.0 - delta);
  const PlanarContact t = measure(plate, turned(floe, phi, centre));
  const double torque = t.load_moment + geometry::cross(t.point - centre, t.load);
  EXPECT_NEAR(torque, -phi * l * l * l / 6.0, 0.02 * phi * l * l * l / 6.0);
  EXPECT_NEAR(t.load_moment, 0.0, 0.01 * phi * l * l * l / 6.0);
}

// A convex polygon on the circle of radius r about `centre`: 60 vertices on the arc within 25 degrees of `facing`
// (facets 0.15 m long at r = 10 m, 3e-4 m deep) and three more round the back.
std::vector<Vec2> arc_polygon(double r, const Vec2& centre, double facing) {
  std::vector<Vec2> v;
  const double half = 25.0 * std::numbers::pi / 180.0;
  for (int k = 0; k < 60; ++k) {
    const double t = facing - half + 2.0 * half * k / 59.0;
    v.push_back(centre + r * Vec2(std::cos(t), std::sin(t)));
  }
  for (double t : {1.0, 1.5, 2.0}) {  // the back, at +90, +180 and +270 degrees from `facing`, roughly
    const double ang = facing + half + t * (2.0 * std::numbers::pi - 2.0 * half) / 3.0 - 0.3;
    v.push_back(centre + r * Vec2(std::cos(ang), std::sin(ang)));
  }
  return v;
}

TEST(Foundation, RoundContactsAreHertz) {
  // Circles of radius 10 and 15 m overlapping by δ: I = 16/15 sqrt(2 R*) δ^2.5, load (8/3) sqrt(2 R*) δ^1.5, so
  // that kappa = E*/(2 sqrt 2) gives the Hertz force 4/3 E* sqrt(R*) δ^1.5. The lens's curvature leaves about
  // 0.07 δ/R* (0.3 % at δ = 0.4 m by quadrature over the disks), the facets 3e-4 m / δ.
  const double r1 = 10.0, r2 = 15.0, rs = r1 * r2 / (r1 + r2);
  for (double delta : {0.1, 0.2, 0.4, 0.8}) {
    const auto a = arc_polygon(r1, {0.0, 0.0}, 0.0);
    const auto b = arc_polygon(r2, {r1 + r2 - delta, 0.0}, std::numbers::pi);
    const PlanarContact c = measure(a, b);
    const double e = 16.0 / 15.0 * std::sqrt(2.0 * rs) * std::pow(delta, 2.5);
    const double f = 8.0 / 3.0 * std::sqrt(2.0 * rs) * std::pow(delta, 1.5);
    const double tol = 0.1 * delta / rs + 2e-3 / delta;
    EXPECT_NEAR(c.energy / e, 1.0, tol) << delta;
    EXPECT_NEAR(c.load.norm() / f, 1.0, tol) << delta;
    EXPECT_NEAR(c.load.y(), 0.0, 1e-9 * f);
    EXPECT_GT(c.load.x(), 0.0);
  }
}

TEST(Foundation, EnergyMatchesQuadrature) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  int checked = 0;
  for (int trial = 0; trial < 40; ++trial) {
    const auto a = transform(random_convex(rng, 3 + trial % 6, 4.0, 1.0 + 3.0 * u(rng)), 6.0 * u(rng), {0, 0});
    const auto b = transform(random_convex(rng, 3 + (trial / 6) % 6, 4.0, 1.0 + 3.0 * u(rng)), 6.0 * u(rng),
                             {4.0 * u(rng) - 2.0, 4.0 * u(rng) - 2.0});
    const PlanarContact c = measure(a, b);
    if (!(c.area > 0.0)) continue;
    const double q = quadrature(a, b);
    EXPECT_NEAR(c.energy, q, 2e-4 * q + 1e-9) << "trial " << trial;
    ++checked;
  }
  EXPECT_GT(checked, 25);
}

TEST(Foundation, LoadIsTheExactGradient) {
  // Central differences of I: translating B (load = -dI/dx_B) and turning it about the overlap centroid
  // (load_moment = -dI/dθ_B), over random pairs of sharp, elongated polygons, shallow to deep, one inside the
  // other included.
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  int checked = 0;
  for (int trial = 0; trial < 200; ++trial) {
    const double scale = trial % 3 == 0 ? 0.3 : 1.0;  // every third B small: often inside A
    const auto a = transform(random_convex(rng, 3 + trial % 6, 4.0, 1.0 + 3.0 * u(rng)), 6.0 * u(rng), {0, 0});
    const auto b = transform(random_convex(rng, 3 + (trial / 6) % 6, 4.0 * scale, scale * (1.0 + 3.0 * u(rng))),
                             6.0 * u(rng), {5.0 * u(rng) - 2.5, 5.0 * u(rng) - 2.5});
    const PlanarContact c = measure(a, b);
    if (!(c.area > 1e-6)) continue;
    const double h = 1e-6;
    auto energy = [&](const std::vector<Vec2>& bb) { return measure(a, bb).energy; };
    const double fx = -(energy(shifted(b, {h, 0})) - energy(shifted(b, {-h, 0}))) / (2 * h);
    const double fy = -(energy(shifted(b, {0, h})) - energy(shifted(b, {0, -h}))) / (2 * h);
    const double mz = -(energy(turned(b, h, c.point)) - energy(turned(b, -h, c.point))) / (2 * h);
    const double f_scale = std::max(1e-3, c.load.norm());
    EXPECT_NEAR(c.load.x(), fx, 1e-6 * f_scale + 1e-7) << "trial " << trial;
    EXPECT_NEAR(c.load.y(), fy, 1e-6 * f_scale + 1e-7) << "trial " << trial;
    EXPECT_NEAR(c.load_moment, mz, 1e-6 * (f_scale * 8.0 + std::abs(c.load_moment)) + 1e-7) << "trial " << trial;
    // Swapping the bodies: the same energy, the opposite force on the other body.
    const PlanarContact s = measure(b, a);
    EXPECT_NEAR(s.energy, c.energy, 1e-12 * (1.0 + c.energy));
    EXPECT_NEAR((s.load + c.load).norm(), 0.0, 1e-9 * f_scale);
    ++checked;
  }
  EXPECT_GT(checked, 100);
}

TEST(Foundation, LoadIsContinuousThroughACornerEntering) {
  // B's corner slides along A's face and then a corner of A enters B: the load changes by at most O(step) between
  // neighbouring positions (no jump), and its work along the path is minus the change of I (trapezoid rule).
  const auto a = rectangle(10.0, 2.0, {0.0, 0.0});
  const auto b0 = transform(std::vector<Vec2>{{0, 0}, {3, -1}, {4, 1}, {1, 2}}, 0.3, {0, 0});
  Vec2 prev_load{0, 0};
  double prev_e = 0.0, work = 0.0, e0 = -1.0;
  const int steps = 4000;
  double worst_jump = 0.0;
  for (int k = 0; k <= steps; ++k) {
    const double s = static_cast<double>(k) / steps;
    const Vec2 d(-8.0 + 10.0 * s, 0.4 - 0.5 * s);
    const PlanarContact c = measure(a, shifted(b0, d));
    if (k > 0) {
      const Vec2 step(10.0 / steps, -0.5 / steps);
      work += 0.5 * (prev_load + c.load).dot(step);
      worst_jump = std::max(worst_jump, (c.load - prev_load).norm());
    } else {
      e0 = c.energy;
    }
    prev_load = c.load;
    prev_e = c.energy;
  }
  EXPECT_GT(prev_e, 0.1);
  EXPECT_LT(worst_jump, 0.02);  // a few steps' worth of the load's slope
  EXPECT_NEAR(work, -(prev_e - e0), 1e-5 * prev_e);
}
