// The run guard (run/guard.h).
#include "run/guard.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <type_traits>

namespace polyfloe::run {

namespace {

// One body's motion, as the guard searches the bodies for the one to name.
struct BodyMotion {
  bool finite = true;    // position, orientation, velocity and angular velocity
  bool dynamic = false;  // (kinematic bodies move as the scene prescribes)
  double speed = 0.0;    // |v| + |omega| x circumradius [m/s]
  double energy = 0.0;   // kinetic energy [J]
};

BodyMotion body_motion(const dynamics::World& w, int i) {
  const auto k = static_cast<std::size_t>(i);
  const geometry::Vec2 p = w.positions()[k], v = w.velocities()[k];
  const double om = w.angular_velocities()[k];
  BodyMotion m;
  m.finite = std::isfinite(p.x()) && std::isfinite(p.y()) && std::isfinite(v.x()) && std::isfinite(v.y()) &&
             std::isfinite(om) && std::isfinite(w.yaws()[k]);
  m.dynamic = w.motion(i) == dynamics::Motion::dynamic;
  if (!m.finite) return m;
  m.speed = v.norm() + std::abs(om) * w.shape(i).circumradius();
  m.energy = 0.5 * w.mass(i) * v.squaredNorm() + 0.5 * w.inertia(i) * om * om;
  return m;
}

BodyMotion body_motion(const dynamics::SpatialWorld& w, int i) {
  const dynamics::Vec3 v = w.velocity(i), om = w.angular_velocity(i);
  BodyMotion m;
  m.finite = w.position(i).allFinite() && w.orientation(i).coeffs().allFinite() && v.allFinite() && om.allFinite();
  m.dynamic = w.motion(i) == dynamics::Motion::dynamic;
  if (!m.finite) return m;
  const dynamics::Mat3 rot = w.orientation(i).toRotationMatrix();
  m.speed = v.norm() + om.norm() * w.shape(i).circumradius();
  m.energy = 0.5 * w.mass(i) * v.squaredNorm() + 0.5 * om.dot(rot * w.body_inertia(i) * rot.transpose() * om);
  return m;
}

template <class W>
void check_deepest_overlap(const W& w, const dynamics::DeepestOverlap& c, double dt) {
  if (c.ratio <= 1.0) return;
  std::ostringstream why;
  why << "bodies " << w.id(c.a) << " and " << w.id(c.b) << " overlap by " << c.depth << " m (more than "
      << (W::kOverlapLimit == 0.5 ? "half" : "a quarter of") << " the smaller body's equivalent radius, " << c.limit
      << " m) at t = " << w.time() << " s (step " << w.step_count() << "). The contact is too soft or the time step "
      << "too large for the impact speeds: set run.dt to " << 0.25 * dt
      << ", or raise run.reference_speed or run.steps_per_contact.";
  throw InstabilityError(why.str());
}

}  // namespace

template <class W>
void check_contact_resolution(const W& w, const dynamics::StepReport& report, double dt) {
  const dynamics::ContactResolution& r = report.shortest;
  if (r.a < 0 || r.duration >= dynamics::kMinStepsPerContact * dt) return;
  std::ostringstream why;
  why << "the contact between bodies " << w.id(r.a) << " and " << w.id(r.b) << " at t = " << w.time() << " s (step "
      << w.step_count() << ") has an impact speed of about " << r.impact_speed << " m/s, so it lasts " << r.duration
      << " s: only " << r.duration / dt << " time steps of dt = " << dt << " s (at least "
      << dynamics::kMinStepsPerContact << " are needed, 40 for accuracy). Set run.reference_speed to " << r.impact_speed
      << " (the automatic time step then resolves such impacts), or run.dt to " << r.duration / 40.0 << ".";
  throw InstabilityError(why.str());
}

namespace {

// What every runaway message ends with: when, and what to change.
template <class W>
std::string advice(const W& w, double dt) {
  std::ostringstream why;
  why << " at t = " << w.time() << " s (step " << w.step_count() << "). The time step dt = " << dt
      << " s is probably too large for the contact stiffness: set run.dt to " << 0.25 * dt
      << " or raise run.steps_per_contact (e.g. x4), or lower ice.youngs_modulus.";
  return why.str();
}

template <class W>
bool ghost(const W& w, int i) {
  if constexpr (std::is_same_v<W, dynamics::World>) return w.is_ghost(i);
  return false;
}

// The first body in id order (ghosts left out: their owners') with a non-finite state or a speed over the limit,
// named; empty where there is none.
template <class W>
std::string check_bodies(const W& w, double speed_limit, double dt) {
  for (const int i : w.id_order()) {
    if (ghost(w, i)) continue;
    const BodyMotion m = body_motion(w, i);
    std::ostringstream why;
    if (!m.finite)
      why << "body " << w.id(i) << " has a non-finite state (NaN or Inf)";
    else if (m.dynamic && m.speed > speed_limit)
      why << "body " << w.id(i) << " moves at " << m.speed << " m/s (limit " << speed_limit
          << " m/s = max(50, 20 x reference speed))";
    else
      continue;
    return why.str() + advice(w, dt);
  }
  return {};
}

// The kinetic energy of the dynamic bodies (ghosts left out) summed in id order [J], and the most energetic (the
// first in id order of equals; worst = -1 where there is none).
struct EnergyScan {
  double total = 0.0, worst = -1.0;
  int worst_body = -1;
};
template <class W>
EnergyScan scan_energy(const W& w) {
  EnergyScan e;
  for (const int i : w.id_order()) {
    if (ghost(w, i)) continue;
    const BodyMotion m = body_motion(w, i);
    if (!m.dynamic || !m.finite) continue;
    e.total += m.energy;
    if (m.energy > e.worst) {
      e.worst = m.energy;
      e.worst_body = i;
    }
  }
  return e;
}

template <class W>
std::string runaway_energy_message(const W& w, double energy, double limit, dynamics::BodyId worst, double worst_energy,
                                   double dt) {
  std::ostringstream why;
  why << "the kinetic energy of the ice, " << energy << " J, exceeds " << limit
      << " J (every floe at 10 x the reference speed; the most energetic is body " << worst << " with " << worst_energy
      << " J): runaway energy";
  return why.str() + advice(w, dt);
}

// The fastest a dynamic body may move [m/s]: max(50, 20 x the reference speed).
double runaway_speed_limit(double reference_speed) { return std::max(50.0, 20.0 * reference_speed); }

}  // namespace

double runaway_energy_limit(double mass, double reference_speed) {
  const double ref = std::max(1.0, reference_speed);
  return 0.5 * mass * 100.0 * ref * ref;
}

template <class W>
void check_stability(const W& w, const dynamics::StepReport& r, double dt, double reference_speed) {
  check_contact_resolution(w, r, dt);
  // Runaway: far faster than anything the forcing or the impacts can produce. (Not in space: bodies falling under
  // gravity gain speed that the scene's reference speed does not bound; there the overlap and the contact
  // resolution checks stop a step too large for the speeds reached.)
  double speed_limit = contact::kInfinite, energy_limit = contact::kInfinite;
  if constexpr (std::is_same_v<W, dynamics::World>) {
    speed_limit = runaway_speed_limit(reference_speed);
    energy_limit = runaway_energy_limit(w.dynamic_mass(), reference_speed);
  }
  // The report's summary of the step clears the bodies at once; only a state it cannot clear is searched body by
  // body below, for the body to name (and decides by itself).
  if (const dynamics::MotionSummary& s = r.motion;
      s.all_finite && std::sqrt(s.max_speed2) + s.max_spin_speed <= speed_limit && s.energy <= energy_limit) {
    check_deepest_overlap(w, r.deepest, dt);
    return;
  }
  if (std::string why = check_bodies(w, speed_limit, dt); !why.empty()) throw InstabilityError(why);
  // Runaway energy: the kinetic energy of the dynamic bodies beyond what they would have all moving at 10 x the
  // reference speed (an instability that grows in many bodies at once, before any one reaches the speed limit).
  if (const EnergyScan e = scan_energy(w); e.total > energy_limit)
    throw InstabilityError(
        runaway_energy_message(w, e.total, energy_limit, w.id(std::max(e.worst_body, 0)), std::max(e.worst, 0.0), dt));
  check_deepest_overlap(w, r.deepest, dt);
}

ShareCheck check_share(const dynamics::World& w, const dynamics::StepReport& r, double dt, double reference_speed) {
  ShareCheck c;
  c.energy = r.motion.energy;  // (the share's: the report leaves the ghosts to their owners)
  try {
    check_contact_resolution(w, r, dt);
    const dynamics::MotionSummary& s = r.motion;
    const double speed_limit = runaway_speed_limit(reference_speed);
    if (!s.all_finite || std::sqrt(s.max_speed2) + s.max_spin_speed > speed_limit)
      c.motion = check_bodies(w, speed_limit, dt);
  } catch (const InstabilityError& e) {
    c.motion = e.what();
  }
  try {
    check_deepest_overlap(w, r.deepest, dt);
  } catch (const InstabilityError& e) {
    c.overlap = e.what();
  }
  return c;
}

std::pair<double, dynamics::BodyId> most_energetic(const dynamics::World& w) {
  const EnergyScan e = scan_energy(w);
  return e.worst_body < 0 ? std::pair<double, dynamics::BodyId>{-1.0, 0} : std::pair{e.worst, w.id(e.worst_body)};
}

std::string runaway_energy(const dynamics::World& w, double energy, double limit, dynamics::BodyId worst,
                           double worst_energy, double dt) {
  return runaway_energy_message(w, energy, limit, worst, worst_energy, dt);
}

template void check_contact_resolution(const dynamics::World&, const dynamics::StepReport&, double);
template void check_contact_resolution(const dynamics::SpatialWorld&, const dynamics::StepReport&, double);
template void check_stability(const dynamics::World&, const dynamics::StepReport&, double, double);
template void check_stability(const dynamics::SpatialWorld&, const dynamics::StepReport&, double, double);

}  // namespace polyfloe::run
