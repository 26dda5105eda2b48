#include "forcing/drift.h"

#include <Eigen/Core>
#include <algorithm>
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
    // A face in the lee (w.n <= 0) feels nothing (its terms would all be zeros, which change no bit of the sums;
    // a NaN goes on into them). The faces facing the flow are one run of the outline, so the branch turns twice.
    if (wn_len <= 0.0) continue;
    // f = -k L d (w.n) w: along w its derivative is 2 k L d (w.n), across it k L d (w.n).
    const double speed = w.norm();
    acc.add(k * wn_len, r, w, speed > 0.0 ? 1.0 / speed : 0.0);
  }
  load += acc;
}

// Surface drag, one sample at a time (few samples: the centroid rule).
template <class Fluid>
void surface_drag(DriftLoad& load, double k, const FloeMotion& m, const SurfaceSamples& q, const Fluid& fx,
                  const Fluid& fy) {
  const std::size_t n = q.rx.size();
  DriftLoad acc;  // local: kept in registers (load may alias the inputs)
  for (std::size_t i = 0; i < n; ++i) {
    const double rx = q.rx[i], ry = q.ry[i];
    const Vec2 w{m.velocity.x() - m.omega * ry - fx[i], m.velocity.y() + m.omega * rx - fy[i]};
    const double speed = w.norm();
    const double kw = k * q.weight[i];
    acc.add(kw * speed, {rx, ry}, w, speed > 0.0 ? 1.0 / speed : 0.0);
  }
  load += acc;
}

struct Scalar {
  double v;
  double operator[](std::size_t) const { return v; }
};

// The same over up to kChunk samples at a time in Eigen arrays (SIMD sqrt, division and reductions): faster from
// a few samples on.
constexpr Eigen::Index kChunk = 64;
using Chunk = Eigen::Array<double, Eigen::Dynamic, 1, Eigen::ColMajor, kChunk, 1>;
using ConstMap = Eigen::Map<const Eigen::ArrayXd>;

template <class FluidX, class FluidY>
void surface_drag_chunk(DriftLoad& acc, double k, const FloeMotion& m, const ConstMap& rx, const ConstMap& ry,
                        const ConstMap& weight, const FluidX& fx, const FluidY& fy) {
  const Chunk wx = m.velocity.x() - m.omega * ry - fx;  // w = u + omega k x r - fluid
  const Chunk wy = m.velocity.y() + m.omega * rx - fy;
  const Chunk speed = (wx.square() + wy.square()).sqrt();
  const Chunk kw = k * weight;
  const Chunk c = kw * speed;  // [N s/m]
  // w / |w| (0 where w = 0; no division by zero is evaluated)
  const Chunk inv = (speed > 0.0).select(1.0 / speed.max(1e-300), Chunk::Zero(speed.size()));
  const Chunk e = rx * wy - ry * wx;  // (k x r) . w
  // Lazy expressions (evaluated inside each sum: cheaper than storing them)
  const auto ux = wx * inv;
  const auto uy = wy * inv;
  const auto ue = e * inv;
  acc.force -= Vec2((c * wx).sum(), (c * wy).sum());
  acc.torque -= (c * e).sum();
  acc.dxx += (c * (1.0 + ux.square())).sum();
  acc.dxy += (c * ux * uy).sum();
  acc.dyy += (c * (1.0 + uy.square())).sum();
  acc.dxw += (c * (ux * ue - ry)).sum();
  acc.dyw += (c * (uy * ue + rx)).sum();
  acc.dww += (c * (rx.square() + ry.square() + ue.square())).sum();
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
  load.dww += 2.0 * c;  // d(|x| x)/dx = 2 |x|
}

void add_surface_drag(DriftLoad& load, double coefficient, double rho, const FloeMotion& m, const SurfaceSamples& q,
                      std::span<const double> fluid_x, std::span<const double> fluid_y) {
  const double k = 0.5 * coefficient * rho;  // [kg/m^3]
  const Eigen::Index n = static_cast<Eigen::Index>(q.rx.size());
  if (n < 4) return surface_drag(load, k, m, q, fluid_x, fluid_y);
  for (Eigen::Index i = 0; i < n; i += kChunk) {
    const Eigen::Index len = std::min(kChunk, n - i);
    surface_drag_chunk(load, k, m, ConstMap(q.rx.data() + i, len), ConstMap(q.ry.data() + i, len),
                       ConstMap(q.weight.data() + i, len), ConstMap(fluid_x.data() + i, len),
                       ConstMap(fluid_y.data() + i, len));
  }
}

void add_surface_drag(DriftLoad& load, double coefficient, double rho, const FloeMotion& m, const SurfaceSamples& q,
                      const Vec2& fluid) {
  const double k = 0.5 * coefficient * rho;
  const Eigen::Index n = static_cast<Eigen::Index>(q.rx.size());
  if (n < 4) return surface_drag(load, k, m, q, Scalar{fluid.x()}, Scalar{fluid.y()});
  for (Eigen::Index i = 0; i < n; i += kChunk) {
    const Eigen::Index len = std::min(kChunk, n - i);
    surface_drag_chunk(load, k, m, ConstMap(q.rx.data() + i, len), ConstMap(q.ry.data() + i, len),
                       ConstMap(q.weight.data() + i, len), fluid.x(), fluid.y());
  }
}

void add_coriolis(DriftLoad& load, double mass, double f, const Vec2& u) {
  const double mf = mass * f;                 // [kg/s]
  load.force -= mf * geometry::perp_left(u);  // -m f k x u = -C u with C = m f [[0, -1], [1, 0]]
  load.mf += mf;
}

Vec2 free_drift_velocity(const DriftSettings& s, const Vec2& current, const Vec2& wind) {
  if (s.skin_drag && s.air_drag) {
    // Equal and opposite drags: u - u_c and u_a - u are parallel with |u - u_c| = k |u_a - u|.
    const double k = std::sqrt(s.air_density * s.air_drag_coefficient / (s.water_density * s.skin_drag_coefficient));
    return (current + k * wind) / (1.0 + k);
  }
  if (s.air_drag && !s.form_drag) return wind;  // (the drag moment does not resist translation)
  return current;
}

}  // namespace polyfloe::forcing
