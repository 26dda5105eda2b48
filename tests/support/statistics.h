// Order statistics of measured samples, for the benchmarks and tests that report medians and percentiles.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <vector>

namespace polyfloe::tsupport {

// Linear interpolation between order statistics; NaN for an empty set.
inline double percentile(std::vector<double> v, double q) {
  if (v.empty()) return std::nan("");
  std::sort(v.begin(), v.end());
  const double pos = q * static_cast<double>(v.size() - 1);
  const std::size_t i = static_cast<std::size_t>(pos);
  const double f = pos - static_cast<double>(i);
  return i + 1 < v.size() ? v[i] * (1.0 - f) + v[i + 1] * f : v[i];
}

// Max against min of positive samples as a +- about their middle: (max - min) / (max + min); NaN for an empty set.
inline double spread(const std::vector<double>& v) {
  if (v.empty()) return std::nan("");
  const auto [lo, hi] = std::minmax_element(v.begin(), v.end());
  return (*hi - *lo) / (*hi + *lo);
}

}  // namespace polyfloe::tsupport
