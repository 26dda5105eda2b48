// A velocity field given on a rectilinear grid of snapshots: what an ocean field file holds (OpenFOAM output
// resampled by coupling/, docs/scene-reference.md "Field files"). Trilinear in space, linear between snapshots,
// with the scene's choice beyond the last snapshot (clamp, cyclic, error) and where the grid has no water.
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "forcing/analytic_fields.h"
#include "forcing/field.h"

namespace polyfloe::forcing {

// The grid and its samples. Axes are strictly increasing; z (height, <= 0 in the water) and t may hold a single
// value: the field is then the same at every depth, or steady. Node (it, iz, iy, ix) is element
// ((it * nz + iz) * ny + iy) * nx + ix of u and v; node (iz, iy, ix) of `wet` is 1 in the water, 0 on land or
// outside the fluid mesh, where u = v = 0 (the no-slip value at a wall).
struct GridData {
  std::vector<double> x, y, z, t;  // [m], [m], [m], [s]
  std::vector<double> u, v;        // horizontal velocity [m/s]
  std::vector<std::uint8_t> wet;   // 1 = water

  std::size_t nodes_per_snapshot() const { return x.size() * y.size() * z.size(); }
  std::size_t index(std::size_t it, std::size_t iz, std::size_t iy, std::size_t ix) const {
    return ((it * z.size() + iz) * y.size() + iy) * x.size() + ix;
  }
};

// The fastest velocity component a field may hold [m/s]: beyond, the drag terms (quadratic in speed) leave the
// range the integrator resolves, and the file is surely in other units.
inline constexpr double kMaxFieldSpeed = 1e3;

// Empty when `g` is a usable grid; otherwise what is wrong ("axis y is not strictly increasing at index 4",
// "u has 10 values, expected 12 (t x z x y x x)", "u is not finite at node (t 0, z 1, y 3, x 2)").
std::string grid_data_error(const GridData& g);

// The land of a grid's surface level (the level nearest z = 0) as axis-aligned rectangles [m] in the grid's
// coordinates: each dry node stands for the square of one spacing around it (the coast half-way between a wet and a
// dry node, within half a spacing of the fluid mesh's wall), squares merged into runs along x and runs of the same
// extent into rectangles along y. Convex pieces that tile the land without overlapping.
struct LandRectangle {
  Vec2 lo, hi;
};
std::vector<LandRectangle> land_rectangles(const GridData& g);

struct GriddedFieldOptions {
  TimeBoundary time_outside = TimeBoundary::clamp;  // beyond [t.front(), t.back()]
  OutsideWater no_water = OutsideWater::error;      // outside the grid in x or y, or on land
  Vec2 no_water_velocity{0.0, 0.0};                 // [m/s] with no_water = velocity
  std::string source;                               // the file, for error messages
  Vec2 offset{0.0, 0.0};     // where the grid's (0, 0) lies [m]: point p samples the grid at p - offset
  double time_offset = 0.0;  // time t samples the snapshots at t + time_offset [s]
};

// Where t falls among strictly increasing snapshot times: the earlier snapshot and the weight of the next one (0
// with a single snapshot: steady), after applying `outside` beyond them. Throws FieldError naming `source` for a t
// beyond them with TimeBoundary::error. Shared by every field made of snapshots (coupling/'s direct mode too).
struct TimeBracket {
  std::size_t i = 0;
  double w = 0.0;
};
TimeBracket time_bracket(std::span<const double> times, double t, TimeBoundary outside, const std::string& source);

class GriddedField final : public VelocityField {
 public:
  // Throws std::invalid_argument with grid_data_error() for an unusable grid.
  GriddedField(std::shared_ptr<const GridData> grid, GriddedFieldOptions options);
  // Outside the z range the nearest level is used (a floe drafting deeper than the grid's last level feels
  // that level's current).
  void sample(double t, std::span<const Vec3> points, std::span<Vec2> out) const override;
  const GridData& grid() const { return *grid_; }
  const GriddedFieldOptions& options() const { return options_; }

  // An axis's spacing, found once: uniform axes are indexed directly, others searched.
  struct AxisScale {
    bool uniform = false;
    double inv_h = 0.0;  // [1/m]
  };

 private:
  static AxisScale scale_of(const std::vector<double>& a);
  std::shared_ptr<const GridData> grid_;
  GriddedFieldOptions options_;
  AxisScale sx_, sy_, sz_;
  // Per grid cell, indexed by its lowest node (z, y, x): 1 when every corner the interpolation reads is water, so
  // sampling there needs no per-corner land test (most of the water, away from the coast).
  std::vector<std::uint8_t> all_wet_;
  // A steady single-level field's (u, v) side by side per node: one cache line holds both of a corner's values.
  std::vector<double> uv_;
};

}  // namespace polyfloe::forcing
