// What one step of a world reports about itself: the bodies' motion, the deepest overlap and the shortest contact
// in progress. Both worlds return one from step() (and give it again from report()); the run guard (run/guard.h)
// reads nothing else of the step.
#pragma once

#include <algorithm>

#include "contact/contact_law.h"

namespace polyfloe::dynamics {

// The bodies' motion at the end of a step.
struct MotionSummary {
  bool all_finite = true;       // every body's position, orientation, velocity and angular velocity
  double max_speed2 = 0.0;      // the largest |v|^2 of a dynamic body [m^2/s^2]
  double max_spin_speed = 0.0;  // the largest |omega| x circumradius of a dynamic body [m/s]
  double energy = 0.0;          // kinetic energy of the dynamic bodies, translation + rotation [J]
  void merge(const MotionSummary& o) {
    all_finite &= o.all_finite;
    max_speed2 = std::max(max_speed2, o.max_speed2);
    max_spin_speed = std::max(max_spin_speed, o.max_spin_speed);
    energy += o.energy;
  }
};

// The contact whose depth is the largest fraction of its world's overlap limit (a fraction of the smaller
// equivalent radius of its two bodies: World::kOverlapLimit, SpatialWorld::kOverlapLimit); the run guard stops a
// run where that fraction exceeds 1. Ratio 0 and a = b = -1 when there is no contact.
struct DeepestOverlap {
  double ratio = 0.0;  // depth / limit [-]
  double depth = 0.0;  // [m]
  double limit = 0.0;  // the overlap limit of the pair [m]
  int a = -1, b = -1;  // body indices
  // Takes the contact (a, b) of `depth` against `limit` where it is deeper in proportion (the first of equals).
  void consider(double d, double lim, int ia, int ib) {
    const double r = d / lim;
    if (r > ratio) *this = {r, d, lim, ia, ib};
  }
};

// The shortest Hertz contact duration implied by the contacts in progress: each contact's impact speed is
// estimated from its approach rate and its stored elastic energy, v^2 = d_dot^2 + (4/5) k_n d^2.5 / m*. A step
// that does not resolve it (t_c < dynamics::kMinStepsPerContact dt) is unstable.
struct ContactResolution {
  double duration = contact::kInfinite;  // [s]
  double impact_speed = 0.0;             // [m/s]
  int a = -1, b = -1;                    // body indices of that contact
};

struct StepReport {
  MotionSummary motion;
  DeepestOverlap deepest;
  ContactResolution shortest;
};

}  // namespace polyfloe::dynamics
