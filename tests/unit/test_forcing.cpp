// dem/forcing building blocks against exact references:
//   analytic fields give their defining formulas (1e-15 relative); the Rankine vortex is continuous at the core
//   radius; time series interpolate linearly, clamp, wrap cyclically, or throw FieldError outside; bad specs are
//   refused with a message naming the key;
//   each quadrature rule's weights sum to the polygon's area and it integrates every monomial x^a y^b of total
//   degree <= its degree exactly (1e-12 relative) over random convex polygons, against Green's theorem evaluated
//   with Gauss-Legendre on the edges; it is not exact one degree higher;
//   form drag acts only on faces moving into the water; the water's rotation rate from the side samples is exactly
//   half the vorticity of a linear field; the damping matrix is the Jacobian of the skin/air and moment drag
//   (central differences, 1e-7) and, for form drag, exact along the relative velocity, symmetric and positive
//   semi-definite; Coriolis is -m f k x u with f = 2 Omega sin(latitude)
//   (+ beta (y - y0) on a beta plane).
#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>

#include <cmath>
#include <functional>
#include <numbers>
#include <random>

#include "forcing/analytic_fields.h"
#include "forcing/drift.h"
#include "forcing/quadrature.h"
#include "test_support.h"

using namespace polyfloe;
using forcing::FieldKind;
using forcing::FieldSpec;
using forcing::Vec3;
using geometry::Vec2;

namespace {

Vec2 at(const FieldSpec& s, const Vec3& p, double t) { return forcing::make_field(s)->at(p, t); }

TEST(Fields, UniformIsConstantAndLinearAddsTheGradientAndDepthTermsFromTheOrigin) {
  EXPECT_EQ(at(FieldSpec::uniform({0.3, -0.2}), {5, 6, -1}, 7.0), Vec2(0.3, -0.2));
  FieldSpec s;
  s.kind = FieldKind::linear;
  s.velocity = {0.5, 0.1};
  s.origin = {100.0, -50.0};
  s.gradient << 1e-3, 2e-3, -3e-3, 4e-4;
  s.depth_gradient = {0.01, -0.02};
  const Vec3 p{130.0, 20.0, -0.7};
  const Vec2 d{30.0, 70.0};
  const Vec2 expect{0.5 + 1e-3 * d.x() + 2e-3 * d.y() + 0.01 * -0.7, 0.1 - 3e-3 * d.x() + 4e-4 * d.y() - 0.02 * -0.7};
  EXPECT_NEAR((at(s, p, 0.0) - expect).norm(), 0.0, 1e-15);
  EXPECT_FALSE(forcing::make_field(s)->uniform_in_space());
}

TEST(Fields, SolidBodyAndRankineVorticesGiveTheirClosedFormsContinuousAtTheCore) {
  FieldSpec s;
  s.kind = FieldKind::solid_body;
  s.origin = {10.0, 20.0};
  s.angular_velocity = 0.01;
  s.velocity = {0.1, 0.0};
  EXPECT_NEAR((at(s, {13.0, 24.0, 0}, 0) - Vec2(0.1 - 0.01 * 4.0, 0.01 * 3.0)).norm(), 0.0, 1e-16);

  FieldSpec r;
  r.kind = FieldKind::rankine;
  r.origin = {0.0, 0.0};
  r.core_radius = 100.0;
  r.max_speed = 2.0;
  // Inside: solid body at V/R; at R: V; outside: V R / r; counter-clockwise for V > 0.
  EXPECT_NEAR((at(r, {50.0, 0.0, 0}, 0) - Vec2(0.0, 1.0)).norm(), 0.0, 1e-15);
  EXPECT_NEAR((at(r, {0.0, 100.0, 0}, 0) - Vec2(-2.0, 0.0)).norm(), 0.0, 1e-15);
  EXPECT_NEAR((at(r, {0.0, 100.0 + 1e-9, 0}, 0) - Vec2(-2.0, 0.0)).norm(), 0.0, 1e-9);  // continuous
  EXPECT_NEAR((at(r, {-400.0, 0.0, 0}, 0) - Vec2(0.0, -0.5)).norm(), 0.0, 1e-15);
  EXPECT_EQ(at(r, {0.0, 0.0, 0}, 0), Vec2(0.0, 0.0));
}

TEST(Fields, TidalIsAUniformCosineAboutTheMeanAndTimeSeriesInterpolateClampWrapOrThrow) {
  FieldSpec s;
  s.kind = FieldKind::tidal;
  s.velocity = {0.1, 0.0};
  s.amplitude = {0.0, 0.5};
  s.period = 44712.0;  // M2 [s]
  s.phase = 0.3;
  for (double t : {0.0, 1000.0, 30000.0}) {
    const Vec2 e = s.velocity + std::cos(2 * std::numbers::pi * t / s.period + 0.3) * s.amplitude;
    EXPECT_NEAR((at(s, {1, 2, -3}, t) - e).norm(), 0.0, 1e-15);
  }
  EXPECT_TRUE(forcing::make_field(s)->uniform_in_space());

  FieldSpec ts;
  ts.kind = FieldKind::time_series;
  ts.times = {0.0, 10.0, 30.0};
  ts.values = {{0.0, 0.0}, {1.0, 2.0}, {3.0, -2.0}};
  EXPECT_NEAR((at(ts, {}, 5.0) - Vec2(0.5, 1.0)).norm(), 0.0, 1e-15);
  EXPECT_NEAR((at(ts, {}, 20.0) - Vec2(2.0, 0.0)).norm(), 0.0, 1e-15);
  EXPECT_EQ(at(ts, {}, 30.0), Vec2(3.0, -2.0));
  EXPECT_EQ(at(ts, {}, 45.0), Vec2(3.0, -2.0));  // clamp
  EXPECT_EQ(at(ts, {}, -5.0), Vec2(0.0, 0.0));
  ts.outside = forcing::TimeBoundary::cyclic;
  EXPECT_NEAR((at(ts, {}, 35.0) - Vec2(0.5, 1.0)).norm(), 0.0, 1e-14);   // 35 -> 5
  EXPECT_NEAR((at(ts, {}, -25.0) - Vec2(0.5, 1.0)).norm(), 0.0, 1e-14);  // -25 -> 5
  ts.outside = forcing::TimeBoundary::error;
  EXPECT_NO_THROW(at(ts, {}, 30.0));
  try {
    at(ts, {}, 30.5);
    ADD_FAILURE() << "no FieldError past the end of the series";
  } catch (const forcing::FieldError& e) {
    EXPECT_NE(std::string(e.what()).find("outside the velocity time series [0, 30] s"), std::string::npos) << e.what();
  }
}

TEST(Fields, BadSpecsAreRefused) {
  auto refused = [](const FieldSpec& s, const std::string& says) {
    try {
      forcing::make_field(s);
      ADD_FAILURE() << "accepted: " << says;
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find(says), std::string::npos) << e.what();
    }
  };
  FieldSpec r;
  r.kind = FieldKind::rankine;
  refused(r, "core_radius must be > 0 m");
  FieldSpec t;
  t.kind = FieldKind::tidal;
  refused(t, "period must be > 0 s");
  FieldSpec ts;
  ts.kind = FieldKind::time_series;
  ts.times = {0.0};
  ts.values = {{0, 0}};
  refused(ts, "at least 2 entries");
  ts.times = {0.0, 1.0};
  refused(ts, "values has 1 entries but times has 2");
  ts.values = {{0, 0}, {1, 1}};
  ts.times = {1.0, 1.0};
  refused(ts, "times must increase strictly");
  FieldSpec u = FieldSpec::uniform({std::nan(""), 0.0});
  refused(u, "finite");
}

// --- quadrature ---

// Exact integral of x^a y^b over a polygon: Green's theorem, int x^a y^b dA = 1/(a+1) closed-int x^(a+1) y^b dy,
// each edge integrated by 5-point Gauss-Legendre (exact for polynomials up to degree 9 along the edge).
double monomial_integral(const std::vector<Vec2>& v, int a, int b) {
  static const double x5[5] = {-0.9061798459386640, -0.5384693101056831, 0.0, 0.5384693101056831, 0.9061798459386640};
  static const double w5[5] = {0.2369268850561891, 0.4786286704993665, 0.5688888888888889, 0.4786286704993665,
                               0.2369268850561891};
  double s = 0.0;
  for (std::size_t i = 0; i < v.size(); ++i) {
    const Vec2 p = v[i], q = v[(i + 1) % v.size()];
    for (int k = 0; k < 5; ++k) {
      const Vec2 x = 0.5 * (p + q) + 0.5 * x5[k] * (q - p);
      s += w5[k] * 0.5 * (q.y() - p.y()) * std::pow(x.x(), a + 1) * std::pow(x.y(), b);
    }
  }
  return s / (a + 1);
}

int degree_of(forcing::Quadrature q) {
  switch (q) {
    case forcing::Quadrature::centroid:
    case forcing::Quadrature::degree1: return 1;
    case forcing::Quadrature::degree2: return 2;
    case forcing::Quadrature::degree4: return 4;
    case forcing::Quadrature::degree5: return 5;
  }
  return 0;
}

TEST(Quadrature, ExactToItsDegree) {
  using forcing::Quadrature;
  std::mt19937_64 rng(42);
  for (int trial = 0; trial < 20; ++trial) {
    const int n = 3 + trial % 12;
    const auto poly = tsupport::transform(tsupport::random_convex(rng, n, 30.0, 12.0), 0.4 * trial, {3.0, -7.0});
    const double area = monomial_integral(poly, 0, 0);
    for (Quadrature q :
         {Quadrature::centroid, Quadrature::degree1, Quadrature::degree2, Quadrature::degree4, Quadrature::degree5}) {
      std::vector<forcing::QuadraturePoint> pts;
      forcing::polygon_quadrature(poly, q, pts);
      ASSERT_EQ(static_cast<int>(pts.size()), forcing::quadrature_points(q, n));
      const int p = degree_of(q);
      double worst_higher = 0.0;
      for (int deg = 0; deg <= p + 1; ++deg) {
        for (int a = 0; a <= deg; ++a) {
          const int b = deg - a;
          double s = 0.0;
          for (const auto& qp : pts) s += qp.weight * std::pow(qp.point.x(), a) * std::pow(qp.point.y(), b);
          const double exact = monomial_integral(poly, a, b);
          // Scale of the integrand: area x (size)^deg.
          const double scale = area * std::pow(40.0, deg);
          if (deg <= p)
            EXPECT_NEAR(s, exact, 1e-12 * scale) << to_string(q) << " x^" << a << " y^" << b;
          else
            worst_higher = std::max(worst_higher, std::abs(s - exact) / scale);
        }
      }
      EXPECT_GT(worst_higher, 1e-9) << to_string(q) << ": exact beyond its degree?";
    }
  }
}

// --- kernels ---

std::vector<Vec2> square(double half, double yaw, const Vec2& c) {
  return tsupport::transform({{-half, -half}, {half, -half}, {half, half}, {-half, half}}, yaw, c);
}

TEST(DriftKernels, FormDragOnlyOnFacesMovingIntoTheWater) {
  // A square moving along +x through still water: only the +x face pushes, with 1/2 C rho (L d) u^2.
  const auto v = square(5.0, 0.0, {0.0, 0.0});
  forcing::DriftLoad load;
  forcing::add_form_drag(load, 0.2, 1025.0, 0.9, {{0, 0}, {2.0, 0.0}, 0.0}, v, Vec2{0.0, 0.0});
  EXPECT_NEAR(load.force.x(), -0.5 * 0.2 * 1025.0 * (10.0 * 0.9) * 4.0, 1e-9);
  EXPECT_NEAR(load.force.y(), 0.0, 1e-12);
  EXPECT_NEAR(load.torque, 0.0, 1e-9);
  // A square at rest in water moving along +y at 0.5 m/s: w = (0, -0.5). The +-x faces see the flow along them
  // (w.n = 0: no push), the +y face is in the lee, the upstream -y face pushes: f = -k L (w.n) w, n = (0, -1).
  forcing::DriftLoad along;
  forcing::add_form_drag(along, 0.2, 1025.0, 0.9, {{0, 0}, {0.0, 0.0}, 0.0}, v, Vec2{0.0, 0.5});
  EXPECT_NEAR((along.force - Vec2(0.0, 0.5 * 0.2 * 1025.0 * 9.0 * 0.25)).norm(), 0.0, 1e-9);
  EXPECT_NEAR(along.torque, 0.0, 1e-9);
  // Still water, nothing moving: no force, no damping (and no NaN from 0/0).
  forcing::DriftLoad rest;
  forcing::add_form_drag(rest, 0.2, 1025.0, 0.9, {{0, 0}, {0.0, 0.0}, 0.0}, v, Vec2{0.0, 0.0});
  EXPECT_EQ(rest.force, Vec2(0.0, 0.0));
  EXPECT_FALSE(rest.has_damping());
}

TEST(DriftKernels, FormDragOnASpinningSquareSumsOnlyTheFacesMovingIntoTheWater) {
  // Square of side 10 centred at the origin, u = (1, 0.3) m/s, omega = 0.1 rad/s, still water, C rho d / 2 = 100.
  // Face centres r, normals n, w = u + omega k x r:
  //   +x: r = (5, 0),  w = (1, 0.8),   w.n = 1    -> f = -100 10 1 (1, 0.8) = (-1000, -800), r x f = -4000
  //   +y: r = (0, 5),  w = (0.5, 0.3), w.n = 0.3  -> f = -100 10 0.3 (0.5, 0.3) = (-150, -90), r x f = 750
  //   -x: r = (-5, 0), w = (1, -0.2),  w.n = -1   -> lee, 0
  //   -y: r = (0, -5), w = (1.5, 0.3), w.n = -0.3 -> lee, 0
  forcing::DriftLoad load;
  forcing::add_form_drag(load, 0.2, 1000.0, 1.0, {{0, 0}, {1.0, 0.3}, 0.1}, square(5.0, 0.0, {0.0, 0.0}),
                         Vec2{0.0, 0.0});
  EXPECT_NEAR((load.force - Vec2(-1150.0, -890.0)).norm(), 0.0, 1e-9);
  EXPECT_NEAR(load.torque, -3250.0, 1e-9);
}

TEST(DriftKernels, WaterRotationIsHalfTheVorticity) {
  FieldSpec s;
  s.kind = FieldKind::linear;
  s.velocity = {0.3, 0.1};
  s.gradient << 2e-3, -5e-3, 7e-3, 1e-3;  // vorticity dv/dx - du/dy = 12e-3
  const auto field = forcing::make_field(s);
  std::mt19937_64 rng(3);
  const auto v = tsupport::transform(tsupport::random_convex(rng, 9, 40.0, 25.0), 0.7, {300.0, -80.0});
  std::vector<Vec3> pts(v.size());
  std::vector<Vec2> water(v.size());
  forcing::side_sample_points(v, 0.9, pts);
  for (const Vec3& p : pts) EXPECT_EQ(p.z(), -0.45);
  field->sample(0.0, pts, water);
  const double area = monomial_integral(v, 0, 0);
  EXPECT_NEAR(forcing::water_rotation_rate(v, water, area), 6e-3, 1e-15);
}

// The load of one kernel as a function of v = (u_x, u_y, omega), for finite differences.
using LoadOf = std::function<forcing::DriftLoad(const forcing::FloeMotion&)>;
Eigen::Matrix3d jacobian(const LoadOf& f, const forcing::FloeMotion& m0, double step) {
  Eigen::Matrix3d jac;
  for (int k = 0; k < 3; ++k) {
    forcing::FloeMotion a = m0, b = m0;
    if (k < 2) {
      a.velocity(k) += step;
      b.velocity(k) -= step;
    } else {
      a.omega += step;
      b.omega -= step;
    }
    const forcing::DriftLoad la = f(a), lb = f(b);
    jac.col(k) = -(Eigen::Vector3d(la.force.x(), la.force.y(), la.torque) -
                   Eigen::Vector3d(lb.force.x(), lb.force.y(), lb.torque)) /
                 (2 * step);
  }
  return jac;
}

TEST(DriftKernels, DampingIsTheJacobian) {
  // Surface drag with a 3-point rule in a sheared flow and the drag moment: D = -dF/dv exactly (central
  // differences, 1e-7 relative); D symmetric and positive definite.
  std::mt19937_64 rng(11);
  // A triangle with degree1 (3 samples: the one-at-a-time path) and a 7-gon with degree2 (14: the SIMD path).
  for (const auto& [nv, rule] :
       {std::pair{3, forcing::Quadrature::degree1}, std::pair{7, forcing::Quadrature::degree2}}) {
    const auto v = tsupport::random_convex(rng, nv, 20.0, 14.0);
    std::vector<forcing::QuadraturePoint> qp;
    forcing::polygon_quadrature(v, rule, qp);
    std::vector<double> rx, ry, w, fx, fy;
    for (const auto& q : qp) {
      rx.push_back(q.point.x());
      ry.push_back(q.point.y());
      w.push_back(q.weight);
      fx.push_back(0.4 + 0.01 * q.point.y());
      fy.push_back(-0.1 + 0.003 * q.point.x());
    }
    const forcing::SurfaceSamples samples{rx, ry, w};
    const LoadOf surface_and_moment = [&](const forcing::FloeMotion& m) {
      forcing::DriftLoad l;
      forcing::add_surface_drag(l, 0.0055, 1025.0, m, samples, fx, fy);
      forcing::add_moment_drag(l, 0.14, 1025.0, 60.0, 9.0, m.omega - 0.001);
      return l;
    };
    const forcing::FloeMotion m0{{0, 0}, {0.1, 0.05}, 0.003};
    const Eigen::Matrix3d d = surface_and_moment(m0).damping();
    const Eigen::Matrix3d jac = jacobian(surface_and_moment, m0, 1e-6);
    EXPECT_LT((d - jac).norm(), 1e-7 * d.norm()) << to_string(rule) << "\n" << d << "\n" << jac;
    EXPECT_LT((d - d.transpose()).norm(), 1e-12 * d.norm());
    EXPECT_GT(d.eigenvalues().real().minCoeff(), 0.0);
    // The two paths agree: the same samples one by one (uniform fluid overload, < 4 samples per call).
    forcing::DriftLoad split;
    for (std::size_t q = 0; q < rx.size(); ++q)
      forcing::add_surface_drag(split, 0.0055, 1025.0, m0, {{&rx[q], 1}, {&ry[q], 1}, {&w[q], 1}}, Vec2(fx[q], fy[q]));
    forcing::DriftLoad whole;
    forcing::add_surface_drag(whole, 0.0055, 1025.0, m0, samples, fx, fy);
    EXPECT_NEAR((split.force - whole.force).norm(), 0.0, 1e-12 * whole.force.norm());
    EXPECT_NEAR(split.torque, whole.torque, 1e-12 * std::abs(whole.torque));
    EXPECT_LT((split.damping() - whole.damping()).norm(), 1e-12 * whole.damping().norm());
  }
  // A huge floe at rest in still water: w = 0 everywhere; no NaN, no damping from the Newton term.
  const std::vector<double> zx{0.0, 1e4}, zy{0.0, -1e4}, big{1e9, 1e9}, zero{0.0, 0.0};
  forcing::DriftLoad rest;
  forcing::add_surface_drag(rest, 0.0055, 1025.0, {{0, 0}, {0, 0}, 0.0}, {zx, zy, big}, zero, zero);
  EXPECT_TRUE(rest.damping().allFinite());
  EXPECT_FALSE(rest.has_damping());

  // Form drag: exact along the relative velocity of the one pushing face; symmetric, positive semi-definite.
  const auto sq = square(5.0, 0.0, {0.0, 0.0});
  const LoadOf form = [&](const forcing::FloeMotion& m) {
    forcing::DriftLoad l;
    forcing::add_form_drag(l, 0.2, 1025.0, 0.9, m, sq, Vec2{0.0, 0.0});
    return l;
  };
  const forcing::FloeMotion mf{{0, 0}, {0.8, 0.3}, 0.0};  // only the +x face pushes (w.n > 0 for n = +x only?)
  forcing::DriftLoad lf = form(mf);
  const Eigen::Matrix3d df = lf.damping();
  EXPECT_LT((df - df.transpose()).norm(), 1e-12 * df.norm());
  EXPECT_GE(df.eigenvalues().real().minCoeff(), -1e-9 * df.norm());
  // Directional derivative along w = (0.8, 0.3) for the +x face and (0.8, 0.3) for the +y face: both push here,
  // each exact along its own w, and w is the same for both (no rotation): exact along w.
  const Eigen::Vector3d dir = Eigen::Vector3d(0.8, 0.3, 0.0).normalized();
  const Eigen::Matrix3d jf = jacobian(form, mf, 1e-6);
  EXPECT_LT((df * dir - jf * dir).norm(), 1e-7 * (df * dir).norm());
}

TEST(DriftKernels, MomentDragOpposesTheSpinAndCoriolisPushesRightWithFFromLatitudeAndBeta) {
  forcing::DriftLoad load;
  forcing::add_moment_drag(load, 0.14, 1025.0, 36.0, 5.0, -0.2);
  EXPECT_NEAR(load.torque, 0.5 * 0.14 * 1025.0 * 36.0 * 125.0 * 0.04, 1e-9);    // opposes omega_rel < 0
  EXPECT_NEAR(load.dww, 2.0 * 0.5 * 0.14 * 1025.0 * 36.0 * 125.0 * 0.2, 1e-9);  // d(-k|x|x)/dx = -2k|x|

  forcing::DriftSettings s;
  s.latitude = 90.0;
  EXPECT_NEAR(s.coriolis_parameter(1e5), 2.0 * forcing::kEarthRotationRate, 1e-18);
  s.latitude = 60.0;
  s.beta_plane = true;
  s.reference_y = 1000.0;
  const double beta = 2.0 * forcing::kEarthRotationRate * 0.5 / forcing::kEarthRadius;
  EXPECT_NEAR(s.coriolis_parameter(51000.0), 2.0 * forcing::kEarthRotationRate * std::sqrt(3.0) / 2 + beta * 5e4,
              1e-18);
  forcing::DriftLoad c;
  forcing::add_coriolis(c, 1000.0, 1e-4, {0.3, 0.4});
  EXPECT_NEAR((c.force - Vec2(1000.0 * 1e-4 * 0.4, -1000.0 * 1e-4 * 0.3)).norm(), 0.0, 1e-15);  // to the right
  EXPECT_NEAR(c.force.dot(Vec2(0.3, 0.4)), 0.0, 1e-15);                                         // does no work
}

}  // namespace
