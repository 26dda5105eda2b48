// ContactLaw (paper Eq. 4-5) against hand values and closed forms:
//   k_n = 4/3 E* sqrt(R*), E* = E / (2 (1 - nu^2)), k_s = k_n / (2 + 2 nu)      (1e-14 relative)
//   R* and m* with infinite values (walls): the other body's value                (exact)
//   F_n = k_n d^1.5 at zero rate; damping adds c d^p d_dot (p = 1/4 or 1/2), with its sign, never F_n < 0
//   tangential spring: F_s = -k_s d^0.5 s below mu F_n; capped at mu F_n and the spring reset to the limit above
//   damping coefficient: zeta(e) sqrt(m* k_n) (speed-independent) or gamma(e) k_n^3/5 m*^2/5 v_ref^-1/5 (paper);
//   and, integrating m* x'' = -F_n(x, x') with the law itself, the exit speed is e times the impact speed (1e-3)
//   hertz_contact_duration against a direct RK4 integration of m x'' = -k x^1.5 (1e-4 relative; the closed form
//   is 3.218065 (m/k)^(2/5) v^(-1/5), the code's constant 3.2181 is 1.1e-5 above it).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <limits>

#include <Eigen/Core>

#include "contact/contact_law.h"

using namespace polyfloe;
using contact::ContactLaw;
using contact::ContactLawSettings;
using contact::DampingModel;
using contact::kInfinite;

namespace {

ContactLawSettings settings(double e = 0.5, double mu = 0.3, DampingModel model = DampingModel::speed_independent) {
  ContactLawSettings s;
  s.youngs_modulus = 1.0e9;
  s.poisson_ratio = 0.3;
  s.restitution = e;
  s.friction = mu;
  s.damping = model;
  s.reference_speed = 1.0;
  return s;
}

// Integrates m x'' = f(x, x') with RK4 from x = 0, x' = v until x returns to 0 (linear interpolation of the
// crossing), or until the force vanishes on the way out (the contact ends there); returns {duration, exit speed}.
template <class Force>
std::pair<double, double> integrate_impact(Force f, double m, double v, double h) {
  double x = 0.0, u = v, t = 0.0;
  for (long it = 0; it < 100000000L; ++it) {
    auto acc = [&](double xx, double uu) { return xx > 0.0 ? f(xx, uu) / m : 0.0; };
    const double k1x = u, k1u = -acc(x, u);
    const double k2x = u + 0.5 * h * k1u, k2u = -acc(x + 0.5 * h * k1x, u + 0.5 * h * k1u);
    const double k3x = u + 0.5 * h * k2u, k3u = -acc(x + 0.5 * h * k2x, u + 0.5 * h * k2u);
    const double k4x = u + h * k3u, k4u = -acc(x + h * k3x, u + h * k3u);
    const double xn = x + h / 6.0 * (k1x + 2.0 * k2x + 2.0 * k3x + k4x);
    const double un = u + h / 6.0 * (k1u + 2.0 * k2u + 2.0 * k3u + k4u);
    if (un < 0.0 && (xn <= 0.0 || f(xn, un) <= 0.0)) {
      // Crossing of x = 0 (undamped) or of F = 0 (damped) within this step.
      const double a = xn <= 0.0 ? x / (x - xn) : f(x, u) / (f(x, u) - f(xn, un));
      return {t + a * h, -(u + a * (un - u))};
    }
    x = xn;
    u = un;
    t += h;
  }
  return {std::numeric_limits<double>::quiet_NaN(), 0.0};
}

}  // namespace

TEST(ContactLaw, EffectiveModulusRadiusAndMassMatchHandValuesAndAWallGivesTheFloesOwn) {
  EXPECT_DOUBLE_EQ(contact::effective_modulus(1.0e9, 0.3), 549450549.4505495);
  EXPECT_DOUBLE_EQ(contact::effective_radius(3.0, 6.0), 2.0);
  EXPECT_DOUBLE_EQ(contact::effective_mass(1000.0, 3000.0), 750.0);
  // A wall or plate (infinite radius, infinite mass): the floe's own value, exactly, in either order.
  EXPECT_EQ(contact::effective_radius(kInfinite, 3.7), 3.7);
  EXPECT_EQ(contact::effective_radius(3.7, kInfinite), 3.7);
  EXPECT_EQ(contact::effective_mass(kInfinite, 5.0e4), 5.0e4);
  EXPECT_EQ(contact::effective_mass(5.0e4, kInfinite), 5.0e4);
  EXPECT_TRUE(std::isinf(contact::effective_radius(kInfinite, kInfinite)));
  const ContactLaw law(settings());
  EXPECT_DOUBLE_EQ(law.effective_modulus(), 549450549.4505495);
}

TEST(ContactLaw, StiffnessIsHertzOfTheEffectiveRadiusAlsoAgainstAWallAndIsSymmetric) {
  const ContactLaw law(settings(0.5, 0.3));
  // R = 3 and 6 m: R* = 2 m; k_n = 4/3 E* sqrt(2) = 1.0360538918e9 N/m^1.5, k_s = k_n / 2.6.
  const contact::PairCoefficients c = law.coefficients(3.0, 6.0, 1.0e4, 3.0e4);
  EXPECT_NEAR(c.k_n, 1036053891.8484213, 1e-14 * c.k_n);
  EXPECT_NEAR(c.k_s, 398482266.09554666, 1e-14 * c.k_s);
  EXPECT_EQ(c.mu, 0.3);
  // Against a wall: R* = R of the floe.
  const contact::PairCoefficients w = law.coefficients(kInfinite, 2.0, kInfinite, 1.0e4);
  EXPECT_NEAR(w.k_n, 4.0 / 3.0 * 549450549.4505495 * std::sqrt(2.0), 1e-14 * w.k_n);
  EXPECT_NEAR(w.k_s, w.k_n / 2.6, 1e-14 * w.k_s);
  // Symmetric in the two bodies.
  const contact::PairCoefficients r = law.coefficients(6.0, 3.0, 3.0e4, 1.0e4);
  EXPECT_EQ(r.k_n, c.k_n);
  EXPECT_EQ(r.damping, c.damping);
}

TEST(ContactLaw, DampingCoefficientFromRestitution) {
  const double m_star = 7500.0;
  {
    const ContactLaw law(settings(0.5, 0.3, DampingModel::speed_independent));
    const auto c = law.coefficients(3.0, 6.0, 1.0e4, 3.0e4);
    const double zeta = contact::damping_from_restitution(0.5, DampingModel::speed_independent);
    EXPECT_NEAR(c.damping, zeta * std::sqrt(m_star * c.k_n), 1e-12 * c.damping);
    // Wall: m* is the floe's mass.
    const auto w = law.coefficients(kInfinite, 2.0, kInfinite, 1.0e4);
    EXPECT_NEAR(w.damping, zeta * std::sqrt(1.0e4 * w.k_n), 1e-12 * w.damping);
  }
  {
    auto s = settings(0.5, 0.3, DampingModel::paper);
    s.reference_speed = 2.0;
    const ContactLaw law(s);
    const auto c = law.coefficients(3.0, 6.0, 1.0e4, 3.0e4);
    const double gamma = contact::damping_from_restitution(0.5, DampingModel::paper);
    EXPECT_NEAR(c.damping, gamma * std::pow(c.k_n, 0.6) * std::pow(m_star, 0.4) * std::pow(2.0, -0.2),
                1e-12 * c.damping);
  }
  // e = 1: no damping at all.
  const ContactLaw elastic(settings(1.0));
  EXPECT_EQ(elastic.coefficients(3.0, 6.0, 1.0e4, 3.0e4).damping, 0.0);
}

TEST(ContactLaw, NormalForceIsHertzPlusDampingLinearInTheRateAndNeverNegative) {
  for (DampingModel model : {DampingModel::speed_independent, DampingModel::paper}) {
    const ContactLaw law(settings(0.3, 0.3, model));
    const auto c = law.coefficients(4.0, 4.0, 2.0e4, 2.0e4);
    const double p = model == DampingModel::paper ? 0.5 : 0.25;
    for (double d : {1e-5, 1e-3, 0.02}) {
      // Zero rate: pure Hertz.
      const auto f0 = law.evaluate(c, d, 0.0, 0.0, 0.0, 1e-4);
      EXPECT_NEAR(f0.normal, c.k_n * std::pow(d, 1.5), 1e-14 * f0.normal);
      EXPECT_EQ(f0.tangential, 0.0);
      EXPECT_FALSE(f0.sliding);
      // Approaching (d_dot > 0) adds c d^p d_dot; separating removes it.
      const double rate = 0.3;
      const auto fa = law.evaluate(c, d, rate, 0.0, 0.0, 1e-4);
      EXPECT_GT(fa.normal, f0.normal);
      EXPECT_NEAR(fa.normal, f0.normal + c.damping * std::pow(d, p) * rate, 1e-12 * fa.normal);
      const double small = 0.1 * f0.normal / (c.damping * std::pow(d, p));  // separating, force stays positive
      const auto fs = law.evaluate(c, d, -small, 0.0, 0.0, 1e-4);
      EXPECT_LT(fs.normal, f0.normal);
      EXPECT_NEAR(fs.normal, 0.9 * f0.normal, 1e-12 * f0.normal);
      // Separating fast: the force is clamped at zero, never negative (no adhesion).
      for (double r : {1.0 + 1e-9, 2.0, 1000.0})
        EXPECT_EQ(law.evaluate(c, d, -r * 10.0 * small, 0.0, 0.0, 1e-4).normal, 0.0);
    }
    EXPECT_EQ(law.evaluate(c, 0.0, 0.0, 0.0, 0.0, 1e-4).normal, 0.0);
  }
}

TEST(ContactLaw, TangentialSpringStickAndSlip) {
  const ContactLaw law(settings(0.5, 0.4));
  const auto c = law.coefficients(5.0, 5.0, 3.0e4, 3.0e4);
  const double d = 4e-3, dt = 1e-3;
  const double fn = c.k_n * std::pow(d, 1.5);
  const double kt = c.k_s * std::sqrt(d);  // k_s d^(kappa - 1)
  const double s_limit = 0.4 * fn / kt;    // spring stretch at which friction saturates

  // Stick: s = s0 + v dt, F_s = -k_s d^0.5 s, spring kept.
  for (double s0 : {0.0, 0.3 * s_limit, -0.5 * s_limit}) {
    for (double v : {0.0, 0.1 * s_limit / dt, -0.2 * s_limit / dt}) {
      const auto f = law.evaluate(c, d, 0.0, v, s0, dt);
      const double s = s0 + v * dt;
      EXPECT_FALSE(f.sliding);
      EXPECT_NEAR(f.spring, s, 1e-15 * s_limit);
      EXPECT_NEAR(f.tangential, -kt * s, 1e-12 * fn);
    }
  }
  // Slip: |k_t s| > mu F_n -> F_s = -mu F_n sign(s), spring reset to the limit, in both directions.
  for (double sign : {1.0, -1.0}) {
    const auto f = law.evaluate(c, d, 0.0, sign * 3.0 * s_limit / dt, sign * 0.5 * s_limit, dt);
    EXPECT_TRUE(f.sliding);
    EXPECT_NEAR(f.tangential, -sign * 0.4 * fn, 1e-12 * fn);
    EXPECT_NEAR(f.spring, sign * s_limit, 1e-12 * s_limit);
    // Next step without further slip: exactly at the limit, still Coulomb's force.
    const auto g = law.evaluate(c, d, 0.0, 0.0, f.spring, dt);
    EXPECT_NEAR(std::abs(g.tangential), 0.4 * fn, 1e-12 * fn);
    // Reversing: the spring unloads elastically from the limit (no slip while |s| shrinks).
    const auto r = law.evaluate(c, d, 0.0, -sign * 0.5 * s_limit / dt, f.spring, dt);
    EXPECT_FALSE(r.sliding);
    EXPECT_NEAR(r.tangential, -sign * 0.5 * 0.4 * fn, 1e-12 * fn);
  }
  // The cap uses the damped normal force: approaching raises it, separating lowers it.
  {
    const double rate = 0.05;
    const auto fa = law.evaluate(c, d, rate, 10.0 * s_limit / dt, 0.0, dt);
    EXPECT_TRUE(fa.sliding);
    EXPECT_NEAR(-fa.tangential, 0.4 * fa.normal, 1e-12 * fa.normal);
    EXPECT_GT(fa.normal, fn);
    const auto fz = law.evaluate(c, d, -1.0e3, 10.0 * s_limit / dt, 0.0, dt);  // normal force clamped to 0
    EXPECT_EQ(fz.normal, 0.0);
    EXPECT_EQ(fz.tangential, 0.0);
    EXPECT_TRUE(std::isfinite(fz.spring));
  }
  // Frictionless: no tangential force whatever the spring.
  const ContactLaw smooth(settings(0.5, 0.0));
  const auto cs = smooth.coefficients(5.0, 5.0, 3.0e4, 3.0e4);
  const auto f = smooth.evaluate(cs, d, 0.0, 1.0, 0.01, dt);
  EXPECT_EQ(f.tangential, 0.0);
  EXPECT_EQ(f.spring, 0.0);
}

TEST(ContactLaw, TheTangentialSpringIsOneLawInThePlaneAndInSpace) {
  // contact::tangential_spring serves the planar world (a scalar along t) and the spatial one (a vector in the
  // tangent plane): along any direction e the vector law is the scalar law times e; off one line, the capped force
  // has Coulomb's magnitude and points against the advanced spring.
  using Vec3 = Eigen::Vector3d;
  const double k_t = 2.0e6, limit = 500.0, dt = 1e-3;  // [N/m], [N], [s]
  const Vec3 e = Vec3(0.3, -0.5, 0.8).normalized();
  for (double s0 : {0.0, 1e-4, -2e-4, 3e-4}) {
    for (double v : {0.0, 0.05, -0.4, 1.0}) {
      const auto plane = contact::tangential_spring(s0, v, k_t, limit, dt);
      const auto space = contact::tangential_spring<Vec3>(s0 * e, v * e, k_t, limit, dt);
      EXPECT_EQ(plane.sliding, space.sliding) << s0 << " " << v;
      EXPECT_LT((space.force - plane.force * e).norm(), 1e-12 * limit) << s0 << " " << v;
      EXPECT_LT((space.spring - plane.spring * e).norm(), 1e-15) << s0 << " " << v;
      EXPECT_LE(std::abs(plane.force), limit * (1.0 + 1e-15));
      if (!plane.sliding) {
        EXPECT_EQ(plane.force, -k_t * (s0 + v * dt));
      }
    }
  }
  const Vec3 s0(2e-4, 0.0, 0.0), slip(0.0, 0.5, 0.0);
  const auto t = contact::tangential_spring(s0, slip, k_t, limit, dt);
  const Vec3 advanced = s0 + slip * dt;
  ASSERT_TRUE(t.sliding);
  EXPECT_NEAR(t.force.norm(), limit, 1e-12 * limit);
  EXPECT_NEAR(t.force.normalized().dot(-advanced.normalized()), 1.0, 1e-15);
  EXPECT_LT((t.spring + t.force / k_t).norm(), 1e-18);
}

TEST(ContactLaw, HertzContactDurationAgainstIntegration) {
  for (double k : {1.0e8, 1.0e9}) {
    for (double m : {5.0e3, 2.0e5}) {
      for (double v : {0.1, 1.0, 3.0}) {
        const double closed = contact::hertz_contact_duration(k, m, v);
        const auto [t, exit] =
            integrate_impact([k](double x, double) { return k * std::pow(x, 1.5); }, m, v, closed / 20000.0);
        std::printf(
            "Hertz duration k %.0e m %.0e v %.1f: closed form %.6e s, integrated %.6e s (%+.2e), exit "
            "speed / v = %.8f\n",
            k, m, v, closed, t, (closed - t) / t, exit / v);
        EXPECT_NEAR(closed, t, 1e-4 * t);
        EXPECT_NEAR(exit, v, 1e-8 * v);  // undamped: elastic
      }
    }
  }
}

TEST(ContactLaw, RestitutionOfTheLawItself) {
  // m* x'' = -F_n(x, x') with F_n from evaluate(): the exit speed is e v for the speed-independent form at every
  // speed, and for the paper form at its reference speed.
  for (DampingModel model : {DampingModel::speed_independent, DampingModel::paper}) {
    for (double e : {0.2, 0.5, 0.9}) {
      for (double v : {0.2, 1.0, 3.0}) {
        auto s = settings(e, 0.0, model);
        s.reference_speed = v;
        const ContactLaw law(s);
        const double m = 2.0e4;
        const auto c = law.coefficients(kInfinite, 4.0, kInfinite, m);
        const double tc = contact::hertz_contact_duration(c.k_n, m, v);
        const auto [t, exit] = integrate_impact(
            [&](double x, double u) { return law.evaluate(c, x, u, 0.0, 0.0, 0.0).normal; }, m, v, tc / 20000.0);
        EXPECT_NEAR(exit / v, e, 1e-3) << "model " << static_cast<int>(model) << " e " << e << " v " << v;
        EXPECT_LT(t, 1.5 * tc);
      }
    }
  }
}

// evaluate_stiffness with a DampingStep: a Hertz contact's stiffness gives evaluate()'s force; the end-of-step rate
// is solved exactly (F_n = elastic + c r_end, r_end = r - dt/2 w (F_n - F_last), to round-off), falls back to
// the rate as given where the last force is unknown (NaN) or no inverse mass is given, and ends the step without
// force where the solve would pull; a first step scales the damping by (dt/2 + tau)/dt (1 - w c (dt/2 - tau)/2).
TEST(ContactLaw, DampingAtTheEndOfTheStep) {
  ContactLawSettings s = settings(0.3, 0.0);
  s.force_model = contact::ForceModel::foundation;  // (the law's power-law damping table is built for it)
  const ContactLaw law(s);
  const auto c = law.coefficients(4.0, 4.0, 2.0e4, 2.0e4);
  const double d = 1e-3, dt = 1e-4, rate = 0.2;
  const double elastic = c.k_n * std::pow(d, 1.5), stiffness = 1.5 * c.k_n * std::sqrt(d);
  const auto hertz = law.evaluate(c, d, rate, 0.0, 0.0, dt);
  const auto plain = law.evaluate_stiffness(c, elastic, stiffness, 2.5, rate, 0.0, 0.0, dt, {});
  EXPECT_NEAR(plain.normal, hertz.normal, 1e-12 * hertz.normal);
  const double damping = (plain.normal - elastic) / rate;  // the law's c for this stiffness [N s/m]
  const double w = 2.0 / 2.0e4;                            // two free masses, no arms [1/kg]
  for (const double last : {0.0, 0.5 * elastic, 2.0 * elastic}) {
    const auto f = law.evaluate_stiffness(c, elastic, stiffness, 2.5, rate, 0.0, 0.0, dt,
                                          {.inverse_mass = w, .last_normal = last});
    const double r_end = rate - 0.5 * dt * w * (f.normal - last);
    EXPECT_NEAR(f.normal, elastic + damping * r_end, 1e-12 * f.normal) << "last " << last;
  }
  for (const contact::DampingStep step :
       {contact::DampingStep{.inverse_mass = w, .last_normal = std::numeric_limits<double>::quiet_NaN()},
        contact::DampingStep{.inverse_mass = 0.0, .last_normal = 3.0 * elastic}})
    EXPECT_EQ(law.evaluate_stiffness(c, elastic, stiffness, 2.5, rate, 0.0, 0.0, dt, step).normal, plain.normal);
  // Separating fast after a large force: no pull, and no force at the end of the step.
  EXPECT_EQ(law.evaluate_stiffness(c, elastic, stiffness, 2.5, -50.0, 0.0, 0.0, dt,
                                   {.inverse_mass = w, .last_normal = 10.0 * elastic})
                .normal,
            0.0);
  // First step.
  for (const double tau : {0.0, 0.25 * dt, dt}) {
    const auto f = law.evaluate_stiffness(c, elastic, stiffness, 2.5, rate, 0.0, 0.0, dt,
                                          {.inverse_mass = w, .last_normal = std::nan(""), .since_entry = tau});
    const double scale = (0.5 * dt + tau) / dt * (1.0 - 0.5 * w * damping * (0.5 * dt - tau));
    EXPECT_NEAR(f.normal, elastic + scale * damping * rate, 1e-12 * f.normal) << "tau " << tau;
  }
}
