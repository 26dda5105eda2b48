// Floe-field generator: determinism, concentration, no overlaps (checked with an independent polygon test),
// convexity, size bounds, obstacles, failure messages; the realised statistics of generated fields.
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include "geometry/polygon.h"
#include "scene/field_statistics.h"
#include "scene/floe_field.h"

namespace polyfloe::scene {
namespace {

using geometry::cross;

std::vector<Vec2> world_vertices(const dynamics::BodyDesc& d) {
  const double c = std::cos(d.yaw), s = std::sin(d.yaw);
  std::vector<Vec2> v;
  for (const Vec2& x : d.shape->vertices()) v.push_back(d.position + geometry::rotate(x, c, s));
  return v;
}

// --- an independent polygon test: segment distances and point containment, no separating axes ---

double point_segment_distance(const Vec2& p, const Vec2& a, const Vec2& b) {
  const Vec2 ab = b - a;
  const double t = std::clamp((p - a).dot(ab) / ab.squaredNorm(), 0.0, 1.0);
  return (p - (a + t * ab)).norm();
}

bool segments_cross(const Vec2& a, const Vec2& b, const Vec2& c, const Vec2& d) {
  const double d1 = cross(b - a, c - a), d2 = cross(b - a, d - a);
  const double d3 = cross(d - c, a - c), d4 = cross(d - c, b - c);
  return ((d1 > 0) != (d2 > 0)) && ((d3 > 0) != (d4 > 0)) && d1 != 0 && d2 != 0 && d3 != 0 && d4 != 0;
}

bool strictly_inside(const Vec2& p, const std::vector<Vec2>& poly) {  // convex, counter-clockwise
  for (std::size_t i = 0; i < poly.size(); ++i)
    if (cross(poly[(i + 1) % poly.size()] - poly[i], p - poly[i]) <= 0.0) return false;
  return true;
}

// Distance between two convex polygons; 0 when they intersect.
double polygon_distance(const std::vector<Vec2>& a, const std::vector<Vec2>& b) {
  for (std::size_t i = 0; i < a.size(); ++i)
    for (std::size_t j = 0; j < b.size(); ++j)
      if (segments_cross(a[i], a[(i + 1) % a.size()], b[j], b[(j + 1) % b.size()])) return 0.0;
  if (strictly_inside(a[0], b) || strictly_inside(b[0], a)) return 0.0;
  double d = INFINITY;
  for (std::size_t i = 0; i < a.size(); ++i)
    for (std::size_t j = 0; j < b.size(); ++j) {
      d = std::min(d, point_segment_distance(a[i], b[j], b[(j + 1) % b.size()]));
      d = std::min(d, point_segment_distance(b[j], a[i], a[(i + 1) % a.size()]));
    }
  return d;
}

double size_of(const dynamics::BodyDesc& d) { return std::sqrt(4.0 * d.shape->area() / std::numbers::pi); }

FloeFieldSpec small_spec(double concentration = 0.5) {
  FloeFieldSpec s;
  s.region_min = {0.0, 0.0};
  s.region_max = {250.0, 200.0};
  s.concentration = concentration;
  s.size_min = 5.0;
  s.size_max = 40.0;
  s.exponent = 2.0;
  s.corners_min = 5;
  s.corners_max = 10;
  s.seed = 7;
  return s;
}

FloeFieldSpec paper_spec(double concentration) {
  FloeFieldSpec s;  // defaults: 1 km x 1 km, sizes 5-100 m, alpha 2, 5-10 corners
  s.concentration = concentration;
  s.seed = 1;
  return s;
}

// --- random numbers and the size distribution ---

TEST(FieldRandom, UniformIsInUnitIntervalAndIntsCoverTheirRange) {
  FieldRandom r(3);
  std::vector<int> seen(7, 0);
  for (int i = 0; i < 20000; ++i) {
    const double u = r.uniform();
    ASSERT_GE(u, 0.0);
    ASSERT_LT(u, 1.0);
    const int k = r.uniform_int(5, 11);
    ASSERT_GE(k, 5);
    ASSERT_LE(k, 11);
    ++seen[static_cast<std::size_t>(k - 5)];
  }
  for (int n : seen) EXPECT_NEAR(n, 20000 / 7.0, 300);
}

TEST(FieldRandom, SameSeedSameSequence) {
  FieldRandom a(42), b(42), c(43);
  bool differs = false;
  for (int i = 0; i < 100; ++i) {
    const double x = a.uniform();
    EXPECT_EQ(x, b.uniform());
    differs = differs || x != c.uniform();
  }
  EXPECT_TRUE(differs);
}

TEST(PowerLaw, QuantileEndpointsAndMonotone) {
  for (double alpha : {0.0, 0.5, 1.0, 1.2, 2.0, 3.5}) {
    EXPECT_NEAR(power_law_quantile(0.0, 5.0, 100.0, alpha), 5.0, 1e-12) << alpha;
    EXPECT_NEAR(power_law_quantile(1.0, 5.0, 100.0, alpha), 100.0, 1e-9) << alpha;
    double prev = 0.0;
    for (int i = 0; i <= 100; ++i) {
      const double x = power_law_quantile(i / 100.0, 5.0, 100.0, alpha);
      EXPECT_GE(x, prev);
      prev = x;
    }
  }
  // alpha = 1 is the log-uniform law; alpha -> 1 from either side approaches it.
  EXPECT_NEAR(power_law_quantile(0.5, 5.0, 100.0, 1.0), std::sqrt(500.0), 1e-12);
  EXPECT_NEAR(power_law_quantile(0.5, 5.0, 100.0, 1.0 + 1e-7), std::sqrt(500.0), 1e-4);
}

TEST(PowerLaw, SampleMatchesTheCdf) {
  // F(x) = (x^-1 - a^-1) / (b^-1 - a^-1) for alpha = 2.
  FieldRandom r(11);
  const int n = 200000;
  std::vector<double> x(n);
  for (double& v : x) v = power_law_quantile(r.uniform(), 5.0, 100.0, 2.0);
  for (double probe : {6.0, 10.0, 20.0, 50.0}) {
    const double expected = (1.0 / probe - 0.2) / (0.01 - 0.2);
    const double got = static_cast<double>(std::count_if(x.begin(), x.end(), [&](double v) { return v <= probe; })) / n;
    EXPECT_NEAR(got, expected, 0.005) << probe;
  }
}

TEST(FloeSizes, TotalAreaIsTheTargetAndSizesStayInBounds) {
  for (double c : {0.05, 0.3, 0.5, 0.6}) {
    FloeFieldSpec s = small_spec(c);
    FieldRandom r(s.seed);
    const std::vector<double> sizes = floe_sizes(s, r);
    double area = 0.0;
    for (double x : sizes) {
      EXPECT_GE(x, s.size_min);
      EXPECT_LE(x, s.size_max);
      area += std::numbers::pi * x * x / 4.0;
    }
    EXPECT_NEAR(area / (250.0 * 200.0), c, 1e-9);
    EXPECT_TRUE(std::is_sorted(sizes.rbegin(), sizes.rend()));
  }
}

TEST(FloeSizes, TooSmallARegionIsAnError) {
  FloeFieldSpec s = small_spec(0.01);
  s.region_max = {5.0, 5.0};  // 0.25 m^2 of ice wanted, one 5 m floe is 19.6 m^2
  FieldRandom r(1);
  EXPECT_THROW(floe_sizes(s, r), SceneError);
}

// Found while bounding the fuzzer's work (tests/fuzz/fuzz_scene_parser.cpp): a region given in the wrong unit
// (or one whose area overflows to inf) drew sizes until the memory ran out; now it is an error naming the keys.
TEST(FloeSizes, TooManyFloesIsAnError) {
  FloeFieldSpec s = small_spec(0.5);
  s.region_min = {-1e300, -1e300};  // the area overflows to inf; [0, 0, 1e6, 1e6] (mm taken for m) is as bad
  s.region_max = {1e300, 1e300};
  FieldRandom r(1);
  try {
    (void)floe_sizes(s, r);
    ADD_FAILURE() << "accepted";
  } catch (const SceneError& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("needs more than 10000000 floes"), std::string::npos) << m;
    EXPECT_NE(m.find("shrink floe_field.region"), std::string::npos) << m;
  }
}

// --- shapes ---

TEST(FloePolygon, ConvexCounterClockwiseExactAreaCentred) {
  FieldRandom r(5);
  for (int i = 0; i < 2000; ++i) {
    const int k = r.uniform_int(3, 20);
    const double size = power_law_quantile(r.uniform(), 5.0, 100.0, 2.0);
    const std::vector<Vec2> v = random_floe_polygon(r, k, size);
    ASSERT_EQ(static_cast<int>(v.size()), k);
    ASSERT_EQ(geometry::convexity_error(v), "");
    const geometry::PolygonProperties p = geometry::polygon_properties(v);
    EXPECT_NEAR(p.area, std::numbers::pi * size * size / 4.0, 1e-9 * size * size);
    EXPECT_NEAR(p.centroid.norm(), 0.0, 1e-9 * size);
  }
}

TEST(FloePolygon, MeanCircularityGrowsWithCorners) {
  auto mean_circularity = [](int lo, int hi) {
    FieldRandom r(9);
    double sum = 0.0;
    for (int i = 0; i < 4000; ++i) {
      const auto v = random_floe_polygon(r, r.uniform_int(lo, hi), 10.0);
      const auto p = geometry::polygon_properties(v);
      sum += geometry::circularity(p.area, p.perimeter);
    }
    return sum / 4000;
  };
  const double c5 = mean_circularity(5, 10), c10 = mean_circularity(10, 15), c15 = mean_circularity(15, 20);
  EXPECT_LT(c5, c10);
  EXPECT_LT(c10, c15);
  EXPECT_GT(c5, 0.75);
  EXPECT_LT(c15, 1.0);
}

TEST(PolygonSeparation, SquaresApartOverlappingAndTouchingGiveTheSignedGapAndTheDistanceAgrees) {
  const std::vector<Vec2> a{{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  const std::vector<Vec2> b{{3, 0}, {4, 0}, {4, 1}, {3, 1}};
  const std::vector<Vec2> c{{0.75, 0.5}, {1.75, 0.5}, {1.75, 1.5}, {0.75, 1.5}};
  const std::vector<Vec2> d{{1, 0}, {2, 0}, {2, 1}, {1, 1}};
  EXPECT_NEAR(polygon_separation(a, b), 2.0, 1e-12);
  EXPECT_NEAR(polygon_separation(a, c), -0.25, 1e-12);
  EXPECT_NEAR(polygon_separation(a, d), 0.0, 1e-12);
  // The tests' own distance agrees.
  EXPECT_NEAR(polygon_distance(a, b), 2.0, 1e-12);
  EXPECT_EQ(polygon_distance(a, c), 0.0);
  const std::vector<Vec2> inner{{0.25, 0.25}, {0.75, 0.25}, {0.75, 0.75}, {0.25, 0.75}};
  EXPECT_EQ(polygon_distance(a, inner), 0.0);
  const std::vector<Vec2> diagonal{{2, 2}, {3, 2}, {3, 3}, {2, 3}};
  EXPECT_NEAR(polygon_distance(a, diagonal), std::sqrt(2.0), 1e-12);
}

// --- the generated field ---

void expect_valid_field(const FloeFieldSpec& s, const FloeField& f, bool pairwise) {
  ASSERT_FALSE(f.floes.empty());
  const double region = (s.region_max - s.region_min).prod();
  double area = 0.0;
  for (std::size_t i = 0; i < f.floes.size(); ++i) {
    const dynamics::BodyDesc& d = f.floes[i];
    EXPECT_EQ(geometry::convexity_error(d.shape->vertices()), "") << i;
    EXPECT_GE(d.shape->size(), s.corners_min);
    EXPECT_LE(d.shape->size(), s.corners_max);
    EXPECT_GE(size_of(d), s.size_min * (1 - 1e-9));
    EXPECT_LE(size_of(d), s.size_max * (1 + 1e-9));
    EXPECT_EQ(d.motion, dynamics::Motion::dynamic);
    EXPECT_EQ(d.thickness, s.thickness);
    for (const Vec2& v : world_vertices(d)) {
      EXPECT_GE(v.x(), s.region_min.x() - 1e-9);
      EXPECT_GE(v.y(), s.region_min.y() - 1e-9);
      EXPECT_LE(v.x(), s.region_max.x() + 1e-9);
      EXPECT_LE(v.y(), s.region_max.y() + 1e-9);
    }
    area += d.shape->area();
  }
  EXPECT_NEAR(area / region, s.concentration, 0.005);
  EXPECT_NEAR(f.concentration, area / region, 1e-12);
  if (!pairwise) return;
  std::vector<std::vector<Vec2>> w;
  std::vector<geometry::Aabb> box;
  for (const auto& d : f.floes) {
    w.push_back(world_vertices(d));
    geometry::Aabb b{w.back()[0], w.back()[0]};
    for (const Vec2& v : w.back()) b.lo = b.lo.cwiseMin(v), b.hi = b.hi.cwiseMax(v);
    box.push_back(b);
  }
  // Every pair: the boxes' gap is a lower bound of the polygons' distance, so only pairs with close boxes need the
  // exact distance.
  for (std::size_t i = 0; i < w.size(); ++i)
    for (std::size_t j = i + 1; j < w.size(); ++j) {
      const double gap = placement_clearance(std::min(size_of(f.floes[i]), size_of(f.floes[j])));
      const Vec2 box_gap = (box[i].lo - box[j].hi).cwiseMax(box[j].lo - box[i].hi);
      if (box_gap.maxCoeff() >= gap) continue;
      ASSERT_GE(polygon_distance(w[i], w[j]), gap * (1 - 1e-9)) << "floes " << i << " and " << j;
    }
}

TEST(FloeField, SmallFieldHasNoOverlapsAndHitsTheConcentration) {
  for (double c : {0.3, 0.5, 0.6}) {
    const FloeFieldSpec s = small_spec(c);
    const FloeField f = generate_floe_field(s, 920.0, 100);
    SCOPED_TRACE(c);
    expect_valid_field(s, f, true);
    for (std::size_t i = 0; i < f.floes.size(); ++i) {
      EXPECT_EQ(f.floes[i].id, 100 + i);
      EXPECT_EQ(f.floes[i].density, 920.0);
      if (i > 0) {
        EXPECT_LE(size_of(f.floes[i]), size_of(f.floes[i - 1]) * (1 + 1e-12));  // largest first
      }
    }
  }
}

TEST(FloeField, DeterministicForASeed) {
  FloeFieldSpec s = small_spec(0.5);
  const FloeField a = generate_floe_field(s, 920.0, 0);
  const FloeField b = generate_floe_field(s, 920.0, 0);
  ASSERT_EQ(a.floes.size(), b.floes.size());
  for (std::size_t i = 0; i < a.floes.size(); ++i) {
    EXPECT_EQ(a.floes[i].position, b.floes[i].position);
    EXPECT_EQ(a.floes[i].shape->vertices(), b.floes[i].shape->vertices());
  }
  s.seed = 8;
  const FloeField c = generate_floe_field(s, 920.0, 0);
  EXPECT_NE(a.floes[0].position, c.floes[0].position);
}

TEST(FloeField, KeepsClearOfObstacles) {
  const FloeFieldSpec s = small_spec(0.45);
  const std::vector<std::vector<Vec2>> obstacles{{{100, 80}, {150, 80}, {150, 120}, {100, 120}},
                                                 {{-50, -50}, {300, -50}, {300, 0}, {-50, 0}}};
  const FloeField f = generate_floe_field(s, 920.0, 0, obstacles);
  for (const auto& d : f.floes) {
    const auto v = world_vertices(d);
    for (const auto& o : obstacles) EXPECT_GE(polygon_distance(v, o), placement_clearance(size_of(d)) * (1 - 1e-9));
  }
}

// (speed: tests/bench/bench_floe_field.cpp)
TEST(FloeField, PaperFieldsAt50And60PercentAreValidAndAt50PercentNearThePapersFloeCount) {
  for (double c : {0.5, 0.6}) {
    const FloeFieldSpec s = paper_spec(c);
    const FloeField f = generate_floe_field(s, 920.0, 0);
    std::printf("1 km x 1 km field at %.0f %%: %zu floes, concentration %.6f, %llu attempts\n", 100 * c, f.floes.size(),
                f.concentration, static_cast<unsigned long long>(f.attempts));
    SCOPED_TRACE(c);
    expect_valid_field(s, f, true);
    if (c == 0.5) {
      EXPECT_GT(f.floes.size(), 1100u);  // the paper reports 1243
      EXPECT_LT(f.floes.size(), 1450u);
    }
  }
}

TEST(FloeField, VoronoiFieldIsValidAveragesSixCornersAndRefusesACornerRangeNoCellGives) {
  // Outlines cut from Poisson-Voronoi tessellations: a valid field (convex, sizes exact, no overlaps, the
  // concentration), the corner range honoured, deterministic for a seed; over the full range the mean corner count
  // is the tessellation's: 6 (Euler's formula for a planar tiling with degree-3 vertices), less the few corners that
  // merging edges shorter than 1e-3 of the perimeter removes.
  FloeFieldSpec s = paper_spec(0.6);
  s.shape = FloeShape::voronoi;
  s.corners_min = 3;
  s.corners_max = 64;
  const FloeField f = generate_floe_field(s, 920.0, 0);
  expect_valid_field(s, f, true);
  double corners = 0.0;
  for (const auto& d : f.floes) corners += static_cast<double>(d.shape->size());
  corners /= static_cast<double>(f.floes.size());
  EXPECT_NEAR(corners, 6.0, 0.15) << f.floes.size() << " floes";
  const FloeField again = generate_floe_field(s, 920.0, 0);
  ASSERT_EQ(again.floes.size(), f.floes.size());
  for (std::size_t i = 0; i < f.floes.size(); ++i)
    ASSERT_EQ(again.floes[i].shape->vertices(), f.floes[i].shape->vertices()) << i;
  // Only the outlines differ from an ellipse field of the same seed: the sizes are the same draws.
  FloeFieldSpec e = s;
  e.shape = FloeShape::ellipse;
  e.corners_min = 5;
  e.corners_max = 10;
  const FloeField ellipse = generate_floe_field(e, 920.0, 0);
  EXPECT_EQ(ellipse.floes.size(), f.floes.size());
  EXPECT_NEAR(ellipse.floes.front().shape->area(), f.floes.front().shape->area(), 1e-9 * f.floes.front().shape->area());
  // A narrower range is honoured.
  s.corners_min = 7;
  s.corners_max = 9;
  expect_valid_field(s, generate_floe_field(s, 920.0, 0), false);
  // Ranges the tessellation cannot give are refused with the reason.
  s.corners_min = 15;
  s.corners_max = 20;
  try {
    generate_floe_field(s, 920.0, 0);
    ADD_FAILURE() << "expected a SceneError";
  } catch (const SceneError& err) {
    EXPECT_NE(std::string(err.what()).find("floe_field.corners: only 0 of 65536 Voronoi cells have 15 to 20 corners"),
              std::string::npos)
        << err.what();
  }
}

TEST(FloeField, GivesUpWithAHelpfulMessage) {
  FloeFieldSpec s = small_spec(0.65);
  s.size_min = s.size_max = 30.0;  // equal discs jam near 55 %
  s.max_attempts = 200;
  s.source.where = "jam.yaml:4:3";
  try {
    generate_floe_field(s, 920.0, 0);
    FAIL() << "expected a SceneError";
  } catch (const SceneError& e) {
    const std::string m = e.what();
    EXPECT_EQ(m.rfind("jam.yaml:4:3: floe_field: could not place floe ", 0), 0u) << m;
    EXPECT_NE(m.find("after 200 attempts"), std::string::npos) << m;
    EXPECT_NE(m.find("concentration reached"), std::string::npos) << m;
    EXPECT_NE(m.find("lower floe_field.concentration"), std::string::npos) << m;
  }
}

TEST(FloeField, FloeLargerThanRegionIsAnError) {
  FloeFieldSpec s = small_spec(0.1);
  s.region_max = {30.0, 500.0};
  s.size_min = s.size_max = 40.0;
  EXPECT_THROW(generate_floe_field(s, 920.0, 0), SceneError);
}

// --- realised statistics ---

TEST(FieldStatistics, PowerLawFitRecoversTheExponentWithItsStandardError) {
  // Exact inverse-CDF samples: over 200 replicates of 400 samples the estimates scatter around alpha with the
  // spread the Fisher information predicts (within 15 %), and the mean bias is below 0.3 standard errors.
  for (double alpha : {0.5, 1.0, 1.2, 1.6, 2.0, 3.0}) {
    FieldRandom rng(7);
    double sum = 0.0, sum2 = 0.0, se = 0.0;
    const int reps = 200;
    for (int r = 0; r < reps; ++r) {
      std::vector<double> x(400);
      for (double& v : x) v = power_law_quantile(rng.uniform(), 5.0, 100.0, alpha);
      const PowerLawFit fit = fit_power_law(x, 5.0, 100.0);
      sum += fit.exponent;
      sum2 += fit.exponent * fit.exponent;
      se += fit.standard_error;
    }
    const double mean = sum / reps, sd = std::sqrt(sum2 / reps - mean * mean);
    se /= reps;
    std::printf("alpha %.1f: mean estimate %.4f, spread %.4f, predicted standard error %.4f\n", alpha, mean, sd, se);
    EXPECT_LT(std::abs(mean - alpha), 0.3 * se) << alpha;
    EXPECT_NEAR(sd / se, 1.0, 0.15) << alpha;
  }
}

TEST(FieldStatistics, PaperCircularitiesForTheCornerRanges) {
  // Paper section 2.2 (60 %, alpha = 2): corners 5-10 / 10-15 / 15-20 give mean circularity 0.83 / 0.90 / 0.92.
  // With the default aspect_max = 2.5 the fields land within 2 % (acceptance: 5 %), over three seeds each.
  const std::pair<int, double> ranges[] = {{5, 0.83}, {10, 0.90}, {15, 0.92}};
  for (const auto& [lo, paper] : ranges) {
    double sum = 0.0;
    std::size_t floes = 0;
    for (std::uint64_t seed : {1u, 2u, 3u}) {
      FloeFieldSpec s = paper_spec(0.6);
      s.corners_min = lo;
      s.corners_max = lo + 5;
      s.seed = seed;
      const FloeField f = generate_floe_field(s, 920.0, 0);
      const FieldStatistics st = field_statistics(f.floes, f.region_area, s.size_min, s.size_max);
      sum += st.mean_circularity;
      floes += st.floes;
    }
    const double mean = sum / 3.0;
    std::printf("corners %d-%d at 60 %%: mean circularity %.4f (paper %.2f), %.0f floes per field\n", lo, lo + 5, mean,
                paper, floes / 3.0);
    EXPECT_NEAR(mean, paper, 0.02 * paper);
  }
}

TEST(FieldStatistics, GeneratedFieldsMatchTheirSpec) {
  // The paper's settings (50 / 55 / 60 %, alpha = 2; alpha = 1.2 and 1.6 at 50 %), three seeds each: the
  // concentration within 0.5 % absolute, the fitted exponent within three standard errors, no overlaps.
  for (const auto& [c, alpha] :
       {std::pair{0.5, 2.0}, std::pair{0.55, 2.0}, std::pair{0.6, 2.0}, std::pair{0.5, 1.2}, std::pair{0.5, 1.6}}) {
    for (std::uint64_t seed : {1u, 2u, 3u}) {
      FloeFieldSpec s = paper_spec(c);
      s.exponent = alpha;
      s.seed = seed;
      const FloeField f = generate_floe_field(s, 920.0, 0);
      const FieldStatistics st = field_statistics(f.floes, f.region_area, s.size_min, s.size_max);
      std::printf("c = %.2f, alpha = %.1f, seed %llu: %s\n", c, alpha, static_cast<unsigned long long>(seed),
                  to_string(st).c_str());
      EXPECT_EQ(st.floes, f.floes.size());
      EXPECT_LT(std::abs(st.concentration - c), 0.005);
      EXPECT_LT(std::abs(st.size_distribution.exponent - alpha), 3.0 * st.size_distribution.standard_error)
          << "c " << c << " alpha " << alpha << " seed " << seed;
      expect_valid_field(s, f, seed == 1);
    }
  }
}

}  // namespace
}  // namespace polyfloe::scene
