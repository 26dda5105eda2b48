// The planar narrow phase against a brute-force reference: the overlap polygon by hulling all edge crossings and
// contained vertices; the chord vector by classifying each hull edge geometrically as lying on ∂A or not and summing
// the outward edge normals of the ∂A part. Hand cases check that this chord is minus the gradient of the overlap
// area with respect to translating B.
#include <gtest/gtest.h>

#include <algorithm>
#include <limits>
#include <random>

#include "contact/narrow_phase_planar.h"
#include "test_support.h"

using namespace polyfloe;
using contact::PlanarContact;
using geometry::Vec2;
using tsupport::brute_area;
using tsupport::brute_overlap;

namespace {

std::vector<Vec2> shifted(const std::vector<Vec2>& v, const Vec2& d) {
  std::vector<Vec2> o;
  for (const Vec2& p : v) o.push_back(p + d);
  return o;
}

struct Reference {
  double area = 0.0;
  Vec2 centroid{0, 0};
  Vec2 chord{0, 0};  // -grad_t area(A ∩ (B + t))
};

Reference reference(const std::vector<Vec2>& a, const std::vector<Vec2>& b, double scale) {
  Reference r;
  const auto hull = brute_overlap(a, b);
  if (hull.size() < 3) return r;
  const auto props = geometry::polygon_properties(hull);
  r.area = props.area;
  r.centroid = props.centroid;
  // An overlap edge lies on ∂A when its midpoint is on one of A's edge segments.
  const double tol = 1e-9 * scale;
  for (std::size_t k = 0; k < hull.size(); ++k) {
    const Vec2 p = hull[k], q = hull[(k + 1) % hull.size()];
    const Vec2 mid = 0.5 * (p + q);
    bool on_a = false;
    for (std::size_t i = 0; i < a.size() && !on_a; ++i) {
      const Vec2 e = a[(i + 1) % a.size()] - a[i];
      const double t = (mid - a[i]).dot(e) / e.squaredNorm();
      on_a = t >= 0.0 && t <= 1.0 && std::abs(geometry::cross(e, mid - a[i])) / e.norm() < tol;
    }
    if (on_a) r.chord += geometry::perp_right(q - p);
  }
  return r;
}

}  // namespace

TEST(NarrowPhase, RandomPairsAgainstBruteForce) {
  std::mt19937_64 rng(12345);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  int compared = 0, contained = 0, separated = 0;
  const int pairs = 20000;
  for (int it = 0; it < pairs; ++it) {
    const double sa = 5.0 + 95.0 * u(rng), sb = 5.0 + 95.0 * u(rng);
    const int na = 3 + static_cast<int>(u(rng) * 14), nb = 3 + static_cast<int>(u(rng) * 14);
    const auto a0 = tsupport::random_convex(rng, na, 0.5 * sa, 0.5 * sa * (0.4 + 0.6 * u(rng)));
    const auto b0 = tsupport::random_convex(rng, nb, 0.5 * sb, 0.5 * sb * (0.4 + 0.6 * u(rng)));
    const Vec2 far = (it % 10 == 0) ? Vec2(1.0e4, -1.0e4) : Vec2(0, 0);  // some pairs 10 km from the origin
    const auto a = tsupport::transform(a0, 6.3 * u(rng), far);
    // Place B at a random distance so that most pairs overlap a little and some not at all.
    const double dist = (0.5 * (sa + sb)) * (0.3 + 0.6 * u(rng));
    const double ang = 6.3 * u(rng);
    const auto b = tsupport::transform(b0, 6.3 * u(rng), far + dist * Vec2(std::cos(ang), std::sin(ang)));

    PlanarContact c;
    const bool hit = contact::planar_overlap(a, b, c);
    const double scale = std::max(sa, sb);
    const Reference ref = reference(a, b, scale);
    const double area_tol = 1e-9 * scale * scale;
    if (ref.area <= area_tol) {
      if (hit) {
        EXPECT_LE(c.area, 10 * area_tol) << "pair " << it;
      }
      ++separated;
      continue;
    }
    ASSERT_TRUE(hit) << "pair " << it << " missed an overlap of area " << ref.area;
    EXPECT_NEAR(c.area, ref.area, 1e-9 * ref.area + area_tol) << "pair " << it;
    EXPECT_NEAR((c.point - ref.centroid).norm(), 0.0, 1e-8 * scale) << "pair " << it;
    const double chord = ref.chord.norm();
    if (chord < 1e-6 * scale) {
      // One polygon inside the other: no chord; the fallback must still give a unit normal and a depth.
      ++contained;
      EXPECT_NEAR(c.normal.norm(), 1.0, 1e-12);
      EXPECT_GT(c.depth, 0.0);
      continue;
    }
    ++compared;
    EXPECT_NEAR(c.chord, chord, 1e-6 * chord + 1e-7 * scale) << "pair " << it;
    EXPECT_NEAR(c.normal.dot(ref.chord / chord), 1.0, 1e-9) << "pair " << it;
    EXPECT_NEAR(c.depth, ref.area / chord, 1e-6 * (ref.area / chord) + 1e-9 * scale) << "pair " << it;
    // Antisymmetry: swapping A and B flips the normal and keeps everything else.
    PlanarContact s;
    ASSERT_TRUE(contact::planar_overlap(b, a, s));
    EXPECT_NEAR((s.normal + c.normal).norm(), 0.0, 1e-9);
    EXPECT_NEAR(s.area, c.area, 1e-9 * c.area);
  }
  EXPECT_GE(compared, 10000);
  EXPECT_GT(separated, 0);
  std::printf("compared %d overlapping pairs, %d contained, %d separated\n", compared, contained, separated);
}

// The depth gradient (used by the energy-conserving force model) against central differences of the depth when B
// (or A) is translated and rotated about its centroid.
TEST(NarrowPhase, DepthGradientMatchesFiniteDifferences) {
  std::mt19937_64 rng(777);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  int checked = 0;
  for (int it = 0; it < 3000; ++it) {
    const double sa = 5.0 + 45.0 * u(rng), sb = 5.0 + 45.0 * u(rng);
    const auto a0 = tsupport::random_convex(rng, 3 + static_cast<int>(u(rng) * 10), 0.5 * sa, 0.4 * sa);
    const auto b0 = tsupport::random_convex(rng, 3 + static_cast<int>(u(rng) * 10), 0.5 * sb, 0.35 * sb);
    const Vec2 ca = geometry::polygon_properties(a0).centroid, cb = geometry::polygon_properties(b0).centroid;
    const double dist = 0.5 * (sa + sb) * (0.3 + 0.5 * u(rng)), ang = 6.3 * u(rng);
    const Vec2 xa{0.0, 0.0}, xb = dist * Vec2(std::cos(ang), std::sin(ang));
    const double ya = 6.3 * u(rng), yb = 6.3 * u(rng);
    // Polygon placed so that its centroid sits at x, rotated by yaw about it.
    auto place = [](const std::vector<Vec2>& v, const Vec2& c, double yaw, const Vec2& x) {
      std::vector<Vec2> local;
      for (const Vec2& p : v) local.push_back(p - c);
      return tsupport::transform(local, yaw, x);
    };
    PlanarContact c;
    if (!contact::planar_overlap(place(a0, ca, ya, xa), place(b0, cb, yb, xb), c, true) || c.chord == 0.0) continue;
    auto depth = [&](const Vec2& pa, double ta, const Vec2& pb, double tb) {
      PlanarContact d;
      if (!contact::planar_overlap(place(a0, ca, ta, pa), place(b0, cb, tb, pb), d)) return 0.0;
      return d.depth;
    };
    const contact::DepthGradient g = contact::depth_gradient(c, xa, xb);
    const double h = 1e-6 * std::max(sa, sb), hr = 1e-7;
    const Vec2 ex{h, 0.0}, ey{0.0, h};
    const double fd_bx = (depth(xa, ya, xb + ex, yb) - depth(xa, ya, xb - ex, yb)) / (2 * h);
    const double fd_by = (depth(xa, ya, xb + ey, yb) - depth(xa, ya, xb - ey, yb)) / (2 * h);
    const double fd_wb = (depth(xa, ya, xb, yb + hr) - depth(xa, ya, xb, yb - hr)) / (2 * hr);
    const double fd_wa = (depth(xa, ya + hr, xb, yb) - depth(xa, ya - hr, xb, yb)) / (2 * hr);
    const double gscale = 1.0 + g.grad_b.norm();
    const double wscale = std::max(sa, sb) * gscale;
    EXPECT_NEAR(g.grad_b.x(), fd_bx, 1e-4 * gscale) << "pair " << it;
    EXPECT_NEAR(g.grad_b.y(), fd_by, 1e-4 * gscale) << "pair " << it;
    EXPECT_NEAR(g.grad_wb, fd_wb, 1e-4 * wscale) << "pair " << it;
    EXPECT_NEAR(g.grad_wa, fd_wa, 1e-4 * wscale) << "pair " << it;
    ++checked;
  }
  EXPECT_GT(checked, 1000);
  std::printf("depth gradient checked on %d overlapping pairs\n", checked);
}

TEST(NarrowPhase, TouchingIsNoContact) {
  const std::vector<Vec2> sq = {{0, 0}, {10, 0}, {10, 10}, {0, 10}};
  PlanarContact c;
  // Edge to edge, exactly touching.
  EXPECT_FALSE(contact::planar_overlap(sq, shifted(sq, {10, 0}), c));
  EXPECT_FALSE(contact::planar_overlap(sq, shifted(sq, {3, 10}), c));
  // Vertex to vertex, exactly touching.
  EXPECT_FALSE(contact::planar_overlap(sq, shifted(sq, {10, 10}), c));
  // A vertex touching an edge.
  const std::vector<Vec2> diamond = {{0, -5}, {5, 0}, {0, 5}, {-5, 0}};
  EXPECT_FALSE(contact::planar_overlap(sq, shifted(diamond, {15, 5}), c));
  // Separated by a hair.
  EXPECT_FALSE(contact::planar_overlap(sq, shifted(sq, {10 + 1e-12, 0}), c));
}

TEST(NarrowPhase, OverlapsAlongSharedEdgeLinesGiveExactAreaDepthAndTheAreaGradientsNormal) {
  const std::vector<Vec2> sq = {{0, 0}, {10, 0}, {10, 10}, {0, 10}};
  PlanarContact c;
  // Same heights, edges on shared lines: the overlap is a 0.1 m x 10 m strip, normal along x.
  ASSERT_TRUE(contact::planar_overlap(sq, shifted(sq, {9.9, 0.0}), c));
  EXPECT_NEAR(c.area, 1.0, 1e-12);
  EXPECT_NEAR(c.depth, 0.1, 1e-12);
  EXPECT_NEAR(c.normal.x(), 1.0, 1e-12);
  EXPECT_NEAR(c.normal.y(), 0.0, 1e-12);
  EXPECT_NEAR(c.point.x(), 9.95, 1e-12);
  EXPECT_NEAR(c.point.y(), 5.0, 1e-12);
  // Offset by 4 m: corner against corner. The crossings are (10, 4) and (9.9, 10), so the chord normal is
  // (6, 0.1)/|.|: moving B up also shrinks the overlap, through A's top edge inside B.
  ASSERT_TRUE(contact::planar_overlap(sq, shifted(sq, {9.9, 4.0}), c));
  const Vec2 n = Vec2(6.0, 0.1).normalized();
  EXPECT_NEAR(c.area, 0.6, 1e-12);
  EXPECT_NEAR(c.normal.x(), n.x(), 1e-12);
  EXPECT_NEAR(c.normal.y(), n.y(), 1e-12);
  EXPECT_NEAR(c.depth, 0.6 / std::sqrt(36.01), 1e-12);
  EXPECT_NEAR(c.point.x(), 9.95, 1e-12);
  EXPECT_NEAR(c.point.y(), 7.0, 1e-12);
  // The same from the area gradient by central differences: d|A ∩ (B + t)|/dt = -chord.
  const double h = 1e-6;
  const auto b = shifted(sq, {9.9, 4.0});
  const double gx = (brute_area(sq, shifted(b, {h, 0})) - brute_area(sq, shifted(b, {-h, 0}))) / (2 * h);
  const double gy = (brute_area(sq, shifted(b, {0, h})) - brute_area(sq, shifted(b, {0, -h}))) / (2 * h);
  EXPECT_NEAR(-gx, c.chord * c.normal.x(), 1e-6);
  EXPECT_NEAR(-gy, c.chord * c.normal.y(), 1e-6);
  // Flush on a shared line and overlapping: a thin overlap, normal still across it.
  ASSERT_TRUE(contact::planar_overlap(sq, shifted(sq, Vec2(0.0, 9.999)), c));
  EXPECT_NEAR(c.normal.y(), 1.0, 1e-12);
  EXPECT_NEAR(c.depth, 0.001, 1e-9);
}

TEST(NarrowPhase, TipToTipDiamondsGiveASquareOverlapWithHalfThePenetrationAsDepth) {
  // Two squares rotated 45 degrees meeting tip to tip with a small overlap: a square overlap of diagonal 2*pen.
  const double h = 5.0 * std::sqrt(2.0);
  const std::vector<Vec2> d = {{0, -h}, {h, 0}, {0, h}, {-h, 0}};
  const double pen = 0.01;
  PlanarContact c;
  ASSERT_TRUE(contact::planar_overlap(d, shifted(d, {2 * h - pen, 0}), c));
  EXPECT_NEAR(c.area, 0.5 * pen * pen, 1e-12);
  EXPECT_NEAR(c.normal.x(), 1.0, 1e-9);
  EXPECT_NEAR(c.chord, pen, 1e-12);
  EXPECT_NEAR(c.depth, 0.5 * pen, 1e-12);
}

TEST(NarrowPhase, ContainmentFallsBack) {
  const std::vector<Vec2> big = {{0, 0}, {100, 0}, {100, 100}, {0, 100}};
  const std::vector<Vec2> small = {{90, 40}, {95, 40}, {95, 45}, {90, 45}};
  PlanarContact c;
  ASSERT_TRUE(contact::planar_overlap(big, small, c));
  EXPECT_NEAR(c.area, 25.0, 1e-9);
  EXPECT_EQ(c.chord, 0.0);
  // Least penetration: push the small square out through the right face (10 m to go).
  EXPECT_NEAR(c.normal.x(), 1.0, 1e-12);
  EXPECT_NEAR(c.depth, 10.0, 1e-9);
}

// Found by fuzzing (tests/fuzz/fuzz_polygon.cpp): the quick rejection along the line between the vertex means
// rejected every pair whose means coincide, so a polygon on itself, or one centred inside another, had no contact.
TEST(NarrowPhase, ConcentricPolygonsOverlap) {
  const std::vector<Vec2> sq = {{-5, -5}, {5, -5}, {5, 5}, {-5, 5}};
  PlanarContact c;
  ASSERT_TRUE(contact::planar_overlap(sq, sq, c, true));
  EXPECT_NEAR(c.area, 100.0, 1e-9);
  EXPECT_EQ(c.chord, 0.0);                                               // containment fallback
  EXPECT_NEAR(c.depth, 10.0, 1e-9);                                      // least penetration: the full width
  const std::vector<Vec2> diamond = {{0, -2}, {2, 0}, {0, 2}, {-2, 0}};  // same vertex mean, inside sq
  ASSERT_TRUE(contact::planar_overlap(sq, diamond, c));
  EXPECT_NEAR(c.area, 8.0, 1e-12);
  ASSERT_TRUE(contact::planar_overlap(diamond, sq, c));
  EXPECT_NEAR(c.area, 8.0, 1e-12);
}

// Found by fuzzing: a B smaller than the round-off of its coordinates relative to A's first vertex collapses there
// to a point that cuts nothing, and all of A was reported as the overlap.
TEST(NarrowPhase, PolygonBelowRoundOffIsNoLargerOverlapThanItself) {
  const std::vector<Vec2> sq = {{-1, -1}, {1, -1}, {1, 1}, {-1, 1}};
  const double s = 1e-20;  // relative to sq's first vertex, (1 +- 1e-20) rounds to 1
  const std::vector<Vec2> tiny = {{0, 0}, {s, 0}, {0, s}};
  PlanarContact c;
  const bool hit = contact::planar_overlap(sq, tiny, c);
  EXPECT_TRUE(!hit || c.area <= 0.5 * s * s) << c.area;
  // The other way round the tiny one is the frame and is resolved: the overlap is all of it.
  ASSERT_TRUE(contact::planar_overlap(tiny, sq, c));
  EXPECT_NEAR(c.area, 0.5 * s * s, 1e-12 * s * s);
}

// Found by fuzzing: two unit squares flush along a face, turned by ~1e-9 rad, overlap in a sliver whose area is
// round-off; its centroid came out 37 m from both. It is kept in the overlap's bounding box now.
TEST(NarrowPhase, RoundOffSliverCentroidStaysInTheOverlap) {
  const std::vector<Vec2> a = {{-0x1.fffffff768fa3p-2, -0x1.000000044b83p-1},
                               {0x1.000000044b831p-1, -0x1.fffffff768fa1p-2},
                               {0x1.fffffff768fa3p-2, 0x1.000000044b83p-1},
                               {-0x1.000000044b831p-1, 0x1.fffffff768fa1p-2}};
  const std::vector<Vec2> b = {{0x1.000000044b83p-1, -0x1.000000044b83p-1},
                               {0x1.8000000225c1ap+0, -0x1.fffffff768fa1p-2},
                               {0x1.7ffffffdda3eap+0, 0x1.000000044b83p-1},
                               {0x1.fffffff768fa2p-2, 0x1.fffffff768fa1p-2}};
  for (const bool swap : {false, true}) {
    SCOPED_TRACE(swap);
    PlanarContact c;
    if (!contact::planar_overlap(swap ? b : a, swap ? a : b, c, true)) continue;  // no contact is as good
    EXPECT_LE(c.area, 1e-14);
    EXPECT_NEAR(c.point.x(), 0.5, 1e-8);
    EXPECT_LE(std::abs(c.point.y()), 0.5 + 1e-8);
  }
}

// Found by fuzzing (tests/fuzz/regressions/fuzz_polygon/collapsed-sliver-far-from-origin-vertex): a 3e-8 m sliver
// triangle 9 m to the side of a 1 m x 866 m strip. Relative to the strip's first vertex (433 m away) round-off
// collapsed the triangle to a segment, whose two opposite half-planes clipped a round-off sliver out of the strip:
// a contact between polygons 8.5 m apart. The narrow phase now works relative to the smaller polygon's vertex and
// refuses a containment made of a collapsed outline.
TEST(NarrowPhase, SliverFarFromTheOtherPolygonsVertexIsNoContact) {
  const std::vector<Vec2> sliver = {{0x1.0000000013cc7p+3, -0x1.a00000010b59dp+3},
                                    {0x1.0000000013cc7p+3, -0x1.a00000010b59cp+3},
                                    {0x1.ffffffffb0ce4p+2, -0x1.9ffffffde94c7p+3}};
  const std::vector<Vec2> strip = {{-0x1.8p+0, -0x1.b1e4a94e8976bp+8},
                                   {-0x1.ffffffffffffep-2, -0x1.b1e4a94e8976bp+8},
                                   {-0x1.ffffffffffffep-2, 0x1.afe4a94e89769p+8},
                                   {-0x1.8p+0, 0x1.afe4a94e89769p+8}};
  ASSERT_EQ(geometry::convexity_error(sliver), "");
  PlanarContact c;
  EXPECT_FALSE(contact::planar_overlap(strip, sliver, c, true));
  EXPECT_FALSE(contact::planar_overlap(sliver, strip, c, true));
  // Moved into the strip, the sliver (1 ulp wide at one end) is thinner than the round-off of the strip's clipped
  // coordinates: a contact may or may not be found, but none larger than the sliver.
  std::vector<Vec2> inside = sliver;
  for (Vec2& v : inside) v.x() -= 9.0;
  for (const bool swap : {false, true}) {
    if (contact::planar_overlap(swap ? inside : strip, swap ? strip : inside, c)) {
      EXPECT_LE(c.area, 1e-20);
    }
  }
  // A small triangle (0.1 um) at the same place is found both ways with its area.
  const std::vector<Vec2> small = {{-1.0, -13.0}, {-1.0 + 1e-7, -13.0}, {-1.0, -13.0 + 1e-7}};
  for (const bool swap : {false, true}) {
    ASSERT_TRUE(contact::planar_overlap(swap ? small : strip, swap ? strip : small, c)) << swap;
    EXPECT_NEAR(c.area, 0.5e-14, 1e-5 * 0.5e-14) << swap;
  }
}

// The broad phase skips a listed pair while its bodies have moved less than separation_lower_bound at the last
// build, so the bound must never exceed the true distance. Against the distance computed by brute force (the
// smallest vertex-to-segment distance both ways, exact for disjoint convex polygons): never above it, equal to it
// when the closest features are a vertex and an edge (a square beside a square), <= 0 whenever the polygons
// overlap.
TEST(NarrowPhase, SeparationLowerBoundNeverExceedsTheDistance) {
  auto segment_distance = [](const Vec2& p, const Vec2& a, const Vec2& b) {
    const Vec2 e = b - a;
    const double t = std::clamp((p - a).dot(e) / e.squaredNorm(), 0.0, 1.0);
    return (p - (a + t * e)).norm();
  };
  auto distance = [&](const std::vector<Vec2>& a, const std::vector<Vec2>& b) {
    double d = std::numeric_limits<double>::infinity();
    for (int pass = 0; pass < 2; ++pass) {
      const auto& s = pass == 0 ? a : b;
      const auto& t = pass == 0 ? b : a;
      for (const Vec2& p : t)
        for (std::size_t i = 0; i < s.size(); ++i) d = std::min(d, segment_distance(p, s[i], s[(i + 1) % s.size()]));
    }
    return d;
  };
  std::mt19937_64 rng(777);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  int apart = 0, overlapping = 0;
  for (int it = 0; it < 20000; ++it) {
    const double sa = 5.0 + 95.0 * u(rng), sb = 5.0 + 95.0 * u(rng);
    const int na = 3 + static_cast<int>(u(rng) * 14), nb = 3 + static_cast<int>(u(rng) * 14);
    const auto a0 = tsupport::random_convex(rng, na, 0.5 * sa, 0.5 * sa * (0.4 + 0.6 * u(rng)));
    const auto b0 = tsupport::random_convex(rng, nb, 0.5 * sb, 0.5 * sb * (0.4 + 0.6 * u(rng)));
    const Vec2 far = (it % 10 == 0) ? Vec2(1.0e4, -1.0e4) : Vec2(0, 0);
    const auto a = tsupport::transform(a0, 6.3 * u(rng), far);
    const double dist = (0.5 * (sa + sb)) * (0.3 + 1.2 * u(rng));
    const double ang = 6.3 * u(rng);
    const auto b = tsupport::transform(b0, 6.3 * u(rng), far + dist * Vec2(std::cos(ang), std::sin(ang)));
    const double bound = contact::separation_lower_bound(a, b);
    PlanarContact c;
    if (contact::planar_overlap(a, b, c)) {
      ++overlapping;
      EXPECT_LE(bound, 0.0) << "pair " << it;
      continue;
    }
    if (tsupport::brute_area(a, b) > 0.0) continue;  // touching within round-off
    ++apart;
    EXPECT_LE(bound, distance(a, b) + 1e-9 * std::max(sa, sb)) << "pair " << it;
    EXPECT_GT(bound, -std::numeric_limits<double>::infinity()) << "pair " << it;
  }
  EXPECT_GT(apart, 5000);
  EXPECT_GT(overlapping, 5000);
  // A vertex-edge closest pair: the bound is the distance. Unit squares 0.25 m apart, and B turned a little.
  const std::vector<Vec2> sq{{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  EXPECT_NEAR(contact::separation_lower_bound(sq, shifted(sq, {1.25, 0.3})), 0.25, 1e-15);
  const auto turned = tsupport::transform(sq, 0.2, {1.5, 0.0});
  EXPECT_NEAR(contact::separation_lower_bound(sq, turned), distance(sq, turned), 1e-12);
  // Overlapping by 0.1 m along x: the bound is minus the penetration.
  EXPECT_NEAR(contact::separation_lower_bound(sq, shifted(sq, {0.9, 0.0})), -0.1, 1e-15);
}
