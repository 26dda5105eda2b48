// Realised statistics of a generated floe field: count, concentration, the fitted size-distribution exponent
// (maximum likelihood for the truncated power law of paper Eq. 15-16) and the mean circularity (Eq. 17).
#pragma once

#include <cstddef>
#include <span>
#include <string>

#include "dynamics/body.h"

namespace polyfloe::scene {

// Maximum-likelihood exponent alpha of f(x) = c x^-alpha on [a, b] for the samples x (all in [a, b]): the root of
// E_alpha[ln x] = mean(ln x_i) (E_alpha[ln x] falls monotonically with alpha), with the standard error
// 1 / sqrt(n Var_alpha[ln x]) from the Fisher information.
struct PowerLawFit {
  double exponent = 0.0;        // alpha [-]
  double standard_error = 0.0;  // [-]
  std::size_t samples = 0;
};
PowerLawFit fit_power_law(std::span<const double> x, double a, double b);

struct FieldStatistics {
  std::size_t floes = 0;
  double concentration = 0.0;     // floe area / region area [-]
  PowerLawFit size_distribution;  // of the sizes (area-equivalent diameters) on [size.min, size.max]
  double mean_circularity = 0.0;  // [-]
  double mean_corners = 0.0;      // [-]
};
// Statistics of `floes` (their shapes) in a region of `region_area` [m^2], sizes fitted on [size_min, size_max].
FieldStatistics field_statistics(std::span<const dynamics::BodyDesc> floes, double region_area, double size_min,
                                 double size_max);
// One line: "1152 floes, concentration 0.5000, size exponent 1.98 +- 0.04 (MLE), mean circularity 0.934, 7.5 corners".
std::string to_string(const FieldStatistics& s);

}  // namespace polyfloe::scene
