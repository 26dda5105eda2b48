// The libccd adapter (contact/narrow_phase_ccd.h) on cases with a known answer: boxes overlapping along one axis
// (plain and rotated, near the origin and far from it), a box resting into a larger one, separated and touching
// pairs, bad input, the support-call bound; and level floes (prisms with the same z-range), where plain libccd
// fails, against the exact minimum translation from separating axes.
#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include <array>
#include <cmath>
#include <iostream>
#include <numbers>
#include <random>
#include <string>
#include <vector>

#include "contact/narrow_phase_ccd.h"

using namespace polyfloe;
using contact::ccd_penetration;
using contact::CcdContact;
using contact::CcdMethod;
using contact::CcdSettings;
using contact::CcdStatus;
using contact::Vec3;
using Vec2 = Eigen::Vector2d;
using Mat3 = Eigen::Matrix3d;

namespace {

constexpr std::array kMethods{CcdMethod::gjk_epa, CcdMethod::gjk_epa_tiebreak, CcdMethod::mpr};

std::vector<Vec3> box(const Vec3& lo, const Vec3& hi) {
  std::vector<Vec3> v;
  for (int k = 0; k < 8; ++k) v.emplace_back(k & 1 ? hi.x() : lo.x(), k & 2 ? hi.y() : lo.y(), k & 4 ? hi.z() : lo.z());
  return v;
}

std::vector<Vec3> moved(const std::vector<Vec3>& v, const Mat3& r, const Vec3& t) {
  std::vector<Vec3> o;
  for (const Vec3& p : v) o.push_back(r * p + t);
  return o;
}

// A convex polygon extruded between z = -0.5 and z = +0.5, bottom ring then top ring (as ConvexPolyhedron::prism).
std::vector<Vec3> prism(const std::vector<Vec2>& poly) {
  std::vector<Vec3> v;
  for (const Vec2& p : poly) v.emplace_back(p.x(), p.y(), -0.5);
  for (const Vec2& p : poly) v.emplace_back(p.x(), p.y(), 0.5);
  return v;
}

// Valid output whatever the status: a failed query carries a reason, a contact finite numbers and a unit normal.
void expect_well_formed(const CcdContact& c) {
  if (c.status == CcdStatus::failed) {
    EXPECT_GT(std::string(c.reason).size(), 0u);
    return;
  }
  EXPECT_TRUE(std::isfinite(c.depth));
  EXPECT_GE(c.depth, 0.0);
  EXPECT_TRUE(c.normal.allFinite());
  EXPECT_NEAR(c.normal.norm(), 1.0, 1e-12);
  EXPECT_TRUE(c.point.allFinite());
}

void expect_contact(const CcdContact& c, double depth, const Vec3& normal, double tol, const std::string& what) {
  ASSERT_EQ(c.status, CcdStatus::contact) << what << " reason: " << c.reason;
  EXPECT_NEAR(c.depth, depth, tol) << what;
  EXPECT_LT((c.normal - normal).norm(), tol) << what << " normal " << c.normal.transpose();
}

// Exact minimum translation of B out of A for two convex polygons (separating axes over both edge-normal sets):
// moving B by depth * n separates them. Both polygons counter-clockwise.
struct Mtd2 {
  double depth;
  Vec2 n;
};
Mtd2 exact_mtd(const std::vector<Vec2>& pa, const std::vector<Vec2>& pb) {
  Mtd2 best{std::numeric_limits<double>::infinity(), Vec2::Zero()};
  for (const auto* poly : {&pa, &pb})
    for (std::size_t i = 0; i < poly->size(); ++i) {
      const Vec2 e = (*poly)[(i + 1) % poly->size()] - (*poly)[i];
      const Vec2 axis = Vec2(e.y(), -e.x()).normalized();
      for (const Vec2& n : {axis, Vec2(-axis)}) {
        double max_a = -1e300, min_b = 1e300;
        for (const Vec2& p : pa) max_a = std::max(max_a, p.dot(n));
        for (const Vec2& q : pb) min_b = std::min(min_b, q.dot(n));
        if (max_a - min_b < best.depth) best = {max_a - min_b, n};
      }
    }
  return best;
}

// Points on an ellipse (so in convex position), angles jittered around k equal sectors, counter-clockwise;
// k = `vertices`, or 5..20 at random when 0.
std::vector<Vec2> random_polygon(std::mt19937_64& rng, const Vec2& centre, int vertices) {
  std::uniform_real_distribution<double> u(0.0, 1.0);
  const int k = vertices > 0 ? vertices : 5 + static_cast<int>(u(rng) * 16.0);
  const double a = 0.5 * 5.0 * std::pow(20.0, u(rng));  // width 5..100 m
  const double b = a * (0.3 + 0.7 * u(rng));
  const double phi = 2.0 * std::numbers::pi * u(rng);
  const Eigen::Rotation2Dd rot(phi);
  std::vector<Vec2> p;
  for (int i = 0; i < k; ++i) {
    const double t = 2.0 * std::numbers::pi * (i + 0.1 + 0.8 * u(rng)) / k;
    p.push_back(centre + rot * Vec2(a * std::cos(t), b * std::sin(t)));
  }
  return p;
}

struct LevelPair {
  std::vector<Vec3> a, b;
  double depth;  // exact (overlapping pairs)
  Vec3 normal;   // exact, horizontal, from A to B (overlapping pairs)
};

// Two level prisms whose exact minimum translation is horizontal with depth 1 mm .. 10 cm: B starts deep in A,
// then moves along the exact direction n0 until the overlap along n0 is the target. Every other axis m then keeps
// an overlap >= target (it shrinks by at most the shift), so n0 stays the minimum; recomputed to be sure.
// `separated`: B moves on until the gap along n0 is the target instead (n0 separates them). `vertices`: per polygon,
// 0 for 5..20 at random.
LevelPair level_pair(std::mt19937_64& rng, bool separated = false, int vertices = 0) {
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (;;) {
    const Vec2 far(2000.0 * (u(rng) - 0.5), 2000.0 * (u(rng) - 0.5));  // away from the world origin
    const auto pa = random_polygon(rng, far, vertices);
    auto pb = random_polygon(rng, far + Vec2(2.0 * (u(rng) - 0.5), 2.0 * (u(rng) - 0.5)), vertices);
    const double target = 1e-3 * std::pow(100.0, u(rng));
    const Mtd2 m0 = exact_mtd(pa, pb);
    if (m0.depth <= target) continue;
    for (Vec2& q : pb) q += (m0.depth + (separated ? target : -target)) * m0.n;
    const Mtd2 m = exact_mtd(pa, pb);
    if (m.depth >= 1.0) continue;  // thicker than the floes: the vertical axis would win (never at these sizes)
    return {prism(pa), prism(pb), m.depth, Vec3(m.n.x(), m.n.y(), 0.0)};
  }
}

// The draws are sequenced (a function's arguments are evaluated in an order each compiler chooses: GCC's, last to
// first, is the one kept here, so that every compiler tests the same trials).
Mat3 random_rotation(std::mt19937_64& rng) {
  std::normal_distribution<double> g(0.0, 1.0);
  const double z = g(rng), y = g(rng), x = g(rng), w = g(rng);
  return Eigen::Quaterniond(w, x, y, z).normalized().toRotationMatrix();
}

}  // namespace

TEST(NarrowPhaseCcd, ToStringGivesEachMethodsSnakeCaseName) {
  EXPECT_STREQ(contact::to_string(CcdMethod::gjk_epa), "gjk_epa");
  EXPECT_STREQ(contact::to_string(CcdMethod::gjk_epa_tiebreak), "gjk_epa_tiebreak");
  EXPECT_STREQ(contact::to_string(CcdMethod::mpr), "mpr");
}

// Unit cubes, B shifted by ±0.9 along one axis (overlap 0.1) and by (0.3, 0.2) across it, so no faces are coplanar:
// depth 0.1 ± 1e-6, normal ±e_k ± 1e-6 pointing from A to B (the side B is on). This fixes libccd's sign.
TEST(NarrowPhaseCcd, CubesOverlappingATenthAlongAnAxisGiveThatDepthAndTheAxisNormalTowardsB) {
  const auto a = box(Vec3::Zero(), Vec3::Ones());
  for (const CcdMethod m : kMethods)
    for (int k = 0; k < 3; ++k)
      for (const double sign : {1.0, -1.0}) {
        Vec3 shift = Vec3::Zero();
        shift[k] = 0.9 * sign;
        shift[(k + 1) % 3] = 0.3;
        shift[(k + 2) % 3] = 0.2;
        const auto b = moved(a, Mat3::Identity(), shift);
        const std::string what =
            std::string(to_string(m)) + " axis " + std::to_string(k) + " sign " + std::to_string(sign);
        const CcdContact c = ccd_penetration(a, b, m);
        expect_contact(c, 0.1, sign * Vec3::Unit(k), 1e-6, what);
        // Moving B by depth * normal separates; by less it still overlaps (the sign check, stated directly).
        const auto out = moved(b, Mat3::Identity(), (c.depth + 1e-3) * c.normal);
        EXPECT_EQ(ccd_penetration(a, out, m).status, CcdStatus::separated) << what;
        // libccd's point is a heuristic (EPA: a mean of polytope vertices; it can lie outside the overlap): only ask
        // that it lies in the bounding box of A and B.
        const Vec3 lo = a.front().cwiseMin(b.front()) - Vec3::Constant(1e-9);
        const Vec3 hi = a.back().cwiseMax(b.back()) + Vec3::Constant(1e-9);
        EXPECT_TRUE((c.point.array() >= lo.array()).all() && (c.point.array() <= hi.array()).all())
            << what << " point " << c.point.transpose();
      }
}

// The same with B level with A across the axis (all side faces coplanar, libccd's degenerate case in miniature):
// depth 0.1 ± 1e-6, normal ±e_k ± 1e-6.
TEST(NarrowPhaseCcd, CubesLevelAcrossTheAxisWithCoplanarSideFacesStillGiveTheDepthAndNormal) {
  const auto a = box(Vec3::Zero(), Vec3::Ones());
  for (const CcdMethod m : kMethods)
    for (int k = 0; k < 3; ++k)
      for (const double sign : {1.0, -1.0})
        expect_contact(ccd_penetration(a, moved(a, Mat3::Identity(), 0.9 * sign * Vec3::Unit(k)), m), 0.1,
                       sign * Vec3::Unit(k), 1e-6, std::string(to_string(m)) + " axis " + std::to_string(k));
}

// 20 random rotations of the offset pair, placed up to 1 km from the world origin: depth 0.1 ± 1e-6, normal
// R * (±e_k) ± 1e-6.
TEST(NarrowPhaseCcd, RandomlyRotatedAndMovedCubesGiveTheRotatedAxisNormalAndDepth) {
  std::mt19937_64 rng(2024);
  std::uniform_real_distribution<double> u(-1000.0, 1000.0);
  const auto a0 = box(Vec3::Zero(), Vec3::Ones());
  for (int trial = 0; trial < 20; ++trial) {
    const Mat3 r = random_rotation(rng);
    const double tz = u(rng), ty = u(rng), tx = u(rng);  // sequenced as random_rotation's draws
    const Vec3 t(tx, ty, tz);
    const int k = trial % 3;
    const double sign = trial % 2 ? -1.0 : 1.0;
    Vec3 shift = Vec3::Zero();
    shift[k] = 0.9 * sign;
    shift[(k + 1) % 3] = 0.3;
    shift[(k + 2) % 3] = 0.2;
    const auto a = moved(a0, r, t);
    const auto b = moved(a0, r, t + r * shift);
    for (const CcdMethod m : kMethods)
      expect_contact(ccd_penetration(a, b, m), 0.1, sign * (r * Vec3::Unit(k)), 1e-6,
                     std::string(to_string(m)) + " trial " + std::to_string(trial));
  }
}

// A 1 m cube 5 cm deep in the top of a 10 x 8 x 1 m slab: depth 0.05 ± 1e-6, normal +z (slab first) or -z.
TEST(NarrowPhaseCcd, CubeSunkFiveCentimetresIntoASlabGivesThatDepthAndTheVerticalNormalFromAToB) {
  const auto slab = box(Vec3(-5.0, -4.0, -1.0), Vec3(5.0, 4.0, 0.0));
  const auto cube = box(Vec3(0.5, -0.3, -0.05), Vec3(1.5, 0.7, 0.95));
  for (const CcdMethod m : kMethods) {
    expect_contact(ccd_penetration(slab, cube, m), 0.05, Vec3::UnitZ(), 1e-6, to_string(m));
    expect_contact(ccd_penetration(cube, slab, m), 0.05, -Vec3::UnitZ(), 1e-6, to_string(m));
  }
}

TEST(NarrowPhaseCcd, CubesWithAGapAlongAnAxisADiagonalOrFarAboveAreSeparated) {
  const auto a = box(Vec3::Zero(), Vec3::Ones());
  for (const CcdMethod m : kMethods) {
    EXPECT_EQ(ccd_penetration(a, moved(a, Mat3::Identity(), Vec3(1.1, 0.3, 0.2)), m).status, CcdStatus::separated);
    EXPECT_EQ(ccd_penetration(a, moved(a, Mat3::Identity(), Vec3(1.05, 1.05, 1.05)), m).status, CcdStatus::separated);
    EXPECT_EQ(ccd_penetration(a, moved(a, Mat3::Identity(), Vec3(0.0, 0.0, 50.0)), m).status, CcdStatus::separated);
  }
}

// Faces in contact with zero depth (offset and level-aligned, as floes of a tessellated sheet): separated for every
// method. libccd exits these as "touching" with depth ~1e-16 and an arbitrary (EPA) or zero (MPR) direction.
// A touch is never a contact: separated, or failed as a zero-depth intersection (which EPA's tie exit on overlapping
// floes looks the same as).
TEST(NarrowPhaseCcd, TouchingPairIsNeverAContact) {
  const auto a = box(Vec3::Zero(), Vec3::Ones());
  for (const Vec3& shift : {Vec3(1.0, 0.3, 0.2), Vec3(1.0, 0.0, 0.0), Vec3(0.0, 1.0, 0.0), Vec3(0.2, 0.3, -1.0)})
    for (const CcdMethod m : kMethods) {
      const CcdContact c = ccd_penetration(a, moved(a, Mat3::Identity(), shift), m);
      EXPECT_NE(c.status, CcdStatus::contact) << to_string(m) << " shift " << shift.transpose() << ": " << c.reason;
    }
}

TEST(NarrowPhaseCcd, BadInputFailsWithAReason) {
  const auto a = box(Vec3::Zero(), Vec3::Ones());
  auto nan_box = a;
  nan_box[3].y() = std::numeric_limits<double>::quiet_NaN();
  const std::vector<Vec3> point{Vec3(0.5, 0.5, 0.5)};
  CcdSettings bad_tol;
  bad_tol.epa_tolerance = 0.0;
  for (const CcdMethod m : kMethods) {
    EXPECT_EQ(ccd_penetration({}, a, m).status, CcdStatus::failed);
    EXPECT_EQ(ccd_penetration(a, nan_box, m).status, CcdStatus::failed);
    EXPECT_EQ(ccd_penetration(point, point, m).status, CcdStatus::failed);
    EXPECT_EQ(ccd_penetration(a, a, m, bad_tol).status, CcdStatus::failed);
  }
}

// max_support_calls = 5 on pairs that need more unbounded (cubes, 40 level-floe pairs): the query ends, failed,
// with the bound's reason, after few support calls (< 100: no hang). And every bound from 0 to 60 on every pair
// fails (within 3 x bound + 100 calls: after the freeze EPA ends within the polytope's face count) if the
// unbounded query needs more calls, else gives exactly the unbounded answer.
TEST(NarrowPhaseCcd, SupportCallBoundEndsTheQuery) {
  std::mt19937_64 rng(7);
  const auto cube = box(Vec3::Zero(), Vec3::Ones());
  std::vector<std::pair<std::vector<Vec3>, std::vector<Vec3>>> pairs{
      {cube, moved(cube, Mat3::Identity(), Vec3(0.9, 0.3, 0.2))},
      {cube, moved(cube, Mat3::Identity(), Vec3(0.9, 0.0, 0.0))}};
  for (int i = 0; i < 40; ++i) {
    LevelPair p = level_pair(rng);
    pairs.emplace_back(std::move(p.a), std::move(p.b));
  }
  for (const CcdMethod m : kMethods) {
    int bounded = 0;
    for (const auto& [a, b] : pairs) {
      const CcdContact free = ccd_penetration(a, b, m);
      ASSERT_NE(free.status, CcdStatus::failed) << to_string(m) << ": " << free.reason;
      CcdSettings s;
      s.max_support_calls = 5;
      if (free.support_calls > 5) {
        ++bounded;
        const CcdContact c = ccd_penetration(a, b, m, s);
        EXPECT_EQ(c.status, CcdStatus::failed) << to_string(m);
        EXPECT_STREQ(c.reason, m == CcdMethod::mpr ? "MPR iteration bound reached" : "EPA iteration bound reached");
        EXPECT_GT(c.support_calls, 5) << to_string(m);
        EXPECT_LT(c.support_calls, 100) << to_string(m);
      }
      for (int bound = 0; bound <= 60; ++bound) {
        s.max_support_calls = bound;
        const CcdContact r = ccd_penetration(a, b, m, s);
        if (bound < free.support_calls) {
          EXPECT_EQ(r.status, CcdStatus::failed) << to_string(m) << " bound " << bound;
          EXPECT_LT(r.support_calls, 3 * bound + 100) << to_string(m) << " bound " << bound;
          continue;
        }
        EXPECT_EQ(r.status, free.status) << to_string(m) << " bound " << bound;
        EXPECT_EQ(r.depth, free.depth) << to_string(m) << " bound " << bound;
        EXPECT_EQ(r.normal, free.normal) << to_string(m) << " bound " << bound;
        EXPECT_EQ(r.support_calls, free.support_calls) << to_string(m) << " bound " << bound;
      }
    }
    EXPECT_GE(bounded, 20) << to_string(m) << ": too few pairs need more than 5 support calls";
  }
}

// Level floes: 5,000 pairs of prisms with the same z-range [-0.5, 0.5] m (random convex polygons, 5-20 vertices,
// widths 5-100 m, 1 km from the origin, exact horizontal overlap 1 mm - 10 cm, seed 31). Every answer must be
// well formed (failed, or finite depth >= 0 with a unit normal: never NaN). Counted per method: failed, missed
// (separated), wrong normal (> 1 degree from the exact direction), wrong depth (> 1e-4 m off with a right normal;
// the tolerance is 1e-6 x the pair's size, <= 7e-5 m here). No method may give a wrong answer (missed + wrong
// normal + wrong depth): plain libccd's false touching exits on these ties must come out as failures (the caller
// then asks the exact method), and tie-breaking must fail no more often than plain libccd.
TEST(NarrowPhaseCcd, LevelFloesNeverGetAWrongAnswerAndTieBreakingFailsNoMoreThanPlainLibccd) {
  constexpr int kPairs = 5000;
  std::mt19937_64 rng(31);
  std::vector<LevelPair> pairs;
  for (int i = 0; i < kPairs; ++i) pairs.push_back(level_pair(rng));
  const double cos_1deg = std::cos(std::numbers::pi / 180.0);
  std::array<int, kMethods.size()> wrong{}, failures{};
  for (std::size_t mi = 0; mi < kMethods.size(); ++mi) {
    int failed = 0, missed = 0, wrong_normal = 0, wrong_depth = 0, right = 0, max_calls = 0;
    long calls = 0;
    for (const LevelPair& p : pairs) {
      const CcdContact c = ccd_penetration(p.a, p.b, kMethods[mi]);
      expect_well_formed(c);
      calls += c.support_calls;
      max_calls = std::max(max_calls, c.support_calls);
      if (c.status == CcdStatus::failed)
        ++failed;
      else if (c.status == CcdStatus::separated)
        ++missed;
      else if (c.normal.dot(p.normal) < cos_1deg)
        ++wrong_normal;
      else if (std::abs(c.depth - p.depth) > 1e-4)
        ++wrong_depth;
      else
        ++right;
    }
    wrong[mi] = missed + wrong_normal + wrong_depth;
    failures[mi] = failed;
    std::cout << "[ level floes ] " << to_string(kMethods[mi]) << ": of " << kPairs << " failed " << failed
              << ", missed " << missed << ", wrong normal " << wrong_normal << ", wrong depth " << wrong_depth
              << ", right " << right << "; support calls mean " << static_cast<double>(calls) / kPairs << " max "
              << max_calls << "\n";
  }
  for (std::size_t mi = 0; mi < kMethods.size(); ++mi) EXPECT_EQ(wrong[mi], 0) << to_string(kMethods[mi]);
  EXPECT_LE(failures[1], failures[0]);
}

// Hexagonal level floes 1 mm - 10 cm apart (5,000 pairs, seed 32): never a contact. libccd's MPR claims some of
// these intersect (the gap as depth, a normal from B to A); the adapter's consistency check makes them failures.
TEST(NarrowPhaseCcd, SeparatedLevelFloesAreNeverContacts) {
  constexpr int kPairs = 5000;
  std::mt19937_64 rng(32);
  std::vector<LevelPair> pairs;
  for (int i = 0; i < kPairs; ++i) pairs.push_back(level_pair(rng, true, 6));
  for (const CcdMethod m : kMethods) {
    int failed = 0;
    for (const LevelPair& p : pairs) {
      const CcdContact c = ccd_penetration(p.a, p.b, m);
      expect_well_formed(c);
      EXPECT_NE(c.status, CcdStatus::contact) << to_string(m) << " depth " << c.depth;
      failed += c.status == CcdStatus::failed;
    }
    std::cout << "[ separated level floes ] " << to_string(m) << ": of " << kPairs << " failed " << failed
              << ", separated " << kPairs - failed << "\n";
  }
}
