// GJK + EPA in the plane against exact answers: hand cases with known depth and normal, the exact planar method
// where the two definitions coincide (containment, symmetric face contact), and random convex pairs against a
// brute-force minimum translation by separating axes (for convex polygons the least overlap over all edge normals
// of both polygons).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <random>
#include <vector>

#include "contact/narrow_phase_gjk2d.h"
#include "contact/narrow_phase_planar.h"
#include "geometry/vec2.h"

using namespace polyfloe;
using contact::Gjk2dContact;
using contact::Gjk2dSettings;
using contact::Gjk2dStatus;
using contact::gjk_epa_2d;
using geometry::Vec2;

namespace {

using Poly = std::vector<Vec2>;

Poly transformed(const Poly& v, double yaw, const Vec2& t) {
  const double c = std::cos(yaw), s = std::sin(yaw);
  Poly o;
  for (const Vec2& p : v) o.push_back(t + geometry::rotate(p, c, s));
  return o;
}

// Axis-aligned rectangle centred at c, counter-clockwise.
Poly box(const Vec2& c, double hx, double hy) {
  return {c + Vec2(-hx, -hy), c + Vec2(hx, -hy), c + Vec2(hx, hy), c + Vec2(-hx, hy)};
}

// Regular n-gon, circumradius r, with a vertex at angle `phase`.
Poly regular(int n, double r, const Vec2& c, double phase) {
  Poly o;
  for (int k = 0; k < n; ++k) {
    const double ang = phase + 2.0 * std::numbers::pi * k / n;
    o.push_back(c + r * Vec2(std::cos(ang), std::sin(ang)));
  }
  return o;
}

// Points on a circle of radius r at jittered random angles (each in its own slot of 2 pi / n), counter-clockwise.
Poly random_on_circle(std::mt19937_64& rng, int n, double r) {
  std::uniform_real_distribution<double> u(0.0, 1.0);
  const double phase = 2.0 * std::numbers::pi * u(rng);
  Poly o;
  for (int k = 0; k < n; ++k) {
    const double ang = phase + 2.0 * std::numbers::pi * (k + 0.9 * u(rng)) / n;
    o.push_back(r * Vec2(std::cos(ang), std::sin(ang)));
  }
  return o;
}

struct Axis {
  double overlap = 0.0;   // max_A n·x - min_B n·x [m]; > 0 overlapping along n
  Vec2 normal{1.0, 0.0};  // from A to B
};

// Overlap of A and B along n (A to B), coordinates taken relative to `o` for precision far from the origin.
double overlap_along(const Poly& a, const Poly& b, const Vec2& n, const Vec2& o) {
  double ha = -INFINITY, lb = INFINITY;
  for (const Vec2& p : a) ha = std::max(ha, n.dot(p - o));
  for (const Vec2& p : b) lb = std::min(lb, n.dot(p - o));
  return ha - lb;
}

// All candidate axes: A's outward edge normals and minus B's, each with the pair's overlap along it.
std::vector<Axis> axes(const Poly& a, const Poly& b) {
  std::vector<Axis> out;
  const Vec2 o = a[0];
  auto scan = [&](const Poly& s, double sign) {
    for (std::size_t i = 0; i < s.size(); ++i) {
      const Vec2 e = s[(i + 1) % s.size()] - s[i];
      const Vec2 n = sign * geometry::perp_right(e) / e.norm();
      out.push_back({overlap_along(a, b, n, o), n});
    }
  };
  scan(a, 1.0);
  scan(b, -1.0);
  return out;
}

// Minimum translation distance by separating axes: the least overlap (negative: separated by that gap at least).
Axis brute_mtd(const Poly& a, const Poly& b) {
  Axis best{INFINITY, {1.0, 0.0}};
  for (const Axis& ax : axes(a, b))
    if (ax.overlap < best.overlap) best = ax;
  return best;
}

double angle_between(const Vec2& u, const Vec2& v) { return std::atan2(std::abs(geometry::cross(u, v)), u.dot(v)); }

// Largest signed distance of p outside the edge lines of a convex polygon (<= 0 inside; a lower bound outside).
double outside(const Poly& poly, const Vec2& p) {
  double s = -INFINITY;
  for (std::size_t i = 0; i < poly.size(); ++i) {
    const Vec2 e = poly[(i + 1) % poly.size()] - poly[i];
    s = std::max(s, geometry::perp_right(e).dot(p - poly[i]) / e.norm());
  }
  return s;
}

Poly shifted(const Poly& v, const Vec2& d) { return transformed(v, 0.0, d); }

}  // namespace

// Two axis-aligned squares (side 2 m) overlapping by 0.25 m along one axis (1.9 m or 2 m along the other): depth
// and normal exact. With the centres on an axis GJK's first segment runs through the origin (the degenerate start).
TEST(Gjk2d, SquaresOverlappingAQuarterMetreGiveThatDepthTheAxisNormalAndTheMidpoint) {
  const Poly a = box({0, 0}, 1, 1);
  struct Case {
    Vec2 centre, normal;
  };
  for (const Case& c : {Case{{1.75, 0.1}, {1, 0}}, Case{{-1.75, 0.1}, {-1, 0}}, Case{{0.1, 1.75}, {0, 1}},
                        Case{{-0.1, -1.75}, {0, -1}}, Case{{1.75, 0.0}, {1, 0}}, Case{{0.0, -1.75}, {0, -1}}}) {
    const Poly b = box(c.centre, 1, 1);
    const Gjk2dContact r = gjk_epa_2d(a, b);
    ASSERT_EQ(r.status, Gjk2dStatus::contact) << r.reason;
    EXPECT_NEAR(r.depth, 0.25, 1e-12 * 0.25);
    EXPECT_NEAR(r.normal.x(), c.normal.x(), 1e-12);
    EXPECT_NEAR(r.normal.y(), c.normal.y(), 1e-12);
    // Witness midpoint: halfway between A's face and B's face along the normal, inside the overlap sideways.
    const Vec2 across = geometry::perp_left(c.normal);
    EXPECT_NEAR(r.point.dot(c.normal), 0.875, 1e-12);  // A's face at 1, B's at 0.75
    const double side = c.centre.dot(across);
    EXPECT_GE(r.point.dot(across), std::max(-1.0, side - 1.0) - 1e-12);
    EXPECT_LE(r.point.dot(across), std::min(1.0, side + 1.0) + 1e-12);
    EXPECT_GT(r.iterations, 0);
    // The sign of the normal: B moved by (depth + 1 um) along it is clear; by (depth - 1 um) it still overlaps.
    EXPECT_EQ(gjk_epa_2d(a, shifted(b, (r.depth + 1e-6) * r.normal)).status, Gjk2dStatus::separated);
    EXPECT_EQ(gjk_epa_2d(a, shifted(b, (r.depth - 1e-6) * r.normal)).status, Gjk2dStatus::contact);
  }
}

// A rigid motion of the pair moves the answer with it: same depth, rotated normal, moved point.
TEST(Gjk2d, ARigidMotionOfThePairMovesTheDepthNormalAndPointWithIt) {
  const Poly a0 = regular(5, 3.0, {0, 0}, 0.3);
  const Poly b0 = transformed(regular(7, 2.0, {0, 0}, 0.0), 0.7, {4.1, 1.2});
  const Gjk2dContact r0 = gjk_epa_2d(a0, b0);
  ASSERT_EQ(r0.status, Gjk2dStatus::contact) << r0.reason;
  const Axis ref = brute_mtd(a0, b0);
  EXPECT_NEAR(r0.depth, ref.overlap, 1e-12 * 5.0);
  EXPECT_LT(angle_between(r0.normal, ref.normal), 1e-12);
  for (double yaw : {0.1, 1.0, 2.5, -2.0, std::numbers::pi / 2}) {
    for (const Vec2& t : {Vec2(0, 0), Vec2(-37.5, 12.25), Vec2(1.0e3, 2.0e3)}) {
      const Poly a = transformed(a0, yaw, t), b = transformed(b0, yaw, t);
      const Gjk2dContact r = gjk_epa_2d(a, b);
      ASSERT_EQ(r.status, Gjk2dStatus::contact) << r.reason;
      const double c = std::cos(yaw), s = std::sin(yaw);
      EXPECT_NEAR(r.depth, r0.depth, 1e-11 * 5.0) << "yaw " << yaw;
      EXPECT_LT(angle_between(r.normal, geometry::rotate(r0.normal, c, s)), 1e-11);
      EXPECT_LT((r.point - (t + geometry::rotate(r0.point, c, s))).norm(), 1e-10 * 5.0);
    }
  }
}

// A 1 m triangle whose tip pokes 1 cm into the top face of a 100 m square: depth 1 cm, normal +y (square to
// triangle), the point halfway between the tip and the face.
TEST(Gjk2d, TriangleTipACentimetreIntoABigSquareGivesThatDepthAndTheNormalFromAToB) {
  const Poly square = box({0, 0}, 50, 50);
  const Poly tri = {{0.0, 49.99}, {0.5, 50.8}, {-0.5, 50.8}};
  const Gjk2dContact r = gjk_epa_2d(square, tri);
  ASSERT_EQ(r.status, Gjk2dStatus::contact) << r.reason;
  EXPECT_NEAR(r.depth, 0.01, 1e-12 * 100);
  EXPECT_NEAR(r.normal.x(), 0.0, 1e-12);
  EXPECT_NEAR(r.normal.y(), 1.0, 1e-12);
  EXPECT_NEAR(r.point.x(), 0.0, 1e-12 * 100);
  EXPECT_NEAR(r.point.y(), 49.995, 1e-12 * 100);
  // Roles swapped: the normal still points from A (now the triangle) to B.
  const Gjk2dContact s = gjk_epa_2d(tri, square);
  ASSERT_EQ(s.status, Gjk2dStatus::contact) << s.reason;
  EXPECT_NEAR(s.depth, 0.01, 1e-12 * 100);
  EXPECT_NEAR(s.normal.y(), -1.0, 1e-12);
  EXPECT_NEAR(s.point.y(), 49.995, 1e-12 * 100);
}

// Regular 12-gons face to face along a face normal u, overlapping by d: the minimum translation is d along u. The
// planar method measures area / chord of the overlap hexagon instead: the same normal (by symmetry) and the depth
// (s d + d^2 / (2 tan 30°)) / (s + d / tan 30°) for side s, which tends to d as d / s -> 0.
TEST(Gjk2d, FaceToFaceTwelveGonsGiveTheOverlapAsDepthAndAgreeWithPlanarToOrderDSquared) {
  const double r = 10.0;                                 // circumradius [m]
  const double h = r * std::cos(std::numbers::pi / 12);  // apothem [m]
  const double side = 2.0 * r * std::sin(std::numbers::pi / 12);
  const double t30 = std::tan(std::numbers::pi / 6);
  for (double yaw : {0.0, 0.4, 1.3}) {
    for (double d : {1e-3, 0.05, 0.5}) {
      // Vertices at yaw + (k + 1/2) 30°: a face normal along yaw.
      const Poly a = regular(12, r, {0, 0}, yaw + std::numbers::pi / 12);
      const Vec2 u(std::cos(yaw), std::sin(yaw));
      const Poly b = regular(12, r, (2.0 * h - d) * u, yaw + std::numbers::pi / 12);
      const Gjk2dContact g = gjk_epa_2d(a, b);
      ASSERT_EQ(g.status, Gjk2dStatus::contact) << g.reason;
      EXPECT_NEAR(g.depth, d, 1e-12 * 2 * r + 1e-12 * d);
      EXPECT_LT(angle_between(g.normal, u), 1e-12 * 2 * r / side + 1e-13);
      const Axis ref = brute_mtd(a, b);
      EXPECT_NEAR(g.depth, ref.overlap, 1e-12 * 2 * r);

      contact::PlanarContact p;
      ASSERT_TRUE(contact::planar_overlap(a, b, p));
      EXPECT_LT(angle_between(p.normal, g.normal), 1e-9);
      const double expect_planar = (side * d + d * d / (2 * t30)) / (side + d / t30);
      EXPECT_NEAR(p.depth, expect_planar, 1e-9 * 2 * r);
      EXPECT_GE(g.depth - p.depth, 0.0);
      EXPECT_LE(g.depth - p.depth, d * d / (2 * side * t30)) << "agree to O(d^2 / s)";
      // Both points at the centre of the overlap (by symmetry): on the line of centres, halfway between the faces.
      EXPECT_LT((g.point - p.point).norm(), 1e-9 * 2 * r);
      EXPECT_LT((g.point - (h - 0.5 * d) * u).norm(), 1e-12 * 2 * r);
    }
  }
}

TEST(Gjk2d, GapsAndExactTouchingAreSeparatedEvenWhenTheBoundingBoxesOverlap) {
  const Poly a = box({0, 0}, 1, 1);
  EXPECT_EQ(gjk_epa_2d(a, box({2.5, 0.3}, 1, 1)).status, Gjk2dStatus::separated);         // 0.5 m gap
  EXPECT_EQ(gjk_epa_2d(a, box({100, -40}, 1, 1)).status, Gjk2dStatus::separated);         // far
  EXPECT_EQ(gjk_epa_2d(a, box({2.0 + 1e-9, 0.3}, 1, 1)).status, Gjk2dStatus::separated);  // 1 nm gap
  // Exactly touching: face on face, corner on corner, face on face flush, vertex on face.
  EXPECT_EQ(gjk_epa_2d(a, box({2.0, 0.3}, 1, 1)).status, Gjk2dStatus::separated);
  EXPECT_EQ(gjk_epa_2d(a, box({2.0, 2.0}, 1, 1)).status, Gjk2dStatus::separated);
  EXPECT_EQ(gjk_epa_2d(a, box({0.0, -2.0}, 1, 1)).status, Gjk2dStatus::separated);
  const Poly tip = {{0.25, 1.0}, {1.0, 2.0}, {-1.0, 2.0}};
  EXPECT_EQ(gjk_epa_2d(a, tip).status, Gjk2dStatus::separated);
  EXPECT_EQ(gjk_epa_2d(tip, a).status, Gjk2dStatus::separated);
  // Bounding boxes overlap, polygons do not: two diamonds with a diagonal gap.
  const Poly da = regular(4, 1.0, {0, 0}, 0.0), db = regular(4, 1.0, {1.05, 1.05}, 0.0);
  EXPECT_EQ(gjk_epa_2d(da, db).status, Gjk2dStatus::separated);
  // Rotated 12-gons face to face at zero overlap (touching up to round-off of the rotation).
  const double h = 10.0 * std::cos(std::numbers::pi / 12);
  for (double yaw : {0.2, 0.9, 2.2}) {
    const Vec2 u(std::cos(yaw), std::sin(yaw));
    const Poly g1 = regular(12, 10.0, {0, 0}, yaw + std::numbers::pi / 12);
    const Poly g2 = regular(12, 10.0, 2.0 * h * u, yaw + std::numbers::pi / 12);
    EXPECT_EQ(gjk_epa_2d(g1, g2).status, Gjk2dStatus::separated) << yaw;
  }
}

// One polygon wholly inside the other: the depth is the least translation that takes it out, the separating-axis
// penetration, which is also what the planar method reports in its containment fallback.
TEST(Gjk2d, ContainedPolygonDepthIsTheShortestWayOutAsSeparatingAxesAndPlanarGiveIt) {
  const Poly big = box({0, 0}, 50, 50);
  const Poly small = transformed(regular(5, 1.0, {0, 0}, 0.2), 0.0, {30.0, -10.0});
  for (int swap = 0; swap < 2; ++swap) {
    const Poly& a = swap ? small : big;
    const Poly& b = swap ? big : small;
    const Gjk2dContact g = gjk_epa_2d(a, b);
    ASSERT_EQ(g.status, Gjk2dStatus::contact) << g.reason;
    const Axis ref = brute_mtd(a, b);
    double min_x = INFINITY;
    for (const Vec2& p : small) min_x = std::min(min_x, p.x());
    EXPECT_NEAR(ref.overlap, 50.0 - min_x, 1e-12 * 100);  // pushed out through the right face
    EXPECT_NEAR(g.depth, ref.overlap, 1e-12 * 100);
    EXPECT_LT(angle_between(g.normal, ref.normal), 1e-12);
    EXPECT_NEAR(g.normal.x(), swap ? -1.0 : 1.0, 1e-12);
    contact::PlanarContact p;
    ASSERT_TRUE(contact::planar_overlap(a, b, p));
    EXPECT_EQ(p.chord, 0.0);
    EXPECT_NEAR(g.depth, p.depth, 1e-12 * 100);
    EXPECT_LT(angle_between(g.normal, p.normal), 1e-12);
    // Moving B out along the normal by the depth (plus 1 um) separates it.
    EXPECT_EQ(gjk_epa_2d(a, shifted(b, (g.depth + 1e-6) * g.normal)).status, Gjk2dStatus::separated);
  }
}

// The same pairs 10 km from the origin: depth and normal as near the origin, to round-off of 1e4 m coordinates.
TEST(Gjk2d, PairsTenKilometresOutGiveTheDepthAndNormalTheyHaveNearTheOrigin) {
  const Vec2 far(1.0e4, -1.0e4);
  const Poly a0 = regular(12, 10.0, {0, 0}, 0.1), b0 = transformed(regular(9, 6.0, {0, 0}, 0.0), 0.5, {15.0, 3.0});
  const Gjk2dContact r0 = gjk_epa_2d(a0, b0);
  const Gjk2dContact r = gjk_epa_2d(shifted(a0, far), shifted(b0, far));
  ASSERT_EQ(r0.status, Gjk2dStatus::contact) << r0.reason;
  ASSERT_EQ(r.status, Gjk2dStatus::contact) << r.reason;
  const double size = 31.0;
  EXPECT_NEAR(r.depth, r0.depth, 1e-10 * size);
  EXPECT_LT(angle_between(r.normal, r0.normal), 1e-9);
  EXPECT_LT((r.point - far - r0.point).norm(), 1e-10 * size);
  const Axis ref = brute_mtd(shifted(a0, far), shifted(b0, far));
  EXPECT_NEAR(r.depth, ref.overlap, 1e-10 * size);
  // Squares overlapping by 1 mm out there.
  const Gjk2dContact q = gjk_epa_2d(box(far, 1, 1), box(far + Vec2(1.999, 0.5), 1, 1));
  ASSERT_EQ(q.status, Gjk2dStatus::contact) << q.reason;
  EXPECT_NEAR(q.depth, 1e-3, 1e-10 * 4);
  EXPECT_NEAR(q.normal.x(), 1.0, 1e-12);
}

// Random convex pairs (5-20 vertices on circles of diameter 5-100 m, placed to overlap by 1 mm to 10 cm along a
// random axis, with a sideways jitter that leaves some apart; 1 in 4 instead overlapping deeply at random; 1 in 10
// of them 10 km from the origin) against the separating-axis minimum translation: depth
// within 1e-9 of the pair's size, normal within 1e-6 rad (where the two least axes are not within the tolerance
// of each other; then it must be one of them), and no failure.
TEST(Gjk2d, RandomPairsAgainstSeparatingAxes) {
  std::mt19937_64 rng(20240611);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::uniform_int_distribution<int> nv(5, 20);
  const int pairs = 20000;
  int contacts = 0, deep_contacts = 0, separated = 0, ambiguous = 0, near_ties = 0, max_iterations = 0;
  double worst_depth = 0.0, worst_angle = 0.0;
  for (int it = 0; it < pairs; ++it) {
    const double ra = 0.5 * (5.0 + 95.0 * u(rng)), rb = 0.5 * (5.0 + 95.0 * u(rng));
    const Vec2 far = (it % 10 == 0) ? Vec2(1.0e4, -1.0e4) : Vec2(0.0, 0.0);
    const Poly a = shifted(random_on_circle(rng, nv(rng), ra), far);
    const Poly b0 = random_on_circle(rng, nv(rng), rb);
    // B overlaps A by `depth` along n, its deepest vertex beside A's outermost one (jittered sideways).
    const double ang = 2.0 * std::numbers::pi * u(rng);
    const Vec2 n(std::cos(ang), std::sin(ang)), side = geometry::perp_left(n);
    const double depth = 1e-3 * std::pow(100.0, u(rng));  // 1 mm to 10 cm, log-uniform [m]
    Vec2 pa = a[0], pb = b0[0];
    for (const Vec2& p : a)
      if (n.dot(p) > n.dot(pa)) pa = p;
    for (const Vec2& p : b0)
      if (n.dot(p) < n.dot(pb)) pb = p;
    // Sideways by up to a few depths: B's deepest vertex stays near A's outermost one, most pairs overlap.
    const double jitter = (2.0 * u(rng) - 1.0) * 3.0 * depth;
    Vec2 offset = (n.dot(pa - pb) - depth) * n + ((pa - pb).dot(side) + jitter) * side;
    // One pair in four overlaps deeply instead: centres 0.3 to 0.9 of the radii's sum apart.
    const bool deep = it % 4 == 1;
    if (deep) offset = far + (0.3 + 0.6 * u(rng)) * (ra + rb) * n;
    const Poly b = shifted(b0, offset);

    Vec2 lo = a[0], hi = a[0];
    for (const Poly* p : {&a, &b})
      for (const Vec2& q : *p) {
        lo = lo.cwiseMin(q);
        hi = hi.cwiseMax(q);
      }
    const double size = (hi - lo).maxCoeff();
    const double tol = 1e-9 * size;

    const std::vector<Axis> all = axes(a, b);
    Axis best{INFINITY, {1, 0}};
    for (const Axis& ax : all)
      if (ax.overlap < best.overlap) best = ax;
    const Gjk2dContact r = gjk_epa_2d(a, b);
    ASSERT_NE(r.status, Gjk2dStatus::failed) << "pair " << it << ": " << r.reason;
    max_iterations = std::max(max_iterations, r.iterations);
    if (std::abs(best.overlap) <= tol) {
      ++ambiguous;  // touching to within the tolerance: either answer is right
      continue;
    }
    if (best.overlap < 0.0) {
      EXPECT_EQ(r.status, Gjk2dStatus::separated) << "pair " << it << " gap " << -best.overlap;
      ++separated;
      continue;
    }
    ASSERT_EQ(r.status, Gjk2dStatus::contact) << "pair " << it << " overlap " << best.overlap;
    ++contacts;
    deep_contacts += deep;
    EXPECT_NEAR(r.depth, best.overlap, tol) << "pair " << it;
    worst_depth = std::max(worst_depth, std::abs(r.depth - best.overlap) / size);
    EXPECT_NEAR(r.normal.norm(), 1.0, 1e-14);
    // Axes within the tolerance of the least are equally right; distinct ones must be further apart than that.
    bool matches = false, tie = false;
    for (const Axis& ax : all) {
      if (ax.overlap > best.overlap + 2.0 * tol) continue;
      if (angle_between(ax.normal, best.normal) > 1e-6) tie = true;
      if (angle_between(ax.normal, r.normal) <= 1e-6) matches = true;
    }
    near_ties += tie;
    EXPECT_TRUE(matches) << "pair " << it << " angle " << angle_between(r.normal, best.normal);
    if (!tie) worst_angle = std::max(worst_angle, angle_between(r.normal, best.normal));
    // The point: midpoint of witnesses on A and B that are `depth` apart along the normal, so within depth / 2
    // of each polygon and halfway between A's support line along n and B's along -n.
    const Vec2 o = a[0];
    double ha = -INFINITY, lb = INFINITY;
    for (const Vec2& p : a) ha = std::max(ha, r.normal.dot(p - o));
    for (const Vec2& p : b) lb = std::min(lb, r.normal.dot(p - o));
    EXPECT_NEAR(r.normal.dot(r.point - o), 0.5 * (ha + lb), tol) << "pair " << it;
    EXPECT_LE(outside(a, r.point), 0.5 * r.depth + tol) << "pair " << it;
    EXPECT_LE(outside(b, r.point), 0.5 * r.depth + tol) << "pair " << it;
  }
  EXPECT_GT(contacts, pairs / 2);
  std::printf(
      "contacts %d (%d deep), separated %d, touching within tolerance %d, near ties %d; worst depth error "
      "%.2e of size, worst angle %.2e rad; most iterations %d\n",
      contacts, deep_contacts, separated, ambiguous, near_ties, worst_depth, worst_angle, max_iterations);
}

// The iteration bounds are honoured: a generic 12-gon pair needs several EPA steps; with one it fails, as it does
// with a single GJK step. Bad input fails with a reason, never throws.
TEST(Gjk2d, OneEpaOrGjkIterationFailsNamingTheLimitAndBadInputFailsWithoutThrowing) {
  const Poly a = regular(12, 10.0, {0, 0}, 0.1);
  const Poly b = regular(12, 10.0, {18.0, 5.0}, 0.37);
  const Gjk2dContact ok = gjk_epa_2d(a, b);
  ASSERT_EQ(ok.status, Gjk2dStatus::contact) << ok.reason;
  Gjk2dSettings one_epa;
  one_epa.max_epa_iterations = 1;
  const Gjk2dContact f = gjk_epa_2d(a, b, one_epa);
  EXPECT_EQ(f.status, Gjk2dStatus::failed);
  EXPECT_STREQ(f.reason, "EPA iteration limit");
  EXPECT_LE(f.iterations, ok.iterations);
  Gjk2dSettings one_gjk;
  one_gjk.max_gjk_iterations = 1;
  const Gjk2dContact g = gjk_epa_2d(a, b, one_gjk);
  EXPECT_EQ(g.status, Gjk2dStatus::failed);
  EXPECT_STREQ(g.reason, "GJK iteration limit");
  EXPECT_EQ(g.iterations, 1);

  Poly nan_a = a;
  nan_a[3].x() = std::nan("");
  EXPECT_EQ(gjk_epa_2d(nan_a, b).status, Gjk2dStatus::failed);
  Poly inf_b = b;
  inf_b[0].y() = INFINITY;
  EXPECT_EQ(gjk_epa_2d(a, inf_b).status, Gjk2dStatus::failed);
  EXPECT_EQ(gjk_epa_2d(Poly{{0, 0}, {1, 0}}, b).status, Gjk2dStatus::failed);
  EXPECT_EQ(gjk_epa_2d(Poly{}, b).status, Gjk2dStatus::failed);
  EXPECT_EQ(gjk_epa_2d(regular(65, 10.0, {0, 0}, 0.0), b).status, Gjk2dStatus::failed);
  Gjk2dSettings bad_tol;
  bad_tol.tolerance = std::nan("");
  EXPECT_EQ(gjk_epa_2d(a, b, bad_tol).status, Gjk2dStatus::failed);
  // Every point identical: no extent.
  EXPECT_EQ(gjk_epa_2d(Poly(3, Vec2(1, 1)), Poly(3, Vec2(1, 1))).status, Gjk2dStatus::failed);
}
