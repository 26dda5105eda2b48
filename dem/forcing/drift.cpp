#include "forcing/drift.h"

#include <cmath>
#include <numbers>

namespace polyfloe::forcing {

std::string_view to_string(DriftTreatment t) {
  return t == DriftTreatment::semi_implicit ? "semi_implicit" : "explicit";
}

double DriftSettings::coriolis_parameter(double y) const {
  const double phi = latitude * std::numbers::pi / 180.0;
  double f = 2.0 * kEarthRotationRate * std::sin(phi);
  if (beta_plane) f += 2.0 * kEarthRotationRate * std::cos(phi) / kEarthRadius * (y - reference_y);
  return f;
}

void side_sample_points(std::span<const Vec2> v, double draft, std::span<Vec3> out) {
  const std::size_t n = v.size();
  for (std::size_t i = 0; i < n; ++i) {
    const Vec2 mid = 0.5 * (v[i] + v[i + 1 == n ? 0 : i + 1]);
    out[i] = {mid.x(), mid.y(), -0.5 * draft};
  }
}

namespace {

// The fluid at sample i: from a span of samples, or one value for all.
struct Sampled {
  std::span<const Vec2> v;
  const Vec2& operator[](std::size_t i) const { return v[i]; }
};
struct Uniform {
  const Vec2& v;
  const Vec2& operator[](std::size_t) const { return v; }
};

template <class Fluid>
void form_drag(DriftLoad& load, double coefficient, double rho, double draft, const FloeMotion& m,
               std::span<const Vec2> v, const Fluid& water) {
  const double k = 0.5 * coefficient * rho * draft;  // [kg/m^2]
  const std::size_t n = v.size();
  DriftLoad acc;  // local: the compiler keeps it in registers (load may alias the inputs)
  for (std::size_t i = 0; i < n; ++i) {
    const Vec2& a = v[i];
    const Vec2& b = v[i + 1 == n ? 0 : i + 1];
    const Vec2 r = 0.5 * (a + b) - m.centre;
    const Vec2 w = m.velocity_at(r) - water[i];
    // (w . n) L with n L = perp_right(b - a): the face's normal velocity times its length [m^2/s].
    const double wn_len = w.dot(geometry::perp_right(b - a));
    if (wn_len > 0.0) acc.add(k * wn_len, r, w);
  }
  load += acc;
}

template <class Fluid>
void surface_drag(DriftLoad& load, double coefficient, double rho, const FloeMotion& m, std::span<const Vec2> levers,
                  std::span<const double> weights, const Fluid& fluid) {
  const double k = 0.5 * coefficient * rho;  // [kg/m^3]
  DriftLoad acc;
  for (std::size_t q = 0; q < levers.size(); ++q) {
    const Vec2 w = m.velocity_at(levers[q]) - fluid[q];
    acc.add(k * weights[q] * w.norm(), levers[q], w);
  }
  load += acc;
}

}  // namespace

void add_form_drag(DriftLoad& load, double coefficient, double rho, double draft, const FloeMotion& m,
                   std::span<const Vec2> v, std::span<const Vec2> water) {
  form_drag(load, coefficient, rho, draft, m, v, Sampled{water});
}

void add_form_drag(DriftLoad& load, double coefficient, double rho, double draft, const FloeMotion& m,
                   std::span<const Vec2> v, const Vec2& water) {
  form_drag(load, coefficient, rho, draft, m, v, Uniform{water});
}

double water_rotation_rate(std::span<const Vec2> v, std::span<const Vec2> water, double area) {
  const std::size_t n = v.size();
  double circulation = 0.0;  // [m^2/s]
  for (std::size_t i = 0; i < n; ++i) circulation += water[i].dot(v[i + 1 == n ? 0 : i + 1] - v[i]);
  return circulation / (2.0 * area);
}

void add_moment_drag(DriftLoad& load, double coefficient, double rho, double submerged_side_area,
                     double equivalent_radius, double omega_rel) {
  const double r3 = equivalent_radius * equivalent_radius * equivalent_radius;
  const double c = 0.5 * coefficient * rho * submerged_side_area * r3 * std::abs(omega_rel);  // [N m s]
  load.torque -= c * omega_rel;
  load.crr += c;
}

void add_surface_drag(DriftLoad& load, double coefficient, double rho, const FloeMotion& m,
                      std::span<const Vec2> levers, std::span<const double> weights, std::span<const Vec2> fluid) {
  surface_drag(load, coefficient, rho, m, levers, weights, Sampled{fluid});
}

void add_surface_drag(DriftLoad& load, double coefficient, double rho, const FloeMotion& m,
                      std::span<const Vec2> levers, std::span<const double> weights, const Vec2& fluid) {
  surface_drag(load, coefficient, rho, m, levers, weights, Uniform{fluid});
}

void add_coriolis(DriftLoad& load, double mass, double f, const Vec2& u) {
  const double mf = mass * f;  // [kg/s]
  load.force -= mf * geometry::perp_left(u);  // -m f k x u = -C u with C = m f [[0, -1], [1, 0]]
  load.mf += mf;
}

Vec2 free_drift_velocity(const DriftSettings& s, const Vec2& current, const Vec2& wind) {
  if (s.skin_drag && s.air_drag) {
    // Equal and opposite drags: u - u_c and u_a - u are parallel with |u - u_c| = k |u_a - u|.
    const double k = std::sqrt(s.air_density * s.air_drag_coefficient / (s.water_density * s.skin_drag_coefficient));
    return (current + k * wind) / (1.0 + k);
  }
  if (s.air_drag && !(s.form_drag || s.moment_drag)) return wind;
  return current;
}

}  // namespace polyfloe::forcing
