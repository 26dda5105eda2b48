#include "contact/contact_law.h"

#include <cmath>
#include <map>
#include <mutex>
#include <stdexcept>
#include <string>

namespace polyfloe::contact {

double effective_modulus(double youngs_modulus, double poisson_ratio) {
  return youngs_modulus / (2.0 * (1.0 - poisson_ratio * poisson_ratio));
}

double effective_radius(double r1, double r2) {
  if (std::isinf(r1)) return r2;
  if (std::isinf(r2)) return r1;
  return r1 * r2 / (r1 + r2);
}

double effective_mass(double m1, double m2) { return effective_radius(m1, m2); }

namespace {

// Right-hand side of the nondimensional impact X'' = -(X^1.5 + zeta X^p X').
struct Impact {
  double zeta;
  bool half;  // p = 1/2, else p = 1/4
  double force(double x, double v) const {
    if (x <= 0.0) return 0.0;
    const double r = std::sqrt(x);
    return x * r + zeta * (half ? r : std::sqrt(r)) * v;
  }
};

// Right-hand side of the nondimensional power-law impact X'' = -(X^(n-1) + zeta X^((n-2)/2) X'): a contact of
// stiffness K = (n - 1) X^(n-2) damped by zeta / sqrt(n - 1) sqrt(K) X' (a restitution independent of the speed).
struct PowerLawImpact {
  double zeta, n;
  double force(double x, double v) const {
    if (x <= 0.0) return 0.0;
    return std::pow(x, n - 1.0) + zeta * std::pow(x, 0.5 * n - 1.0) * v;
  }
};

// The restitution of the nondimensional impact X(0) = 0, X'(0) = 1 under force f: RK4, the contact ending when the
// (non-negative) force reaches zero on the way out, or the overlap closes.
template <class Force>
double impact_restitution(const Force& f) {
  const double h = 1.0e-3;  // zeta within 1e-5 of the h = 2e-4 value (an undamped Hertz impact lasts 3.218 units)
  double x = 0.0, v = 1.0;
  for (int it = 0; it < 1000000; ++it) {
    const double k1x = v, k1v = -f.force(x, v);
    const double k2x = v + 0.5 * h * k1v, k2v = -f.force(x + 0.5 * h * k1x, v + 0.5 * h * k1v);
    const double k3x = v + 0.5 * h * k2v, k3v = -f.force(x + 0.5 * h * k2x, v + 0.5 * h * k2v);
    const double k4x = v + h * k3v, k4v = -f.force(x + h * k3x, v + h * k3v);
    const double xn = x + h / 6.0 * (k1x + 2.0 * k2x + 2.0 * k3x + k4x);
    const double vn = v + h / 6.0 * (k1v + 2.0 * k2v + 2.0 * k3v + k4v);
    if (vn < 0.0) {
      const double fo = f.force(x, v), fn = f.force(xn, vn);
      if (fn <= 0.0 || xn <= 0.0) {
        const double t = (fo > 0.0 && fn < 0.0) ? fo / (fo - fn) : 1.0;
        return -(v + t * (vn - v));
      }
    }
    x = xn;
    v = vn;
  }
  return 0.0;
}

// The zeta for which restitution(zeta) = e (decreasing in zeta), by bisection to 1e-9 relative.
template <class Restitution>
double invert_restitution(double e, const Restitution& restitution) {
  if (!(e > 0.0 && e <= 1.0)) throw std::invalid_argument("restitution must be in (0, 1], got " + std::to_string(e));
  if (e >= 1.0) return 0.0;
  double lo = 0.0, hi = 1.0;
  while (restitution(hi) > e) hi *= 2.0;
  for (int it = 0; it < 60 && hi - lo > 1e-9 * hi; ++it) {
    const double mid = 0.5 * (lo + hi);
    (restitution(mid) > e ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

}  // namespace

double restitution_from_damping(double zeta, DampingModel model) {
  if (zeta <= 0.0) return 1.0;
  return impact_restitution(Impact{zeta, model == DampingModel::paper});
}

double restitution_of_power_law(double zeta, double n) {
  if (zeta <= 0.0) return 1.0;
  return impact_restitution(PowerLawImpact{zeta, n});
}

double damping_from_restitution(double e, DampingModel model) {
  return invert_restitution(e, [&](double z) { return restitution_from_damping(z, model); });
}

double power_law_damping(double e, double n) {
  return invert_restitution(e, [&](double z) { return restitution_of_power_law(z, n); });
}

double hertz_contact_duration(double k_n, double m_star, double speed) {
  return 3.2181 * std::pow(m_star / k_n, 0.4) * std::pow(speed, -0.2);
}

ContactLaw::ContactLaw(const ContactLawSettings& s) : s_(s) {
  e_star_ = contact::effective_modulus(s.youngs_modulus, s.poisson_ratio);
  zeta_ = damping_from_restitution(s.restitution, s.damping);
  if (s.force_model == ForceModel::foundation && s.damping == DampingModel::speed_independent) {
    // The same restitution for every local exponent (a few ms per value of e; kept for the process).
    static std::mutex mutex;
    static std::map<double, std::array<double, kPowerPoints>> tables;
    const std::lock_guard<std::mutex> lock(mutex);
    auto [it, fresh] = tables.try_emplace(s.restitution);
    if (fresh)
      for (int k = 0; k < kPowerPoints; ++k) {
        const double n = 2.0 + kPowerStep * k;
        it->second[static_cast<std::size_t>(k)] = power_law_damping(s.restitution, n) / std::sqrt(n - 1.0);
      }
    power_zeta_ = it->second;
  }
}

PairCoefficients ContactLaw::coefficients(double r_a, double r_b, double m_a, double m_b) const {
  PairCoefficients c;
  const double r = effective_radius(r_a, r_b);
  const double m = effective_mass(m_a, m_b);
  c.k_n = 4.0 / 3.0 * e_star_ * std::sqrt(r);
  c.k_s = c.k_n / (2.0 + 2.0 * s_.poisson_ratio);
  c.mu = s_.friction;
  c.m_star = m;
  c.k_per_m = c.k_n / m;
  if (s_.damping == DampingModel::speed_independent) {
    c.damping = zeta_ * std::sqrt(m * c.k_n);
  } else {
    // gamma = C v^(1/5) / (k^(3/5) m^(2/5)) is the nondimensional damping of the d^(1/2) form.
    c.damping = zeta_ * std::pow(c.k_n, 0.6) * std::pow(m, 0.4) * std::pow(s_.reference_speed, -0.2);
  }
  return c;
}

}  // namespace polyfloe::contact
