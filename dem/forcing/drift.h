// Drift forcing of a floe (paper Eq. 9-14): form drag on the submerged side faces, the drag moment, skin drag on
// the bottom, air drag on the top, and Coriolis. The kernels are pure functions of one floe's geometry, motion and
// the fluid velocities sampled where they need them; the World's forcing stage calls them for every floe.
//
// Every kernel adds to a DriftLoad: a force, a torque, and the damping matrix D with which that load changes with
// the floe's velocity v = (u_x, u_y, omega): F(v) ~ F(v*) - D (v - v*). The integrator uses D to treat drag and
// Coriolis semi-implicitly (docs/model.md). D is the exact derivative for skin, air and moment drag (a Newton
// linearisation: freezing |w| instead makes large steps ring in a 2-cycle, the fixed-point map of two balancing
// quadratic drags having slope exactly -1); for form drag it is exact along the relative velocity and keeps the
// face's normal speed across it, which keeps D symmetric and positive semi-definite.
#pragma once

#include <Eigen/Core>
#include <memory>
#include <span>
#include <string_view>

#include "forcing/field.h"
#include "forcing/quadrature.h"
#include "geometry/vec2.h"

namespace polyfloe::forcing {

constexpr double kEarthRotationRate = 7.2921159e-5;  // sidereal rotation rate of the Earth [rad/s]
constexpr double kEarthRadius = 6.371e6;             // mean radius [m]

// How drag and Coriolis enter the time step.
enum class DriftTreatment {
  semi_implicit,  // linearised about the predicted velocity and solved with the final half kick (default)
  explicit_step,  // evaluated at the predicted velocity only (for comparison; unstable at large steps)
};
std::string_view to_string(DriftTreatment t);

struct DriftSettings {
  // Ocean (paper Eq. 10-13)
  double water_density = 1025.0;            // rho_w [kg/m^3]
  std::shared_ptr<const OceanField> ocean;  // current; null = still water
  bool form_drag = true;                    // Eq. 11 on the submerged side faces
  double form_drag_coefficient = 0.20;      // C_d^F [-]
  bool moment_drag = true;                  // Eq. 12 (with r_e^3, see docs/model.md)
  double moment_drag_coefficient = 0.14;    // C_d^M [-]
  bool skin_drag = true;                    // Eq. 13 on the bottom
  double skin_drag_coefficient = 0.0055;    // c_w [-]
  // Air (Eq. 14)
  double air_density = 1.2;               // rho_a [kg/m^3]
  std::shared_ptr<const WindField> wind;  // null = calm
  bool air_drag = true;
  double air_drag_coefficient = 0.0012;  // c_a [-]
  // Bottom and top integrals
  Quadrature quadrature = Quadrature::degree2;  // see docs/figures/drift_quadrature.png
  // Coriolis -m f k x u, f = 2 Omega sin(latitude) [+ beta (y - reference_y) on a beta plane]
  bool coriolis = false;
  double latitude = 75.0;    // [deg], [-90, 90]
  bool beta_plane = false;   // beta = 2 Omega cos(latitude) / R_earth
  double reference_y = 0.0;  // y where f = f0 [m]
  DriftTreatment treatment = DriftTreatment::semi_implicit;
  // The loads are evaluated in full every `update_every` steps [-]; between, each body's drift load comes from the
  // linear model of the last full evaluation, F_d(v) = b - D v (semi-implicit treatment only; 1 = every step).
  int update_every = 1;

  bool any() const { return form_drag || moment_drag || skin_drag || air_drag || coriolis; }
  // Every term off (contact-only tests and scenes).
  static DriftSettings none() {
    DriftSettings s;
    s.form_drag = s.moment_drag = s.skin_drag = s.air_drag = s.coriolis = false;
    return s;
  }
  // f [1/s] at y [m].
  double coriolis_parameter(double y) const;
};

// Force, torque and damping matrix accumulated over a floe's samples. Torque is about the floe's centre (z).
// The damping matrix D (for v = (u_x, u_y, omega)) is the derivative -dF/dv of the load: a symmetric positive
// semi-definite drag part plus the antisymmetric Coriolis part m f [[0, -1], [1, 0]] in the (u_x, u_y) block.
struct DriftLoad {
  Vec2 force{0.0, 0.0};  // [N]
  double torque = 0.0;   // [N m]
  // symmetric drag part [N s/m; N s; N m s]
  double dxx = 0.0, dxy = 0.0, dyy = 0.0, dxw = 0.0, dyw = 0.0, dww = 0.0;
  double mf = 0.0;  // Coriolis m f [kg/s]

  // A sample force f = -c w at lever r from the centre: w the sample's velocity relative to the fluid [m/s], c >= 0
  // its speed factor [N s/m] (k |w| for quadratic drag, k (w.n) for a face). The derivative added is the quadratic
  // drag's, df/dw = -c (I + w^ w^T), w^ = w inv_speed (inv_speed = 1/|w|, or 0 where w = 0).
  void add(double c, const Vec2& r, const Vec2& w, double inv_speed) {
    force -= c * w;
    torque -= c * geometry::cross(r, w);
    const Vec2 rp = geometry::perp_left(r);  // dw/domega
    const double ux = w.x() * inv_speed, uy = w.y() * inv_speed, ue = rp.dot(w) * inv_speed;
    dxx += c * (1.0 + ux * ux);
    dxy += c * ux * uy;
    dyy += c * (1.0 + uy * uy);
    dxw += c * (rp.x() + ux * ue);
    dyw += c * (rp.y() + uy * ue);
    dww += c * (r.squaredNorm() + ue * ue);
  }
  DriftLoad& operator+=(const DriftLoad& o) {
    force += o.force;
    torque += o.torque;
    dxx += o.dxx;
    dxy += o.dxy;
    dyy += o.dyy;
    dxw += o.dxw;
    dyw += o.dyw;
    dww += o.dww;
    mf += o.mf;
    return *this;
  }
  bool has_damping() const { return dxx != 0.0 || dyy != 0.0 || dww != 0.0 || mf != 0.0; }
  Eigen::Matrix3d damping() const {
    Eigen::Matrix3d d;
    d << dxx, dxy - mf, dxw, dxy + mf, dyy, dyw, dxw, dyw, dww;
    return d;
  }
  // D v [N, N, N m]
  Eigen::Vector3d damping_times(const Vec2& u, double w) const {
    return {dxx * u.x() + (dxy - mf) * u.y() + dxw * w, (dxy + mf) * u.x() + dyy * u.y() + dyw * w,
            dxw * u.x() + dyw * u.y() + dww * w};
  }
};

// The rigid motion of a floe: centre (centroid) [m], velocity [m/s], angular velocity [rad/s].
struct FloeMotion {
  Vec2 centre{0.0, 0.0};
  Vec2 velocity{0.0, 0.0};
  double omega = 0.0;
  Vec2 velocity_at(const Vec2& r) const { return velocity + omega * geometry::perp_left(r); }
};

// Where the side faces are sampled: each edge's midpoint at half the draft (the centre of the submerged face,
// the paper's point R). `out` has one entry per edge (edge i runs from vertex i to i+1).
void side_sample_points(std::span<const Vec2> vertices, double draft, std::span<Vec3> out);

// Form drag (Eq. 11) on the submerged side faces of a floe with world-frame counter-clockwise `vertices` and
// draft d [m], in water of density rho [kg/m^3] moving at water[i] at face i's centre. Face i (length L_i,
// outward normal n_i) sees w_i = u + omega k x r_i - water_i at its centre r_i and pushes only when it moves into
// the water (w_i . n_i > 0):  f_i = -1/2 C rho (L_i d) (w_i . n_i) w_i  - the drag of its area projected normal
// to the flow, so a convex floe in a uniform stream feels -1/2 C rho d W |w| w with W its width across the flow.
// The moment of each face force about the centre is included.
void add_form_drag(DriftLoad& load, double coefficient, double rho, double draft, const FloeMotion& m,
                   std::span<const Vec2> vertices, std::span<const Vec2> water);
// The same in water moving at `water` everywhere.
void add_form_drag(DriftLoad& load, double coefficient, double rho, double draft, const FloeMotion& m,
                   std::span<const Vec2> vertices, const Vec2& water);

// Rotation rate of the water around the floe: half its vorticity, from the circulation through the side-face
// samples, 1/(2A) sum_i water_i . (v_{i+1} - v_i) [rad/s]; exact for fields linear in x and y.
double water_rotation_rate(std::span<const Vec2> vertices, std::span<const Vec2> water, double area);

// Drag moment (Eq. 12, first term, made dimensionally consistent):
// M = -1/2 C rho A_sub r_e^3 |omega_rel| omega_rel, A_sub the submerged side area [m^2], r_e = sqrt(A/pi) [m],
// omega_rel = omega - water rotation rate [rad/s]. It is the moment of a drag stress 1/2 C rho (omega r_e)^2 on the
// side of a cylinder of radius r_e.
void add_moment_drag(DriftLoad& load, double coefficient, double rho, double submerged_side_area,
                     double equivalent_radius, double omega_rel);

// Quadrature samples of a floe's bottom or top, as arrays (structure of arrays: the kernel runs in SIMD).
struct SurfaceSamples {
  std::span<const double> rx, ry;  // world-frame lever of each sample from the floe's centre [m]
  std::span<const double> weight;  // area it carries [m^2]
};

// Quadratic surface drag (Eq. 13 on the bottom, Eq. 14 on the top): the stress -1/2 c rho |w| w with
// w = u + omega k x r - fluid(x) integrated by the quadrature samples; the fluid velocity at each sample [m/s].
void add_surface_drag(DriftLoad& load, double coefficient, double rho, const FloeMotion& m, const SurfaceSamples& q,
                      std::span<const double> fluid_x, std::span<const double> fluid_y);
// The same in a fluid moving at `fluid` everywhere.
void add_surface_drag(DriftLoad& load, double coefficient, double rho, const FloeMotion& m, const SurfaceSamples& q,
                      const Vec2& fluid);

// Coriolis force -m f k x u of a floe of mass m [kg] at velocity u [m/s], f [1/s].
void add_coriolis(DriftLoad& load, double mass, double f, const Vec2& u);

// Steady free drift under skin drag and air drag alone, uniform current u_c and wind u_a, no Coriolis:
// rho_a c_a |u_a - u| (u_a - u) = rho_w c_w |u - u_c| (u - u_c), so u = (u_c + k u_a) / (1 + k),
// k = sqrt(rho_a c_a / (rho_w c_w)) [m/s].
Vec2 free_drift_velocity(const DriftSettings& s, const Vec2& current, const Vec2& wind);

}  // namespace polyfloe::forcing
