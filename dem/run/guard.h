// The run guard: after every step, a state that is not finite, runs away, or resolves a contact in too few steps
// stops the run with a message that names the bodies, the time and what to change.
#pragma once

#include <stdexcept>

#include "dynamics/spatial_world.h"
#include "dynamics/world.h"

namespace polyfloe::run {

// The run became unstable: the message names the body, the time and what to change.
class InstabilityError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Checks the state for NaN/Inf and runaway motion; throws InstabilityError with a suggestion. `dt` is the step in
// use, `reference_speed` the scene's impact speed [m/s].
void check_stability(const dynamics::World& world, double dt, double reference_speed);
// The O(1) part, run every step: the shortest contact in progress must last at least dynamics::kMinStepsPerContact
// (10) steps (Hertz duration at
// the impact speed the contact implies).
void check_contact_resolution(const dynamics::World& world, double dt);

// Non-finite state, a contact resolved by fewer than dynamics::kMinStepsPerContact steps, or an overlap deeper than
// a quarter of the smaller body's equivalent radius: throws InstabilityError naming the bodies, the time and the
// step to use.
void check_stability(const dynamics::SpatialWorld& world, double dt);

}  // namespace polyfloe::run
