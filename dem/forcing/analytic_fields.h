// Analytic velocity fields: uniform, linear (shear, strain, depth shear), solid-body and Rankine vortices, a tidal
// (time-periodic) uniform flow and a piecewise-linear time series; and a field file's grid (gridded_field.h). A
// FieldSpec is plain data (what a scene says);
// make_field() turns a valid one into a VelocityField.
#pragma once

#include <Eigen/Core>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "forcing/field.h"

namespace polyfloe::forcing {

enum class FieldKind { uniform, linear, solid_body, rankine, tidal, time_series, file };
// What a time series or a field file does outside [times.front(), times.back()].
enum class TimeBoundary { clamp, cyclic, error };
// What a field file gives where it has no water: outside its grid in x or y, or in a cell whose weight lies
// entirely on dry (land) nodes.
enum class OutsideWater { error, velocity };

std::string_view to_string(FieldKind k);
std::string_view to_string(TimeBoundary b);
std::string_view to_string(OutsideWater o);

struct GridData;  // forcing/gridded_field.h

struct FieldSpec {
  FieldKind kind = FieldKind::uniform;
  // uniform: the velocity; linear: the velocity at `origin`; vortices: a uniform background added to the swirl;
  // tidal: the mean flow [m/s]
  Vec2 velocity{0.0, 0.0};
  Vec2 origin{0.0, 0.0};                               // linear: reference point; vortices: centre [m]
  Eigen::Matrix2d gradient = Eigen::Matrix2d::Zero();  // linear: [[du/dx, du/dy], [dv/dx, dv/dy]] [1/s]
  Vec2 depth_gradient{0.0, 0.0};                       // linear: [du/dz, dv/dz] [1/s]
  double angular_velocity = 0.0;                       // solid_body: rotation rate, counter-clockwise > 0 [rad/s]
  double core_radius = 0.0;                            // rankine: radius of the solid-body core [m], > 0
  double max_speed = 0.0;                              // rankine: swirl speed at the core radius [m/s], ccw > 0
  Vec2 amplitude{0.0, 0.0};                            // tidal: u = velocity + amplitude cos(2 pi t / period + phase)
  double period = 0.0;                                 // tidal [s], > 0
  double phase = 0.0;                                  // tidal [rad]
  std::vector<double> times;                           // time_series: strictly increasing, >= 2 entries [s]
  std::vector<Vec2> values;                            // time_series: velocity at each time [m/s]
  TimeBoundary outside = TimeBoundary::clamp;          // time_series, file: beyond the times
  std::string path;                                    // file: the field file (absolute once read)
  std::shared_ptr<const GridData> grid;                // file: its content (the scene reader loads it)
  OutsideWater no_water = OutsideWater::error;         // file: where it has no water
  Vec2 no_water_velocity{0.0, 0.0};                    // file: the velocity there with no_water = velocity [m/s]
  Vec2 offset{0.0, 0.0};     // file: where the file's (0, 0) lies in the scene [m]: scene point p samples p - offset
  double time_offset = 0.0;  // file: scene time t samples the file at t + time_offset [s] (skips a spin-up)
  bool land_walls = false;   // file: the file's land becomes fixed walls (land: walls); floe fields avoid it anyway

  static FieldSpec uniform(const Vec2& v) {
    FieldSpec s;
    s.velocity = v;
    return s;
  }
};

// Empty when `spec` can be built; otherwise what is wrong, naming the key (e.g. "period must be > 0 s").
std::string field_spec_error(const FieldSpec& spec);
// Throws std::invalid_argument with field_spec_error() for an invalid spec.
std::shared_ptr<const VelocityField> make_field(const FieldSpec& spec);

}  // namespace polyfloe::forcing
