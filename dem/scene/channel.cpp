#include "scene/channel.h"

#include <cmath>
#include <sstream>

namespace polyfloe::scene {

namespace {

std::string number(double x) {
  std::ostringstream s;
  s << x;
  return s.str();
}

}  // namespace

std::optional<SpecIssue> channel_issue(const ChannelSpec& s) {
  const struct {
    const char* key;
    double value;
  } finite[] = {{"basin_x_min", s.basin_x_min},     {"basin_x_max", s.basin_x_max},      {"basin_y_min", s.basin_y_min},
                {"basin_y_max", s.basin_y_max},     {"funnel_length", s.funnel_length},  {"opening", s.opening},
                {"strait_length", s.strait_length}, {"wall_thickness", s.wall_thickness}};
  // A channel of at most 10,000 km: beyond, the wall polygons leave the range where areas and moments are normal
  // doubles.
  constexpr double kMaxLength = 1e7;  // [m]
  for (const auto& f : finite)
    if (!(std::abs(f.value) <= kMaxLength))
      return SpecIssue{f.key, number(f.value) + " is outside the allowed range [-1e+07, 1e+07] [m]"};
  if (!(s.basin_x_max > s.basin_x_min))
    return SpecIssue{"basin_x_max",
                     number(s.basin_x_max) + " must be > basin_x_min = " + number(s.basin_x_min) + " [m]"};
  if (!(s.basin_y_max > s.basin_y_min))
    return SpecIssue{"basin_y_max",
                     number(s.basin_y_max) + " must be > basin_y_min = " + number(s.basin_y_min) + " [m]"};
  if (!(s.funnel_length > 0.0)) return SpecIssue{"funnel_length", number(s.funnel_length) + " must be > 0 [m]"};
  if (!(s.strait_length > 0.0)) return SpecIssue{"strait_length", number(s.strait_length) + " must be > 0 [m]"};
  if (!(s.wall_thickness > 0.0)) return SpecIssue{"wall_thickness", number(s.wall_thickness) + " must be > 0 [m]"};
  const double width = s.basin_y_max - s.basin_y_min;
  if (!(s.opening > 0.0 && s.opening < width))
    return SpecIssue{"opening", number(s.opening) + " is outside the allowed range (0, " + number(width) +
                                    ") [m] (0 < opening < basin width basin_y_max - basin_y_min)"};
  return std::nullopt;
}

void validate_channel(const ChannelSpec& spec) {
  if (std::optional<SpecIssue> issue = channel_issue(spec)) {
    const std::string where = spec.source.where.empty() ? std::string() : spec.source.where + ": ";
    throw SceneError(where + "key 'channel." + issue->key + "': " + issue->message);
  }
}

std::vector<WallPolygon> channel_walls(const ChannelSpec& s) {
  validate_channel(s);
  const double t = s.wall_thickness;
  const double x0 = s.basin_x_min, x1 = s.basin_x_max;
  const double x2 = x1 + s.funnel_length, x3 = x2 + s.strait_length;
  const double y_lo = s.basin_y_min, y_hi = s.basin_y_max;
  const double mid = 0.5 * (y_lo + y_hi);
  const double o_lo = mid - 0.5 * s.opening, o_hi = mid + 0.5 * s.opening;  // the opening's edges [m]

  std::vector<WallPolygon> w;
  w.push_back({"basin wall (y min)", {{x0, y_lo - t}, {x1, y_lo - t}, {x1, y_lo}, {x0, y_lo}}});
  w.push_back({"basin wall (y max)", {{x0, y_hi}, {x1, y_hi}, {x1, y_hi + t}, {x0, y_hi + t}}});
  w.push_back({"funnel wall (y min)", {{x1, y_lo - t}, {x2, o_lo - t}, {x2, o_lo}, {x1, y_lo}}});
  w.push_back({"funnel wall (y max)", {{x1, y_hi}, {x2, o_hi}, {x2, o_hi + t}, {x1, y_hi + t}}});
  w.push_back({"strait wall (y min)", {{x2, o_lo - t}, {x3, o_lo - t}, {x3, o_lo}, {x2, o_lo}}});
  w.push_back({"strait wall (y max)", {{x2, o_hi}, {x3, o_hi}, {x3, o_hi + t}, {x2, o_hi + t}}});
  return w;
}

}  // namespace polyfloe::scene
