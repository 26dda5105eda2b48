// The run guard: after every step, a state that is not finite, runs away, resolves a contact in too few steps or
// overlaps too deeply stops the run with a message that names the bodies, the time and what to change. One guard
// for both worlds: it reads the step's report (dynamics/step_report.h) and, only where the report does not clear
// the step, the bodies one by one for the one to name.
#pragma once

#include <stdexcept>

#include "dynamics/spatial_world.h"
#include "dynamics/step_report.h"
#include "dynamics/world.h"

namespace polyfloe::run {

// The run became unstable: the message names the body, the time and what to change.
class InstabilityError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Throws InstabilityError with a suggestion where the step reported by `r` (world.step()'s or world.report()) has
// a contact resolved by fewer than dynamics::kMinStepsPerContact steps (Hertz duration at the impact speed the
// contact implies), a non-finite body, a dynamic body faster than max(50, 20 x reference_speed), more kinetic
// energy than every dynamic body at 10 x max(1 m/s, reference_speed), or an overlap deeper than the world's limit
// (W::kOverlapLimit x the smaller equivalent radius of the pair). `dt` is the step in use [s], `reference_speed`
// the scene's impact speed [m/s]. W: dynamics::World or dynamics::SpatialWorld.
template <class W>
void check_stability(const W& world, const dynamics::StepReport& r, double dt, double reference_speed);
// Its first check alone (O(1)).
template <class W>
void check_contact_resolution(const W& world, const dynamics::StepReport& r, double dt);

}  // namespace polyfloe::run
