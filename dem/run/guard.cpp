// The run guard (run/guard.h).
#include "run/guard.h"

#include <algorithm>
#include <cmath>
#include <sstream>

namespace polyfloe::run {

void check_contact_resolution(const dynamics::World& w, double dt) {
  std::ostringstream why;
  const dynamics::World::ContactResolution r = w.shortest_active_contact();
  if (r.a >= 0 && r.duration < dynamics::kMinStepsPerContact * dt) {
    why << "the contact between bodies " << w.id(r.a) << " and " << w.id(r.b) << " at t = " << w.time() << " s (step "
        << w.step_count() << ") has an impact speed of about " << r.impact_speed << " m/s, so it lasts " << r.duration
        << " s: only " << r.duration / dt << " time steps of dt = " << dt << " s (at least "
        << dynamics::kMinStepsPerContact << " are needed, 40 for accuracy). Set run.reference_speed to "
        << r.impact_speed << " (the automatic time step then resolves such impacts), or run.dt to " << r.duration / 40.0
        << ".";
    throw InstabilityError(why.str());
  }
}

namespace {

void check_deepest_overlap(const dynamics::World& w, double dt) {
  // The deepest overlap against half the smaller floe's radius (tracked by the World in its contact sum).
  if (const dynamics::World::DeepestOverlap& c = w.deepest_overlap(); c.ratio > 1.0) {
    std::ostringstream why;
    why << "bodies " << w.id(c.a) << " and " << w.id(c.b) << " overlap by " << c.depth
        << " m (more than half the smaller floe's radius, " << c.limit << " m) at t = " << w.time() << " s (step "
        << w.step_count() << "). The contact is too soft or the time step too large for the impact speeds: set "
        << "run.dt to " << 0.25 * dt << ", or raise run.reference_speed or run.steps_per_contact.";
    throw InstabilityError(why.str());
  }
}

}  // namespace

void check_stability(const dynamics::World& w, double dt, double reference_speed) {
  check_contact_resolution(w, dt);
  // Runaway: far faster than anything the forcing or the impacts can produce.
  const double speed_limit = std::max(50.0, 20.0 * reference_speed);
  const double energy_limit =
      0.5 * w.dynamic_mass() * 100.0 * std::max(1.0, reference_speed) * std::max(1.0, reference_speed);
  // The World's summary of the step (gathered in its final kick) clears the bodies at once; only a state it
  // cannot clear is searched body by body below, for the body to name (and decides by itself).
  if (const dynamics::World::MotionSummary& s = w.motion_summary();
      s.all_finite && std::sqrt(s.max_speed2) + s.max_spin_speed <= speed_limit && s.energy <= energy_limit) {
    check_deepest_overlap(w, dt);
    return;
  }
  const auto pos = w.positions();
  const auto vel = w.velocities();
  const auto om = w.angular_velocities();
  std::ostringstream why;
  auto advice = [&] {
    why << " at t = " << w.time() << " s (step " << w.step_count() << "). The time step dt = " << dt
        << " s is probably too large for the contact stiffness: set run.dt to " << 0.25 * dt
        << " or raise run.steps_per_contact (e.g. x4), or lower ice.youngs_modulus.";
    throw InstabilityError(why.str());
  };
  // Runaway energy: the kinetic energy of the dynamic bodies beyond what they would have all moving at 10 x the
  // reference speed (an instability that grows in many bodies at once, before any one reaches the speed limit).
  double energy = 0.0, worst = 0.0;
  std::size_t worst_body = 0;
  for (std::size_t i = 0; i < w.size(); ++i) {
    const int b = static_cast<int>(i);
    const bool dynamic = w.motion(b) == dynamics::Motion::dynamic;
    const bool finite = std::isfinite(pos[i].x()) && std::isfinite(pos[i].y()) && std::isfinite(vel[i].x()) &&
                        std::isfinite(vel[i].y()) && std::isfinite(om[i]) && std::isfinite(w.yaws()[i]);
    const double speed = finite ? vel[i].norm() + std::abs(om[i]) * w.shape(b).circumradius() : 0.0;
    if (!finite) {
      why << "body " << w.id(b) << " has a non-finite state (NaN or Inf)";
    } else if (dynamic && speed > speed_limit) {  // kinematic bodies move as the scene prescribes
      why << "body " << w.id(b) << " moves at " << speed << " m/s (limit " << speed_limit
          << " m/s = max(50, 20 x reference speed))";
    } else {
      if (dynamic) {
        const double e = 0.5 * w.mass(b) * vel[i].squaredNorm() + 0.5 * w.inertia(b) * om[i] * om[i];
        energy += e;
        if (e > worst) {
          worst = e;
          worst_body = i;
        }
      }
      continue;
    }
    advice();
  }
  if (energy > energy_limit) {
    why << "the kinetic energy of the ice, " << energy << " J, exceeds " << energy_limit
        << " J (every floe at 10 x the reference speed; the most energetic is body "
        << w.id(static_cast<int>(worst_body)) << " with " << worst << " J): runaway energy";
    advice();
  }
  check_deepest_overlap(w, dt);
}

void check_stability(const dynamics::SpatialWorld& w, double dt) {
  for (int i = 0; i < static_cast<int>(w.size()); ++i) {
    if (!w.position(i).allFinite() || !w.velocity(i).allFinite() || !w.angular_velocity(i).allFinite()) {
      std::ostringstream m;
      m << "body " << w.id(i) << " has a non-finite position or velocity at t = " << w.time() << " s (dt = " << dt
        << " s); lower run.dt or raise run.steps_per_contact";
      throw InstabilityError(m.str());
    }
  }
  for (const auto& c : w.contacts()) {
    if (c.duration < dynamics::kMinStepsPerContact * dt) {
      std::ostringstream m;
      m << "the contact of bodies " << w.id(c.a) << " and " << w.id(c.b) << " at t = " << w.time() << " s lasts about "
        << c.duration << " s, fewer than " << dynamics::kMinStepsPerContact << " steps of dt = " << dt
        << " s: lower run.dt to " << c.duration / 40.0
        << " s or less, or raise run.reference_speed (the automatic step divides the contact duration at that speed)";
      throw InstabilityError(m.str());
    }
    const double r = std::min(w.shape(c.a).equivalent_radius(), w.shape(c.b).equivalent_radius());
    if (c.depth > 0.25 * r) {
      std::ostringstream m;
      m << "bodies " << w.id(c.a) << " and " << w.id(c.b) << " overlap by " << c.depth << " m at t = " << w.time()
        << " s, more than a quarter of the smaller body's radius (" << r << " m): the step dt = " << dt
        << " s does not resolve the contact; try run.dt = " << dt / 4 << " s or a larger run.steps_per_contact"
        << " (or a larger run.reference_speed when bodies speed up under gravity)";
      throw InstabilityError(m.str());
    }
  }
}

}  // namespace polyfloe::run
