// What a body is before it enters the World: shape, state, how it moves.
#pragma once

#include <cstdint>
#include <memory>
#include <span>
#include <string_view>
#include <vector>

#include "geometry/polygon.h"

namespace polyfloe::dynamics {

using geometry::Vec2;

// Stable body identifier: never reused, never an index. Contact history and output are keyed by it.
using BodyId = std::uint64_t;

// The indices of `ids` in increasing id, into `order` (the worlds' id_order()).
void sort_by_id(std::span<const BodyId> ids, std::vector<int>& order);

enum class Motion : std::uint8_t {
  dynamic = 0,    // integrated from forces
  fixed = 1,      // static: never moves (channel walls)
  kinematic = 2,  // moves with a prescribed velocity and angular velocity, whatever the forces (plates)
};

std::string_view to_string(Motion m);

struct BodyDesc {
  BodyId id = 0;
  std::shared_ptr<const geometry::ConvexPolygon> shape;  // body frame, centroid at origin
  Vec2 position{0.0, 0.0};                               // centroid [m]
  double yaw = 0.0;                                      // rotation of the body frame [rad]
  Vec2 velocity{0.0, 0.0};                               // [m/s]
  double angular_velocity = 0.0;                         // [rad/s], counter-clockwise positive
  double thickness = 1.0;                                // [m]
  double density = 920.0;                                // [kg/m^3]
  Motion motion = Motion::dynamic;
  Vec2 external_force{0.0, 0.0};  // constant applied force at the centroid [N]
  double external_torque = 0.0;   // constant applied torque about z [N m]
};

}  // namespace polyfloe::dynamics
