// Floe-field generator: random strictly convex floes with a power-law size distribution (paper Eq. 15-16), placed
// in a rectangle at a target concentration without initial contact.
//
//   sizes      f(x) = c x^-alpha on [a, b], sampled by inverse CDF; size = diameter of the area-equivalent circle.
//   count      sizes are drawn until their total area reaches concentration x region area; the last floe is
//              resized so that the total is exact (see floe_sizes()).
//   shapes     k corners (k uniform in [corners_min, corners_max]) at sorted random parameter angles on an ellipse
//              of semi-axis ratio uniform in [1, aspect_max], with a minimum angular gap, scaled so that the area
//              is exactly pi size^2 / 4; random orientation. aspect_max = 2.5 reproduces the paper's mean
//              circularities 0.83 / 0.90 / 0.92 for 5-10 / 10-15 / 15-20 corners (docs/validation.md).
//   placement  random sequential adsorption, largest floe first, uniform position with the whole polygon inside the
//              region, rejected when it comes closer than placement_clearance() to a placed floe or an obstacle.
//              A uniform grid over the region keeps each test O(1).
//
// Deterministic for a seed on every platform: std::mt19937_64 with our own integer -> double conversions, no
// standard-library distributions.
#pragma once

#include <cstddef>
#include <cstdint>
#include <random>
#include <span>
#include <vector>

#include "dynamics/body.h"
#include "scene/scene.h"

namespace polyfloe::scene {

// Random numbers with a portable mapping from the engine's 64-bit words.
class FieldRandom {
 public:
  explicit FieldRandom(std::uint64_t seed) : engine_(seed) {}
  double uniform();                      // [0, 1), 53 random bits
  double uniform(double lo, double hi);  // [lo, hi)
  int uniform_int(int lo, int hi);       // [lo, hi], inclusive, unbiased (rejection)

 private:
  std::mt19937_64 engine_;
};

// Quantile (inverse CDF) of the truncated power law f(x) = c x^-alpha on [a, b] at u in [0, 1] [m];
// alpha == 1 (and |alpha - 1| < 1e-12) uses the logarithmic form a (b / a)^u.
double power_law_quantile(double u, double a, double b, double alpha);

// Sizes [m] of the floes of a field (largest first): drawn from the power law until their total area
// sum(pi x^2 / 4) reaches concentration x region area. The last draw is replaced by the floe that makes the total
// exact (size sqrt(4 r / pi) for the remaining area r); if that would be smaller than size_min, r is added to the
// smallest floe drawn instead (when it stays <= size_max), else it is dropped (the total then falls short by less
// than one smallest floe). Throws SceneError if the target area is below one floe of size_min, or needs more than
// kMaxFieldFloes floes (a region given in the wrong unit would otherwise exhaust the memory).
inline constexpr std::size_t kMaxFieldFloes = 10'000'000;
std::vector<double> floe_sizes(const FloeFieldSpec& spec, FieldRandom& rng);

// A random strictly convex counter-clockwise polygon with `corners` vertices on an ellipse of semi-axis ratio
// uniform in [1, aspect_max] (a circle for aspect_max = 1), at sorted random parameter angles (every gap
// >= kMinGapFraction x 2 pi / corners), randomly oriented, scaled to the area pi size^2 / 4 exactly, centroid at
// the origin [m].
inline constexpr double kMinGapFraction = 0.05;
std::vector<Vec2> random_floe_polygon(FieldRandom& rng, int corners, double size, double aspect_max = 1.0);

// Separating-axis measure of two convex counter-clockwise polygons: the largest gap between them measured along any
// edge normal of either [m]. > 0: separated, and their distance is at least this value; <= 0: they touch or
// overlap (minus the least penetration along an edge normal).
double polygon_separation(std::span<const Vec2> a, std::span<const Vec2> b);

// Least distance kept between two generated floes, or a floe and an obstacle: 1 % of the smaller size, at most
// 0.5 m [m].
double placement_clearance(double size);

struct FloeField {
  std::vector<dynamics::BodyDesc> floes;  // largest first, ids first_id, first_id + 1, ...
  double ice_area = 0.0;                  // sum of floe areas [m^2]
  double region_area = 0.0;               // [m^2]
  double concentration = 0.0;             // ice_area / region_area [-]
  std::uint64_t attempts = 0;             // placement tries in total [-]
};

// Generates the field. `density` [kg/m^3] goes into each BodyDesc; `obstacles` are world-frame convex
// counter-clockwise polygons (walls, explicit bodies) the floes must keep clear of. Throws SceneError (prefixed
// with spec.source) when a floe cannot be placed in spec.max_attempts tries, naming the floe, the concentration
// reached and what to change.
FloeField generate_floe_field(const FloeFieldSpec& spec, double density, dynamics::BodyId first_id,
                              std::span<const std::vector<Vec2>> obstacles = {});

}  // namespace polyfloe::scene
