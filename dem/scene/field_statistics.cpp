#include "scene/field_statistics.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <stdexcept>
#include <vector>

namespace polyfloe::scene {

namespace {

// Mean and variance of t = ln x when x has density ~ x^-alpha on [a, b]: t has density ~ e^{u t}, u = 1 - alpha,
// on [A, B] = [ln a, ln b]. Closed forms, with series near u = 0 where they cancel.
void log_moments(double alpha, double a, double b, double& mean, double& var) {
  const double lo = std::log(a), hi = std::log(b), w = hi - lo;
  const double u = 1.0 - alpha;
  const double z = u * w;  // shape of the exponential on the interval
  if (std::abs(z) < 1e-4) {
    // Uniform on [lo, hi] plus first-order tilt.
    mean = 0.5 * (lo + hi) + z * w / 12.0;
    var = w * w / 12.0 * (1.0 - z * z / 60.0);
    return;
  }
  // For s uniform-tilted on [0, w] with density ~ e^{u s}: E[s] = w / (1 - e^{-z}) - 1/u, computed stably for either
  // sign.
  const double e = -std::expm1(-z);  // 1 - e^{-z}
  const double mean_s = w / e - 1.0 / u;
  // Var[s] = 1/u^2 - w^2 e^{-z} / (1 - e^{-z})^2
  const double var_s = 1.0 / (u * u) - w * w * std::exp(-z) / (e * e);
  mean = lo + mean_s;
  var = var_s;
}

}  // namespace

PowerLawFit fit_power_law(std::span<const double> x, double a, double b) {
  if (x.empty() || !(a > 0.0) || !(b > a)) throw std::invalid_argument("fit_power_law: no samples or a bad range");
  double target = 0.0;
  for (double v : x) target += std::log(std::min(std::max(v, a), b));
  target /= static_cast<double>(x.size());
  // E_alpha[ln x] decreases with alpha: bisection on a wide bracket.
  double lo = -20.0, hi = 20.0;
  for (int it = 0; it < 200; ++it) {
    const double mid = 0.5 * (lo + hi);
    double mean = 0.0, var = 0.0;
    log_moments(mid, a, b, mean, var);
    (mean > target ? lo : hi) = mid;
  }
  PowerLawFit fit;
  fit.exponent = 0.5 * (lo + hi);
  double mean = 0.0, var = 0.0;
  log_moments(fit.exponent, a, b, mean, var);
  fit.samples = x.size();
  fit.standard_error = 1.0 / std::sqrt(static_cast<double>(x.size()) * var);
  return fit;
}

FieldStatistics field_statistics(std::span<const dynamics::BodyDesc> floes, double region_area, double size_min,
                                 double size_max) {
  FieldStatistics s;
  s.floes = floes.size();
  if (floes.empty()) return s;
  std::vector<double> sizes;
  sizes.reserve(floes.size());
  double area = 0.0, circ = 0.0, corners = 0.0;
  for (const dynamics::BodyDesc& d : floes) {
    const geometry::ConvexPolygon& p = *d.shape;
    area += p.area();
    circ += p.circularity();
    corners += static_cast<double>(p.size());
    sizes.push_back(std::sqrt(4.0 * p.area() / std::numbers::pi));
  }
  const double n = static_cast<double>(floes.size());
  s.concentration = area / region_area;
  s.mean_circularity = circ / n;
  s.mean_corners = corners / n;
  if (size_max > size_min) s.size_distribution = fit_power_law(sizes, size_min, size_max);
  return s;
}

std::string to_string(const FieldStatistics& s) {
  char buf[256];
  std::snprintf(buf, sizeof buf,
                "%zu floes, concentration %.4f, size exponent %.3f +- %.3f (maximum likelihood), mean circularity "
                "%.3f, %.1f corners on average",
                s.floes, s.concentration, s.size_distribution.exponent, s.size_distribution.standard_error,
                s.mean_circularity, s.mean_corners);
  return buf;
}

}  // namespace polyfloe::scene
