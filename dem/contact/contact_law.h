// Contact law between two prisms (paper Eq. 4-5), in the plane.
//
// Normal:     F_n = max(0, k_n d^1.5 + c d^p d_dot),  k_n = 4/3 E* sqrt(R*)
//             p = 1/4 (speed-independent restitution, default) or p = 1/2 (paper Eq. 4 as printed)
// Tangential: F_s = -min(k_s d^0.5 |s|, mu F_n) sign(s),  k_s = k_n / (2 + 2 nu)
//             s: the tangential spring (history), integrated from the tangential relative velocity.
// See docs/model.md for how the damping coefficient c is mapped from a target restitution e.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numbers>

namespace polyfloe::contact {

enum class DampingModel {
  speed_independent,  // c d^(1/4) d_dot, c = zeta(e) sqrt(m* k_n): restitution e at every impact speed
  paper,              // c d^(1/2) d_dot (Eq. 4), c mapped so that e holds at the reference speed
};

// Where and along what the normal force acts (docs/model.md §3).
enum class ForceModel {
  centroid,    // along the chord normal at the overlap centroid: a flat face pressed into another resists tilting
               // like an elastic foundation; not exactly conservative for corner contacts (2 % energy drift over
               // 70,000 elastic contact-steps of random polygons)
  gradient,    // -F_n grad(depth) over both bodies' positions and rotations: exactly conservative with
               // W = 2/5 k_n d^2.5, but a flat face has no tilt stiffness (it settles on a corner)
  foundation,  // the exact gradient of the elastic-foundation potential W = kappa ∫_{A∩B} (d_A + d_B) dA
               // (contact/foundation.h), kappa = E*/(2 sqrt 2): continuously differentiable through every change
               // of the overlap's shape, Hertz for round contacts, a restoring tilt stiffness for flat faces
};

// The scene files' name of a force model.
inline const char* force_model_name(ForceModel m) {
  switch (m) {
    case ForceModel::gradient: return "gradient";
    case ForceModel::foundation: return "foundation";
    default: return "centroid";
  }
}

struct ContactLawSettings {
  double youngs_modulus = 1.0e9;  // E [Pa]
  double poisson_ratio = 0.3;     // nu [-]
  double restitution = 0.5;       // target coefficient of restitution e [-], 0 < e <= 1
  double friction = 0.3;          // Coulomb coefficient mu [-]
  DampingModel damping = DampingModel::speed_independent;
  ForceModel force_model = ForceModel::centroid;
  double reference_speed = 1.0;  // impact speed at which the paper damping model hits e exactly [m/s]
};

inline constexpr double kInfinite = std::numeric_limits<double>::infinity();

// Equivalent elastic modulus for two bodies of the same material: E / (2 (1 - nu^2)) [Pa].
double effective_modulus(double youngs_modulus, double poisson_ratio);
// R1 R2 / (R1 + R2); an infinite radius (a flat wall or plate) gives the other radius [m].
double effective_radius(double r1, double r2);
// m1 m2 / (m1 + m2); an infinite mass (a fixed or kinematic body) gives the other mass [kg].
double effective_mass(double m1, double m2);

// Restitution obtained by the nondimensional damped Hertz impact X'' + zeta X^p X' + X^1.5 = 0 (X(0) = 0,
// X'(0) = 1), contact ending when the force reaches zero; p = 1/4 or 1/2 by model.
double restitution_from_damping(double zeta, DampingModel model);
// Inverse of restitution_from_damping (bisection, |e error| < 1e-10).
double damping_from_restitution(double e, DampingModel model);

// Restitution of the nondimensional power-law impact X'' = -(X^(n-1) + zeta X^((n-2)/2) X'), X(0) = 0, X'(0) = 1:
// a contact of stiffness K = (n - 1) X^(n-2) with the damping zeta / sqrt(n - 1) sqrt(m K) X', whose restitution
// does not depend on the impact speed (n = 2: a linear spring, 2.5: Hertz, 3: a corner pressed into a face).
double restitution_of_power_law(double zeta, double n);
// Inverse of restitution_of_power_law in zeta.
double power_law_damping(double e, double n);

// Duration of an undamped Hertz impact m* x'' = -k_n x^1.5 at impact speed v:
// t_c = 2.9432 x_max / v = 3.2181 (m* / k_n)^(2/5) v^(-1/5) [s].
double hertz_contact_duration(double k_n, double m_star, double speed);

// Coefficients for one pair, computed once per contact per step.
struct PairCoefficients {
  double k_n = 0.0;      // [N/m^1.5]
  double k_s = 0.0;      // [N/m^1.5]
  double damping = 0.0;  // c [N s/m^(1+p)]
  double mu = 0.0;       // [-]
  double m_star = 0.0;   // effective mass [kg]
  double k_per_m = 0.0;  // k_n / m_star [N/(m^1.5 kg)] (the contact-duration estimate's, per contact)
};

// The tangential spring of one contact, in the plane (V = double: the spring along the tangent t = k x n) and in
// space (V a 3-vector in the tangent plane): the spring advanced by the slip over the step, its force -k_t s capped
// by Coulomb at `limit` = mu F_n, and where it slides the spring set to what the capped force implies (s = -F_t /
// k_t). One implementation for both worlds; magnitude() and capped() are the only things that differ.
inline double magnitude(double x) { return std::abs(x); }
template <class V>
double magnitude(const V& v) {
  return v.norm();
}
inline double zero_of(double) { return 0.0; }
template <class V>
V zero_of(const V&) {
  return V::Zero();
}
// x scaled to length `limit` (for a scalar: its sign kept, exactly).
inline double capped(double x, double limit) { return std::copysign(limit, x); }
template <class V>
V capped(const V& v, double limit) {
  return v * (limit / v.norm());
}
template <class V>
struct TangentialSpring {
  V force;   // on B [N]
  V spring;  // the updated spring [m]
  bool sliding = false;
};
// `spring`: last step's spring, as seen in this step's tangent plane [m]; `slip_velocity` of B relative to A in it
// [m/s]; k_t [N/m]; limit [N]; dt [s].
template <class V>
TangentialSpring<V> tangential_spring(const V& spring, const V& slip_velocity, double k_t, double limit, double dt) {
  TangentialSpring<V> t;
  t.spring = spring + slip_velocity * dt;
  t.force = -k_t * t.spring;
  if (magnitude(t.force) > limit) {
    t.sliding = true;
    t.force = capped(t.force, limit);
    t.spring = k_t > 0.0 ? V(-t.force / k_t) : zero_of(t.force);
  }
  return t;
}

struct ContactForce {
  double normal = 0.0;      // F_n >= 0 [N], pushes B along +n
  double tangential = 0.0;  // F_s along the tangent t = k x n, acting on B [N]
  double spring = 0.0;      // updated tangential spring s [m]
  bool sliding = false;
};

// How the damping of ContactLaw::evaluate_stiffness meets the time step.
struct DampingStep {
  // The pair's inverse effective mass along its direction, its arms included [1/kg] (0: `rate` is used as given).
  // `rate` is then the approach rate predicted at the end of the step with the pair's normal force of the last
  // step, last_normal [N]; over the final half kick the pair's new force F_n changes it by
  // -dt/2 inverse_mass (F_n - last_normal). The damping is evaluated at that end-of-step rate, solved together
  // with F_n = elastic + damping rate (linear: one division). NaN last_normal: unknown, `rate` as given.
  double inverse_mass = 0.0;
  double last_normal = 0.0;
  // On the contact's first step, the time since it began [s], in [0, dt]; negative on later steps. The step's
  // force stands for the impulse from dt/2 before now to dt/2 after; the damping force, which jumps at entry
  // where the law is linear, acted only from the entry: it is scaled by (dt/2 + tau)/dt, and by
  // 1 - inverse_mass c (dt/2 - tau)/2 for the approach rate's fall under the damping over that time (the mean
  // rate over it against the rate now).
  double since_entry = -1.0;
  // The power p of the approach in the damping force as the contact begins (damping ∝ x^p x_dot): the impulse it
  // missed since the entry is then (dt/2 + tau)^(1+p) / ((1 + p) tau^p dt) times the step's (p = 0: a law linear
  // at entry, the foundation model's flat face; 1/4 the speed-independent Hertz damping, 1/2 the paper's).
  double entry_power = 0.0;
};

class ContactLaw {
 public:
  explicit ContactLaw(const ContactLawSettings& s);
  const ContactLawSettings& settings() const { return s_; }
  double effective_modulus() const { return e_star_; }
  // kappa of the foundation force model: E*/(2 sqrt 2), so that round contacts follow Hertz [Pa].
  double foundation_modulus() const { return e_star_ / (2.0 * std::numbers::sqrt2); }
  PairCoefficients coefficients(double r_a, double r_b, double m_a, double m_b) const;
  // depth d [m], depth_rate d_dot [m/s] (> 0 while approaching), tangential slip velocity of B relative to A along
  // t [m/s], previous spring s [m], time step [s].
  // evaluate_hertz with slope and mass ratio 1 and no step terms (the spatial world's contact points).
  ContactForce evaluate(const PairCoefficients& c, double depth, double depth_rate, double slip_velocity, double spring,
                        double dt) const {
    return evaluate_hertz(c, depth, 1.0, 1.0, depth_rate, slip_velocity, spring, dt, DampingStep{});
  }
  // The same law for a contact given by its elastic force and stiffness rather than a Hertz depth (the foundation
  // force model): elastic normal force F_e [N], stiffness K = dF_e/d(approach) [N/m], approach rate [m/s] (> 0
  // closing). A Hertz contact (F_e = k_n d^1.5, K = 1.5 k_n d^0.5) gets exactly evaluate()'s forces: the damping
  // c d^p d_dot with d^p written through K, and the tangential stiffness k_s d^0.5 = K / (1.5 (2 + 2 nu)).
  // `exponent`: n of the power law W ∝ approach^n the contact follows locally (2.5 for Hertz). The speed-independent
  // damping is power_law_damping(e, n) / sqrt(n - 1) sqrt(m* K) (for n = 2.5 exactly evaluate()'s); the paper's
  // c d^0.5 d_dot keeps its form with d^0.5 = K / (1.5 k_n). `step`: how the damping meets the time step
  // (DampingStep; value-initialised: `rate` is the rate to damp).
  ContactForce evaluate_stiffness(const PairCoefficients& c, double elastic, double stiffness, double exponent,
                                  double rate, double slip_velocity, double spring, double dt,
                                  const DampingStep& step) const {
    ContactForce f;
    const double root = stiffness / (1.5 * c.k_n);  // d^0.5 of the Hertz contact of this stiffness
    const double damping = s_.damping == DampingModel::paper
                               ? c.damping * root
                               : power_damping(exponent) * std::sqrt(c.m_star * stiffness);
    f.normal = stepped_normal(elastic, damping, rate, dt, step);
    friction(c.mu, c.k_s * root, slip_velocity, spring, dt, f);
    return f;
  }
  // The Hertz law of evaluate() (F_e = k_n d^1.5, the same tangential spring) for a depth d that grows at `slope`
  // = dd/dx with the coordinate x whose rate `rate` is, along which the pair's effective mass is `mass_ratio` m*:
  // the damping drives x's impact to the target restitution. In x the contact is Hertz with stiffness
  // k_n slope^1.5, so the damping force is c d^p x_dot scaled by sqrt(slope mass_ratio) (speed-independent, p =
  // 1/4) or (slope mass_ratio)^0.4 (paper, p = 1/2); evaluate() is slope = mass_ratio = 1 without `step`. The
  // centroid force model: x the approach along the normal, slope 1 for faces, 1/2 for a corner in a face (the
  // overlap's area over its chord grows at half the corner's penetration), mass_ratio 1. The gradient model: x
  // the depth itself (slope 1), mass_ratio 1/|dd/dx_b|^2. `step`: as evaluate_stiffness's.
  ContactForce evaluate_hertz(const PairCoefficients& c, double depth, double slope, double mass_ratio, double rate,
                              double slip_velocity, double spring, double dt, const DampingStep& step) const {
    ContactForce f;
    const double sqrt_d = std::sqrt(depth);
    const double scale = slope * mass_ratio;
    const double damping = s_.damping == DampingModel::paper
                               ? c.damping * sqrt_d * (scale == 1.0 ? 1.0 : std::pow(scale, 0.4))
                               : c.damping * std::sqrt(sqrt_d * scale);
    f.normal = stepped_normal(c.k_n * depth * sqrt_d, damping, rate, dt, step);
    friction(c.mu, c.k_s * sqrt_d, slip_velocity, spring, dt, f);  // k_t = k_s |d|^(kappa - 1)
    return f;
  }

 private:
  // The normal force elastic + damping rate (>= 0) with the damping met with the step as `step` says.
  static double stepped_normal(double elastic, double damping, double rate, double dt, const DampingStep& step) {
    const double w = step.inverse_mass;
    if (step.since_entry >= 0.0) {
      const double h = 0.5 * dt, tau = std::min(step.since_entry, dt);
      double missed = (h + tau) / dt;
      if (step.entry_power > 0.0 && tau > 0.0)
        missed *= std::pow((h + tau) / tau, step.entry_power) / (1.0 + step.entry_power);
      damping *= missed * std::max(0.0, 1.0 - 0.5 * w * damping * (h - tau));
    }
    if (w > 0.0 && std::isfinite(step.last_normal)) {
      const double response = 0.5 * dt * w;
      const double at_end = (rate - response * (elastic - step.last_normal)) / (1.0 + response * damping);
      // Where that force would pull, the contact ends the step without force: its rate is then the prediction's
      // less the last force's share.
      rate = elastic + damping * at_end >= 0.0 ? at_end : rate + response * step.last_normal;
    }
    return std::max(0.0, elastic + damping * rate);
  }

  // power_law_damping(e, n) / sqrt(n - 1) for this law's e, interpolated in n over [2, 3.5] (clamped there).
  double power_damping(double n) const {
    const double x = std::clamp((n - 2.0) / kPowerStep, 0.0, static_cast<double>(kPowerPoints - 1));
    const int i = std::min(static_cast<int>(x), kPowerPoints - 2);
    return power_zeta_[i] + (x - i) * (power_zeta_[i + 1] - power_zeta_[i]);
  }
  static constexpr int kPowerPoints = 7;
  static constexpr double kPowerStep = 0.25;
  std::array<double, kPowerPoints> power_zeta_{};

  // The tangential spring of stiffness k_t advanced by the slip, capped by Coulomb at mu f.normal.
  static void friction(double mu, double k_t, double slip_velocity, double spring, double dt, ContactForce& f) {
    const TangentialSpring<double> t = tangential_spring(spring, slip_velocity, k_t, mu * f.normal, dt);
    f.tangential = t.force;
    f.spring = t.spring;
    f.sliding = t.sliding;
  }

  ContactLawSettings s_;
  double e_star_ = 0.0;
  double zeta_ = 0.0;  // nondimensional damping for the target restitution
};

}  // namespace polyfloe::contact
