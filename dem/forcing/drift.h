// Drift forcing of a floe (paper Eq. 9-14): form drag on the submerged side faces, the drag moment, skin drag on
// the bottom, air drag on the top, and Coriolis. The kernels are pure functions of one floe's geometry, motion and
// the fluid velocities sampled where they need them; the World's forcing stage calls them for every floe.
//
// Every kernel adds to a DriftLoad: a force, a torque, and the damping matrix D with which that load changes with
// the floe's velocity v = (u_x, u_y, omega) when each sample's speed factor (|w|, or w.n for a face) is held fixed:
// F(v) ~ F(v*) - D (v - v*). The integrator uses D to treat drag and Coriolis semi-implicitly (docs/model.md).
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
constexpr double kEarthRadius = 6.371e6;              // mean radius [m]

// How drag and Coriolis enter the time step.
enum class DriftTreatment {
  semi_implicit,  // linearised about the predicted velocity and solved with the final half kick (default)
  explicit_step,  // evaluated at the predicted velocity only (for comparison; unstable at large steps)
};
std::string_view to_string(DriftTreatment t);

struct DriftSettings {
  // Ocean (paper Eq. 10-13)
  double water_density = 1025.0;           // rho_w [kg/m^3]
  std::shared_ptr<const OceanField> ocean; // current; null = still water
  bool form_drag = true;                   // Eq. 11 on the submerged side faces
  double form_drag_coefficient = 0.20;     // C_d^F [-]
  bool moment_drag = true;                 // Eq. 12 (with r_e^3, see docs/model.md)
  double moment_drag_coefficient = 0.14;   // C_d^M [-]
  bool skin_drag = true;                   // Eq. 13 on the bottom
  double skin_drag_coefficient = 0.0055;   // c_w [-]
  // Air (Eq. 14)
  double air_density = 1.2;                // rho_a [kg/m^3]
  std::shared_ptr<const WindField> wind;   // null = calm
  bool air_drag = true;
  double air_drag_coefficient = 0.0012;    // c_a [-]
  // Bottom and top integrals
  Quadrature quadrature = Quadrature::degree1;
  // Coriolis -m f k x u, f = 2 Omega sin(latitude) [+ beta (y - reference_y) on a beta plane]
  bool coriolis = false;
  double latitude = 75.0;                  // [deg], [-90, 90]
  bool beta_plane = false;                 // beta = 2 Omega cos(latitude) / R_earth
  double reference_y = 0.0;                // y where f = f0 [m]
  DriftTreatment treatment = DriftTreatment::semi_implicit;

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
// The damping matrix for v = (u_x, u_y, omega) has the structure every kernel here produces:
//   D = [[c, -mf, cx], [mf, c, cy], [cx, cy, crr]]
// (drag: symmetric, positive semi-definite; Coriolis: the antisymmetric m f part).
struct DriftLoad {
  Vec2 force{0.0, 0.0};  // [N]
  double torque = 0.0;   // [N m]
  double c = 0.0;        // sum of sample coefficients [N s/m]
  double cx = 0.0, cy = 0.0;  // sum of c (k x r) [N s]
  double crr = 0.0;      // sum of c |r|^2, plus the drag moment's [N m s]
  double mf = 0.0;       // Coriolis m f [kg/s]

  // A sample force -c w at lever r from the centre, c >= 0 [N s/m] with its speed factor frozen, w the sample's
  // velocity relative to the fluid [m/s].
  void add(double ci, const Vec2& r, const Vec2& w) {
    force -= ci * w;
    torque -= ci * geometry::cross(r, w);
    c += ci;
    cx -= ci * r.y();  // (k x r).x = -r.y
    cy += ci * r.x();
    crr += ci * r.squaredNorm();
  }
  DriftLoad& operator+=(const DriftLoad& o) {
    force += o.force;
    torque += o.torque;
    c += o.c;
    cx += o.cx;
    cy += o.cy;
    crr += o.crr;
    mf += o.mf;
    return *this;
  }
  bool has_damping() const { return c != 0.0 || crr != 0.0 || mf != 0.0; }
  Eigen::Matrix3d damping() const {
    Eigen::Matrix3d d;
    d << c, -mf, cx, mf, c, cy, cx, cy, crr;
    return d;
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

// Quadratic surface drag (Eq. 13 on the bottom, Eq. 14 on the top): the stress -1/2 c rho |w| w with
// w = u + omega k x r - fluid(x) integrated by the quadrature points: levers r[q] from the centre [m], weights
// [m^2], fluid[q] [m/s].
void add_surface_drag(DriftLoad& load, double coefficient, double rho, const FloeMotion& m,
                      std::span<const Vec2> levers, std::span<const double> weights, std::span<const Vec2> fluid);
// The same in a fluid moving at `fluid` everywhere.
void add_surface_drag(DriftLoad& load, double coefficient, double rho, const FloeMotion& m,
                      std::span<const Vec2> levers, std::span<const double> weights, const Vec2& fluid);

// Coriolis force -m f k x u of a floe of mass m [kg] at velocity u [m/s], f [1/s].
void add_coriolis(DriftLoad& load, double mass, double f, const Vec2& u);

// Steady free drift under skin drag and air drag alone, uniform current u_c and wind u_a, no Coriolis:
// rho_a c_a |u_a - u| (u_a - u) = rho_w c_w |u - u_c| (u - u_c), so u = (u_c + k u_a) / (1 + k),
// k = sqrt(rho_a c_a / (rho_w c_w)) [m/s].
Vec2 free_drift_velocity(const DriftSettings& s, const Vec2& current, const Vec2& wind);

}  // namespace polyfloe::forcing
