// The drift forcing stage: form drag on every dynamic floe's submerged side faces, the drag moment, skin drag on
// its bottom, air drag on its top and Coriolis, into the bodies' forces and the drift model's loads (with the
// damping matrices the final kick treats them semi-implicitly with). It reads the bodies through a DriftBodies
// view and touches nothing else of the World (as the bond stage reads an ElementState).
#pragma once

#include <cstddef>
#include <span>
#include <string>
#include <vector>

#include "dynamics/body.h"
#include "dynamics/drift_model.h"
#include "forcing/drift.h"

namespace polyfloe::dynamics {

// What the drift stage reads of the bodies, by body index.
struct DriftBodies {
  std::span<const BodyId> id;                 // (for messages)
  std::span<const std::uint8_t> dynamic;      // only dynamic bodies feel the drift
  std::span<const Vec2> position;             // centroid [m]
  std::span<const Vec2> velocity;             // as evaluated (the step's prediction) [m/s]
  std::span<const double> omega;              // as evaluated [rad/s]
  std::span<const Vec2> rotation;             // (cos yaw, sin yaw)
  std::span<const double> mass;               // [kg]
  std::span<const double> thickness;          // [m]
  std::span<const double> draft;              // [m]
  std::span<const double> side_area;          // submerged side area [m^2]
  std::span<const double> equivalent_radius;  // sqrt(A / pi) [m]
  std::span<const double> plan_area;          // [m^2]
  // World-frame vertices (counter-clockwise): body i's vert_off[i + 1] - vert_off[i] of them from
  // world_xy[vert_begin[i]].
  std::span<const Vec2> world_xy;
  std::span<const int> vert_begin, vert_off;
  // Bottom and top quadrature: body i's points quad_off[i] .. quad_off[i + 1] - 1, body-frame levers from the
  // centroid [m] and the area each carries [m^2].
  std::span<const int> quad_off;
  std::span<const double> quad_lx, quad_ly, quad_weight;
  std::size_t max_vertices = 0, max_quad_points = 0;  // of any body
};

class DriftForcing {
 public:
  // Every body's drift load at time t [s] (settings `s`) into `model` (a load with its damping matrix where the
  // treatment is semi-implicit, none otherwise) and added to `force` and `torque`; on `threads` threads, the same
  // bits for any number. A field without water at a sample throws forcing::FieldError naming the lowest such body,
  // its position and t.
  void apply(const forcing::DriftSettings& s, const DriftBodies& bodies, double t, int threads, DriftModel& model,
             std::span<Vec2> force, std::span<double> torque);

  // Per-thread scratch: sample points and sampled fluid velocities of one body (no allocation in the loop).
  struct Scratch {
    std::vector<forcing::Vec3> side_points, quad_points;
    std::vector<Vec2> side_water, quad_fluid;
    std::vector<double> quad_rx, quad_ry, quad_fx, quad_fy;  // world-frame levers, sampled fluid (x, y)
    int error_body = -1;     // the lowest body index whose field sample failed this step on this thread
    std::string error_text;  // and the field's message
  };

 private:
  void prepare(const DriftBodies& bodies, int threads);
  std::vector<Scratch> scratch_;
};

}  // namespace polyfloe::dynamics
