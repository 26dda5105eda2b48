// The paper's cube-plate impact (Eq. 6-7, paper-notes 12), shared by the validation test and the benchmark driver:
// an l = 2 m cube (rho = 920 kg/m^3), turned by alpha about y, falls at v0 onto a fixed plate (no friction, no
// gravity). The first impact is simulated to its end; Eq. 6-7 give the rigid-impact answer.
#pragma once

#include <cmath>
#include <numbers>

#include "dynamics/spatial_world.h"

namespace polyfloe::test {

struct CubePlateResult {
  double v_ratio = 0.0;        // v'/v0, v' positive downwards (Eq. 7's convention)
  double w_ratio = 0.0;        // |w'| r / v0 [-]
  double spurious_w = 0.0;     // |w_x| + |w_z| after the impact, r / v0 [-]
  int manifold_points = 0;     // largest manifold seen during the impact
  int steps = 0;               // steps in contact
  bool second_impact = false;  // a second contact started before the first ended
};

struct CubePlateAnalytic {
  double v_ratio = 0.0, w_ratio = 0.0;
};

inline constexpr double kCubeEdge = 2.0;       // l [m]
inline constexpr double kCubeDensity = 920.0;  // [kg/m^3]

// Eq. 6-7 with I_yy = m l^2 / 6 and r = l / sqrt(2).
inline CubePlateAnalytic cube_plate_analytic(double alpha, double e) {
  const double l = kCubeEdge, r = l / std::sqrt(2.0);
  const double m = kCubeDensity * l * l * l;
  const double iyy = m * l * l / 6.0;
  const double c = std::cos(alpha + std::numbers::pi / 4.0);
  const double v0 = 1.0;
  const double w = m * v0 * (1.0 + e) * r * c / (iyy + m * r * r * c * c);
  return {(w * r * c - e * v0) / v0, w * r / v0};
}

struct CubePlateSetup {
  double alpha = 0.0;                // [rad]
  double v0 = 1.0;                   // [m/s]
  double youngs_modulus = 1.0e9;     // [Pa]
  double restitution = 0.5;          // [-]
  double steps_per_contact = 200.0;  // [-]
  contact::DampingModel damping = contact::DampingModel::speed_independent;
  dynamics::ContactPointModel contact_point = dynamics::ContactPointModel::witness;
  dynamics::SpatialNarrowPhase narrow_phase = dynamics::SpatialNarrowPhase::sat;
};

inline dynamics::SpatialWorld make_cube_plate(const CubePlateSetup& s) {
  dynamics::SpatialSettings ws;
  ws.contact.youngs_modulus = s.youngs_modulus;
  ws.contact.restitution = s.restitution;
  ws.contact.friction = 0.0;
  ws.contact.damping = s.damping;
  ws.contact.reference_speed = s.v0;  // where the paper damping model hits e
  ws.contact_point = s.contact_point;
  ws.narrow_phase = s.narrow_phase;
  dynamics::SpatialWorld w(ws);
  dynamics::SpatialBodyDesc plate;
  plate.id = 1;
  plate.shape = std::make_shared<geometry::ConvexPolyhedron>(geometry::ConvexPolyhedron::box({20.0, 20.0, 1.0}));
  plate.position = {0.0, 0.0, -0.5};  // top face at z = 0
  plate.motion = dynamics::Motion::fixed;
  w.add_body(plate);
  dynamics::SpatialBodyDesc cube;
  cube.id = 2;
  cube.shape =
      std::make_shared<geometry::ConvexPolyhedron>(geometry::ConvexPolyhedron::box({kCubeEdge, kCubeEdge, kCubeEdge}));
  cube.density = kCubeDensity;
  cube.orientation = dynamics::Quat(Eigen::AngleAxisd(s.alpha, geometry::Vec3::UnitY()));
  double low = 0.0;
  for (const auto& v : cube.shape->vertices()) low = std::min(low, (cube.orientation * v).z());
  cube.position = {0.0, 0.0, -low + 1e-3};  // the lowest edge 1 mm above the plate
  cube.velocity = {0.0, 0.0, -s.v0};
  w.add_body(cube);
  return w;
}

// Runs the first impact to its end (the contact list empty again) and reports the cube's velocities.
inline CubePlateResult run_cube_plate(const CubePlateSetup& s) {
  auto w = make_cube_plate(s);
  const double r = kCubeEdge / std::sqrt(2.0);
  const double t_c = w.shortest_contact_duration(s.v0);  // at the least effective mass of a corner impact
  const double dt = t_c / s.steps_per_contact;
  CubePlateResult out;
  bool touched = false;
  for (int k = 0; k < 10'000'000; ++k) {
    w.step(dt);
    const bool in_contact = !w.contacts().empty();
    if (in_contact) {
      touched = true;
      ++out.steps;
      out.manifold_points = std::max(out.manifold_points, w.contacts().front().manifold_points);
    } else if (touched) {
      break;
    }
  }
  const geometry::Vec3 v = w.velocity(1), om = w.angular_velocity(1);
  out.v_ratio = -v.z() / s.v0;
  out.w_ratio = std::abs(om.y()) * r / s.v0;
  out.spurious_w = (std::abs(om.x()) + std::abs(om.z())) * r / s.v0;
  return out;
}

}  // namespace polyfloe::test
