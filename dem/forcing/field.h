// Velocity fields of the ocean and the air, owned by dem/forcing. The step samples them where the drift kernels
// need them (side-face centres at half draft, bottom quadrature points at the draft, top points at the freeboard);
// analytic fields live in analytic_fields.h, OpenFOAM-derived ones in coupling/ behind the same interface.
#pragma once

#include <Eigen/Core>
#include <span>
#include <stdexcept>

#include "geometry/vec2.h"

namespace polyfloe::forcing {

using geometry::Vec2;
using Vec3 = Eigen::Vector3d;  // (x, y, z) [m]; z is height above the mean sea surface (negative in the water)

// A point or a time the field does not cover (outside its mesh, past its last snapshot with 'error' chosen).
class FieldError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

class VelocityField {
 public:
  virtual ~VelocityField() = default;
  // Horizontal velocity [m/s] at each of `points` at time t [s]; out.size() == points.size().
  // Throws FieldError where the field is not defined; never returns a non-finite value.
  virtual void sample(double t, std::span<const Vec3> points, std::span<Vec2> out) const = 0;
  // True when the velocity depends on time only: the step then samples it once for all floes.
  virtual bool uniform_in_space() const { return false; }

  Vec2 at(const Vec3& p, double t) const {
    Vec2 v;
    sample(t, {&p, 1}, {&v, 1});
    return v;
  }
};

// The ocean current (z <= 0) and the wind (z >= 0) share the interface; the names say which a setting expects.
using OceanField = VelocityField;
using WindField = VelocityField;

}  // namespace polyfloe::forcing
