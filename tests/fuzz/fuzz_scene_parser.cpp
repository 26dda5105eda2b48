// libFuzzer target: the scene reader (scene::parse_scene) and, when that is cheap, scene::build_world.
//
// The input is the text of a scene file. Lines of the form "#--set key.path=value" (YAML comments, so the scene text
// itself is unchanged) are also passed as --set overrides, in order, so the override paths are fuzzed too.
//
// What must hold:
//   parse_scene() returns a Scene or throws SceneError (its contract; the command line reports it as bad input);
//   an accepted scene's resolved_yaml() reads back (parse_scene) and resolves to the same text, comments aside (a
//   fixed point);
//   build_world() (and time_step()) return, or throw one of the errors the command line reports as bad input:
//   SceneError, GeometryError, std::invalid_argument.
// Any other exception, a crash, a sanitizer report, a leak or a time-out is a finding.
//
// Legitimately huge work is not built (the scene is still parsed and resolved): build_world() is skipped when
//   - a floe field's expected floe count, concentration x region area / the mean floe area of its size
//     distribution, exceeds kMaxFloes (or is not finite);
//   - an ice sheet has more than kMaxElements elements (cells, or 6 triangles per cell), or its Voronoi work,
//     cells x (1 + relaxation), exceeds kMaxSheetWork;
// and a floe field's max_attempts is capped at kMaxAttempts tries per floe (the failure path is still reached).
// Under the sanitizers a built sheet costs about 1 ms per cell and Lloyd iteration, a floe field 0.1 ms per floe,
// so an execution stays below about 0.5 s. Of the example scenes, channel.yaml (1,152 floes) is built;
// pack_ice_sheet.yaml (573 cells x 3) and uniaxial_compression.yaml (3,700 triangles) are only read (the fuzzer
// builds their smaller variants).
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <numbers>
#include <stdexcept>
#include <string>
#include <vector>

#include "geometry/polygon.h"
#include "scene/field_statistics.h"
#include "scene/floe_field.h"
#include "scene/scene.h"
#include "scene/scene_reader.h"

namespace {

using namespace polyfloe;

constexpr double kMaxFloes = 1500.0;
constexpr double kMaxElements = 500.0;
constexpr double kMaxSheetWork = 500.0;
constexpr int kMaxAttempts = 1000;

[[noreturn]] void finding(const std::string& what, const std::string& detail) {
  std::fprintf(stderr, "fuzz_scene_parser: %s\n%s\n", what.c_str(), detail.c_str());
  std::abort();
}

// "#--set key=value" lines.
std::vector<std::string> overrides_in(const std::string& text) {
  static const std::string kMarker = "#--set ";
  std::vector<std::string> out;
  for (std::size_t line = 0; line < text.size();) {
    std::size_t end = text.find('\n', line);
    if (end == std::string::npos) end = text.size();
    if (text.compare(line, kMarker.size(), kMarker) == 0)
      out.push_back(text.substr(line + kMarker.size(), end - line - kMarker.size()));
    line = end + 1;
  }
  return out;
}

// resolved_yaml() without its comments (they name where each value came from, which differs on reading back):
// whole comment lines, and from "  #" outside a double-quoted string to the end of a line.
std::string without_comments(const std::string& yaml) {
  std::string out;
  for (std::size_t line = 0; line < yaml.size();) {
    std::size_t end = yaml.find('\n', line);
    if (end == std::string::npos) end = yaml.size();
    std::size_t cut = end;
    bool quoted = false;
    for (std::size_t i = line; i < end; ++i) {
      if (quoted && yaml[i] == '\\')
        ++i;
      else if (yaml[i] == '"')
        quoted = !quoted;
      else if (!quoted && yaml[i] == '#' && (i == line || yaml[i - 1] == ' ')) {
        cut = i;
        break;
      }
    }
    while (cut > line && yaml[cut - 1] == ' ') --cut;
    if (cut > line) out.append(yaml, line, cut - line).push_back('\n');
    line = end + 1;
  }
  return out;
}

// Expected number of floes of a field: target ice area / mean floe area (midpoint rule on the quantile function).
double expected_floes(const scene::FloeFieldSpec& f) {
  const geometry::Vec2 extent = f.region_max - f.region_min;
  const double target = f.concentration * extent.x() * extent.y();  // [m^2]
  constexpr int kPoints = 64;
  double mean_area = 0.0;
  for (int i = 0; i < kPoints; ++i) {
    const double x = scene::power_law_quantile((i + 0.5) / kPoints, f.size_min, f.size_max, f.exponent);
    mean_area += 0.25 * std::numbers::pi * x * x / kPoints;
  }
  return target / mean_area;
}

bool cheap_to_build(const scene::Scene& s) {
  if (s.spatial && s.spatial->bodies.size() > 200) return false;  // the initial-overlap check is all pairs
  if (const auto& f = s.floe_field) {
    const double n = expected_floes(*f);
    if (!(n <= kMaxFloes)) return false;  // also NaN / inf
  }
  if (const auto& sh = s.ice_sheet) {
    const double area = (sh->region_max - sh->region_min).prod();
    const double cells = std::max(1.0, area / (0.25 * std::numbers::pi * sh->cell_size * sh->cell_size));
    const double elements = cells * (sh->elements == scene::SheetElements::triangles ? 6.0 : 1.0);
    if (!(elements <= kMaxElements) || !(cells * (1.0 + sh->relaxation) <= kMaxSheetWork)) return false;
  }
  return true;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  const std::vector<std::string> overrides = overrides_in(text);
  scene::Scene s;
  try {
    s = scene::parse_scene(text, "fuzz.yaml", overrides);
  } catch (const scene::SceneError&) {
    return 0;  // rejected with a message: fine
  }

  // The resolved settings are themselves a scene that reads back to the same settings.
  const std::string resolved = scene::resolved_yaml(s);
  try {
    const scene::Scene back = scene::parse_scene(resolved, "fuzz.yaml");
    const std::string again = scene::resolved_yaml(back);
    if (without_comments(again) != without_comments(resolved))
      finding("resolved_yaml() is not a fixed point", resolved + "\n---- read back as:\n" + again);
  } catch (const scene::SceneError& e) {
    finding("resolved_yaml() of an accepted scene is rejected: " + std::string(e.what()), resolved);
  }

  if (!cheap_to_build(s)) return 0;
  if (s.floe_field) s.floe_field->max_attempts = std::min(s.floe_field->max_attempts, kMaxAttempts);
  try {
    double dt = 0.0;
    if (s.spatial) {
      const dynamics::SpatialWorld world = scene::build_spatial_world(s);
      dt = scene::time_step(s, world);
    } else {
      scene::FieldStatistics stats;
      const dynamics::World world = scene::build_world(s, &stats);
      dt = scene::time_step(s, world);
    }
    if (!(dt > 0.0) || !std::isfinite(dt)) finding("time_step() is not positive and finite", std::to_string(dt));
  } catch (const scene::SceneError&) {
  } catch (const geometry::GeometryError&) {
  } catch (const std::invalid_argument&) {
  }
  return 0;
}
