#include "scene/floe_field.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <numbers>
#include <optional>
#include <sstream>

#include "geometry/voronoi.h"
#include "scene/floe_placement.h"

namespace polyfloe::scene {

using detail::PlacedSet;
using detail::prepare;
using detail::PreparedPolygon;

namespace {

// splitmix64: derives independent engine seeds (sizes and shapes / placement) from the user's seed.
std::uint64_t mix_seed(std::uint64_t seed, std::uint64_t stream) {
  std::uint64_t z = seed + 0x9E3779B97F4A7C15ULL * (stream + 1);
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
  return z ^ (z >> 31);
}

double circle_area(double size) { return 0.25 * std::numbers::pi * size * size; }  // [m^2]

std::string prefix(const FloeFieldSpec& spec) {
  return spec.source.where.empty() ? std::string() : spec.source.where + ": ";
}

void check_spec(const FloeFieldSpec& s) {
  auto fail = [&](const std::string& what) { throw SceneError(prefix(s) + "floe_field: " + what); };
  if (!(s.region_max.x() > s.region_min.x()) || !(s.region_max.y() > s.region_min.y()))
    fail("region must have xmax > xmin and ymax > ymin");
  if (!(s.concentration > 0.0 && s.concentration < 1.0)) fail("concentration must lie in (0, 1)");
  if (!(s.size_min > 0.0) || !(s.size_max >= s.size_min) || !std::isfinite(s.size_max))
    fail("sizes must satisfy 0 < size.min <= size.max");
  if (!std::isfinite(s.exponent)) fail("size.exponent must be finite");
  if (s.corners_min < 3 || s.corners_max < s.corners_min || s.corners_max > 64)
    fail("corners must satisfy 3 <= min <= max <= 64");
  if (!(s.thickness > 0.0)) fail("thickness must be > 0");
  if (s.max_attempts < 1) fail("max_attempts must be >= 1");
}

// Floe outlines cut from Poisson-Voronoi tessellations of the unit square: interior cells (not touching the square's
// sides, which clip) whose corner count lies in the spec's range, each normalised to unit area about its centroid.
// Corners closer than kMergeFraction of the cell's perimeter are merged first (a Voronoi cell can have edges a
// millionth of its size, which no contact model resolves), and the count is taken after merging.
class VoronoiShapes {
 public:
  static constexpr int kSitesPerBatch = 4096;
  static constexpr int kMaxBatches = 16;
  static constexpr std::size_t kWanted = 1024;  // distinct outlines to draw from
  static constexpr std::size_t kMinimum = 32;   // fewer than this in range: refuse
  static constexpr double kMergeFraction = 1e-3;

  VoronoiShapes(const FloeFieldSpec& spec, FieldRandom& rng) {
    const geometry::Aabb unit{{0.0, 0.0}, {1.0, 1.0}};
    std::vector<Vec2> sites(kSitesPerBatch);
    int batches = 0;
    for (; batches < kMaxBatches && shapes_.size() < kWanted; ++batches) {
      for (Vec2& x : sites) x = {rng.uniform(1e-9, 1.0 - 1e-9), rng.uniform(1e-9, 1.0 - 1e-9)};
      for (std::vector<Vec2>& cell : geometry::voronoi_cells(sites, unit)) {
        const bool clipped = std::any_of(cell.begin(), cell.end(), [](const Vec2& v) {
          return v.x() <= 1e-9 || v.y() <= 1e-9 || v.x() >= 1.0 - 1e-9 || v.y() >= 1.0 - 1e-9;
        });
        if (clipped) continue;
        merge_short_edges(cell);
        const int k = static_cast<int>(cell.size());
        if (k < spec.corners_min || k > spec.corners_max || !geometry::convexity_error(cell).empty()) continue;
        const geometry::PolygonProperties props = geometry::polygon_properties(cell);
        const double scale = 1.0 / std::sqrt(props.area);
        for (Vec2& v : cell) v = scale * (v - props.centroid);
        shapes_.push_back(std::move(cell));
      }
    }
    if (shapes_.size() < kMinimum) {
      std::ostringstream msg;
      msg << prefix(spec) << "floe_field.corners: only " << shapes_.size() << " of " << batches * kSitesPerBatch
          << " Voronoi cells have " << spec.corners_min << " to " << spec.corners_max
          << " corners (a Poisson-Voronoi cell has 6 on average and rarely more than 10); with shape: voronoi use "
             "a range that reaches below 12 corners, or shape: ellipse";
      throw SceneError(msg.str());
    }
  }

  // A random outline of the pool, randomly rotated, with the area of a circle of diameter `size` [m].
  std::vector<Vec2> draw(FieldRandom& rng, double size) const {
    const std::vector<Vec2>& unit =
        shapes_[static_cast<std::size_t>(rng.uniform_int(0, static_cast<int>(shapes_.size()) - 1))];
    const double turn = rng.uniform(0.0, 2.0 * std::numbers::pi);
    const double c = std::cos(turn), s = std::sin(turn), scale = std::sqrt(circle_area(size));
    std::vector<Vec2> v;
    v.reserve(unit.size());
    for (const Vec2& x : unit) v.push_back(scale * geometry::rotate(x, c, s));
    return v;
  }
  std::size_t size() const { return shapes_.size(); }

 private:
  // Drops the later corner of every edge shorter than kMergeFraction x perimeter (a convex polygon stays convex
  // when a corner is removed).
  static void merge_short_edges(std::vector<Vec2>& v) {
    double perimeter = 0.0;
    for (std::size_t i = 0; i < v.size(); ++i) perimeter += (v[(i + 1) % v.size()] - v[i]).norm();
    const double shortest = kMergeFraction * perimeter;
    for (std::size_t i = 0; v.size() > 3 && i < v.size();) {
      if ((v[(i + 1) % v.size()] - v[i]).norm() < shortest) {
        v.erase(v.begin() + static_cast<std::ptrdiff_t>((i + 1) % v.size()));
        if (i >= v.size()) i = 0;
      } else {
        ++i;
      }
    }
  }

  std::vector<std::vector<Vec2>> shapes_;
};

}  // namespace

double FieldRandom::uniform() { return static_cast<double>(engine_() >> 11) * 0x1.0p-53; }

double FieldRandom::uniform(double lo, double hi) { return lo + (hi - lo) * uniform(); }

int FieldRandom::uniform_int(int lo, int hi) {
  const std::uint64_t n = static_cast<std::uint64_t>(static_cast<std::int64_t>(hi) - lo) + 1;
  // Reject the lowest 2^64 mod n words so that every residue is equally likely.
  const std::uint64_t threshold = (0 - n) % n;
  std::uint64_t x = engine_();
  while (x < threshold) x = engine_();
  return static_cast<int>(static_cast<std::int64_t>(lo) + static_cast<std::int64_t>(x % n));
}

double power_law_quantile(double u, double a, double b, double alpha) {
  u = std::clamp(u, 0.0, 1.0);
  if (std::abs(alpha - 1.0) < 1e-12) return a * std::pow(b / a, u);
  // F(x) = (x^(1-alpha) - a^(1-alpha)) / (b^(1-alpha) - a^(1-alpha))
  const double g = 1.0 - alpha;
  const double ag = std::pow(a, g), bg = std::pow(b, g);
  return std::clamp(std::pow(ag + u * (bg - ag), 1.0 / g), a, b);
}

std::vector<double> floe_sizes(const FloeFieldSpec& spec, FieldRandom& rng) {
  check_spec(spec);
  const Vec2 extent = spec.region_max - spec.region_min;
  const double target = spec.concentration * extent.x() * extent.y();  // [m^2]
  const double area_min = circle_area(spec.size_min), area_max = circle_area(spec.size_max);
  if (target < area_min) {
    std::ostringstream msg;
    msg << prefix(spec) << "floe_field: the target ice area " << target << " m^2 (concentration x region area) is "
        << "smaller than one floe of size.min (" << area_min << " m^2); enlarge the region or the concentration";
    throw SceneError(msg.str());
  }
  std::vector<double> areas;
  double sum = 0.0;
  while (true) {
    const double x = power_law_quantile(rng.uniform(), spec.size_min, spec.size_max, spec.exponent);
    const double a = circle_area(x);
    if (sum + a < target) {
      if (areas.size() == kMaxFieldFloes) {
        std::ostringstream msg;
        msg << prefix(spec) << "floe_field: the target ice area " << target << " m^2 (concentration x region area) "
            << "needs more than " << kMaxFieldFloes << " floes of these sizes; shrink floe_field.region or raise "
            << "floe_field.size";
        throw SceneError(msg.str());
      }
      areas.push_back(a);
      sum += a;
      continue;
    }
    const double rest = target - sum;  // what the last floe must add [m^2]
    if (rest >= area_min) {
      areas.push_back(rest);
    } else if (!areas.empty()) {
      auto smallest = std::min_element(areas.begin(), areas.end());
      if (*smallest + rest <= area_max) *smallest += rest;
    }
    break;
  }
  std::vector<double> sizes(areas.size());
  std::transform(areas.begin(), areas.end(), sizes.begin(), [&](double a) {
    return std::clamp(std::sqrt(4.0 * a / std::numbers::pi), spec.size_min, spec.size_max);
  });
  std::sort(sizes.begin(), sizes.end(), std::greater<>());
  return sizes;
}

std::vector<Vec2> random_floe_polygon(FieldRandom& rng, int corners, double size, double aspect_max) {
  const int k = corners;
  const double two_pi = 2.0 * std::numbers::pi;
  const double min_gap = kMinGapFraction * two_pi / k;  // [rad]
  // Spacings of k - 1 sorted uniforms on [0, 1] (k parts summing to 1), then each gap = min_gap + share of the rest.
  std::vector<double> cuts(static_cast<std::size_t>(k - 1));
  for (double& c : cuts) c = rng.uniform();
  std::sort(cuts.begin(), cuts.end());
  const double free_angle = two_pi - k * min_gap;  // [rad]
  const double start = rng.uniform(0.0, two_pi);   // where the corners start on the ellipse [rad]
  const double aspect = aspect_max > 1.0 ? rng.uniform(1.0, aspect_max) : 1.0;  // semi-axis ratio [-]
  const double turn = rng.uniform(0.0, two_pi);  // random orientation of the ellipse [rad]
  const double ct = std::cos(turn), st = std::sin(turn);
  std::vector<Vec2> v(static_cast<std::size_t>(k));
  for (int i = 0; i < k; ++i) {
    // vertex i sits after i gaps: i min_gaps plus the free angle up to cut i-1
    const double share = i == 0 ? 0.0 : cuts[static_cast<std::size_t>(i - 1)];
    const double angle = start + i * min_gap + free_angle * share;
    // Points of an ellipse in parameter order are in strictly convex position.
    v[static_cast<std::size_t>(i)] = geometry::rotate(Vec2(aspect * std::cos(angle), std::sin(angle)), ct, st);
  }
  const geometry::PolygonProperties props = geometry::polygon_properties(v);
  const double scale = std::sqrt(circle_area(size) / props.area);
  for (Vec2& x : v) x = scale * (x - props.centroid);
  return v;
}

double polygon_separation(std::span<const Vec2> a, std::span<const Vec2> b) {
  double best = -std::numeric_limits<double>::infinity();
  auto along_normals = [&best](std::span<const Vec2> p, std::span<const Vec2> q) {
    const std::size_t k = p.size();
    for (std::size_t i = 0; i < k; ++i) {
      const Vec2 e = p[(i + 1) % k] - p[i];
      const double len = e.norm();
      if (len <= 0.0) continue;
      const Vec2 n = geometry::perp_right(e) / len;
      double lowest = std::numeric_limits<double>::infinity();
      for (const Vec2& x : q) lowest = std::min(lowest, n.dot(x - p[i]));
      best = std::max(best, lowest);
    }
  };
  along_normals(a, b);
  along_normals(b, a);
  return best;
}

double placement_clearance(double size) { return std::min(0.01 * size, 0.5); }

namespace {

[[noreturn]] void refuse(const FloeFieldSpec& spec, const std::string& what) {
  throw SceneError(prefix(spec) + "floe_field: " + what);
}

// "0.5432 of the target 0.6": where a field stopped, for the messages.
std::string reached(const FloeField& field, const FloeFieldSpec& spec) {
  std::ostringstream msg;
  msg.precision(4);
  msg << field.ice_area / field.region_area << " of the target " << spec.concentration;
  return msg.str();
}

dynamics::BodyDesc floe_desc(const FloeFieldSpec& spec, double density, dynamics::BodyId id,
                             std::shared_ptr<const geometry::ConvexPolygon> shape, const Vec2& position) {
  dynamics::BodyDesc desc;
  desc.id = id;
  desc.shape = std::move(shape);
  desc.position = position;
  desc.yaw = 0.0;  // the random orientation is in the shape itself
  desc.velocity = spec.velocity;
  desc.thickness = spec.thickness;
  desc.density = density;
  desc.motion = dynamics::Motion::dynamic;
  return desc;
}

// The sizes are drawn to make up the target area; a field far from it would be a wrong result, not a field.
// (The last floe may be left out when what it would add is smaller than one floe of size.min.)
void check_concentration(const FloeField& field, const FloeFieldSpec& spec) {
  const double slack = 0.01 * spec.concentration + circle_area(spec.size_min) / field.region_area;
  if (std::abs(field.concentration - spec.concentration) <= slack) return;
  std::ostringstream msg;
  msg.precision(4);
  msg << "the generated field has concentration " << field.concentration << ", not the target " << spec.concentration
      << " (" << field.floes.size() << " floes); check floe_field.size and floe_field.region";
  refuse(spec, msg.str());
}

}  // namespace

FloeField generate_floe_field(const FloeFieldSpec& spec, double density, dynamics::BodyId first_id,
                              std::span<const std::vector<Vec2>> obstacles) {
  check_spec(spec);
  FloeField field;
  const Vec2 lo = spec.region_min, hi = spec.region_max;
  field.region_area = (hi - lo).prod();

  FieldRandom shape_rng(mix_seed(spec.seed, 0));
  FieldRandom place_rng(mix_seed(spec.seed, 1));
  const std::vector<double> sizes = floe_sizes(spec, shape_rng);

  // Cells of about twice the smallest floe: the many small floes then test a handful of cells each, and the
  // grid stays below ~4 million cells.
  PlacedSet placed(lo, hi, std::max({2.0 * spec.size_min, (hi - lo).maxCoeff() / 2048.0, 1e-9}));
  placed.add_obstacles(obstacles, sizes.size());

  field.floes.reserve(sizes.size());
  std::optional<VoronoiShapes> voronoi;  // its own random stream: ellipse fields stay as they were
  if (spec.shape == FloeShape::voronoi) {
    FieldRandom pool_rng(mix_seed(spec.seed, 2));
    voronoi.emplace(spec, pool_rng);
  }
  const double attempt_budget =
      FloeFieldSpec::kBaseAttempts + FloeFieldSpec::kAttemptsPerFloe * static_cast<double>(sizes.size());
  for (std::size_t f = 0; f < sizes.size(); ++f) {
    const double size = sizes[f];
    const std::vector<Vec2> raw =
        voronoi ? voronoi->draw(shape_rng, size)
                : random_floe_polygon(shape_rng, shape_rng.uniform_int(spec.corners_min, spec.corners_max), size,
                                      spec.aspect_max);
    auto shape = std::make_shared<const geometry::ConvexPolygon>(geometry::ConvexPolygon::from_vertices(raw));
    const PreparedPolygon body = prepare(shape->vertices());
    const double gap = placement_clearance(size);  // sizes descend: this floe is the smaller of any pair [m]

    // Positions of the centroid that keep the whole polygon inside the region.
    const Vec2 p_lo = lo - body.box.lo, p_hi = hi - body.box.hi;
    if (p_lo.x() > p_hi.x() || p_lo.y() > p_hi.y()) {
      std::ostringstream msg;
      msg << "floe " << f + 1 << " (size " << size
          << " m) does not fit in the region; lower floe_field.size.max or enlarge floe_field.region";
      refuse(spec, msg.str());
    }
    bool done = false;
    for (int attempt = 0; attempt < spec.max_attempts && !done; ++attempt) {
      if (static_cast<double>(++field.attempts) > attempt_budget) {
        std::ostringstream msg;
        msg.precision(4);
        msg << "placing " << f << " of " << sizes.size() << " floes took more than " << attempt_budget
            << " random tries in all (the concentration reached is " << reached(field, spec)
            << "); lower floe_field.concentration or floe_field.max_attempts";
        refuse(spec, msg.str());
      }
      const Vec2 p(place_rng.uniform(p_lo.x(), p_hi.x()), place_rng.uniform(p_lo.y(), p_hi.y()));
      if (!placed.clear(body, p, gap)) continue;
      placed.add(body, p);
      field.floes.push_back(floe_desc(spec, density, first_id + f, shape, p));
      field.ice_area += shape->area();
      done = true;
    }
    if (!done) {
      std::ostringstream msg;
      msg.precision(4);
      msg << "could not place floe " << f + 1 << " of " << sizes.size() << " (size " << size << " m) after "
          << spec.max_attempts << " attempts; the concentration reached is " << reached(field, spec)
          << "; lower floe_field.concentration (or widen floe_field.size)";
      refuse(spec, msg.str());
    }
  }
  field.concentration = field.ice_area / field.region_area;
  check_concentration(field, spec);
  return field;
}

}  // namespace polyfloe::scene
