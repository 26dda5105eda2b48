// The narrow-channel geometry (paper Fig. 9, not in the text; see paper-notes item 9): fixed convex walls.
//
//          basin wall (top)                       funnel (top)    strait wall (top)
//   y_max  ===================================== \\\\\\\\\\ ======================
//                                                    \\             opening (width w, centred on the basin's
//    ice region ->  current, wind  (+x)               ========      mid y)
//                                                    //
//   y_min  ===================================== ////////// ======================
//          x_min                           x_max       x_max + funnel   x_max + funnel + strait
//
// Basin walls lie outside the basin (below y_min, above y_max), wall_thickness thick, from basin_x_min to
// basin_x_max. Each funnel wall is a parallelogram whose inner edge runs from (basin_x_max, y_min or y_max) to the
// opening's edge at x = basin_x_max + funnel_length, with vertical ends, wall_thickness thick measured along y. The
// strait walls are rectangles of length strait_length after that. Neighbouring walls share an end edge, so the
// inner boundary is closed; walls touch but never overlap.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "scene/scene.h"

namespace polyfloe::scene {

struct WallPolygon {
  std::string name;            // "basin wall (y min)", ... for messages and output
  std::vector<Vec2> vertices;  // world frame, counter-clockwise, convex [m]
};

// A problem with one key of a spec: `key` is the key's name inside its block (e.g. "opening").
struct SpecIssue {
  std::string key;
  std::string message;
};

// First inconsistency of the channel settings (non-finite or non-positive lengths, opening not in
// (0, basin width)), or nothing.
std::optional<SpecIssue> channel_issue(const ChannelSpec& spec);

// Throws SceneError "SOURCE: key 'channel.KEY': message" for the first issue.
void validate_channel(const ChannelSpec& spec);

// The six walls: basin (y min), basin (y max), funnel (y min), funnel (y max), strait (y min), strait (y max).
// Validates first.
std::vector<WallPolygon> channel_walls(const ChannelSpec& spec);

}  // namespace polyfloe::scene
