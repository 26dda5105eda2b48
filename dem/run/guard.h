// The run guard: after every step, a state that is not finite, runs away, resolves a contact in too few steps or
// overlaps too deeply stops the run with a message that names the bodies, the time and what to change. One guard
// for both worlds: it reads the step's report (dynamics/step_report.h) and, only where the report does not clear
// the step, the bodies one by one for the one to name.
#pragma once

#include <stdexcept>
#include <string>
#include <utility>

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

// The same checks where `world` holds a share of a planar ice (an MPI rank's World: its ghosts are their owners'),
// kept apart so that the ranks reach the verdict one process would. One process checks, in this order: the
// contact resolution and each body (`motion`: the first failing check's message, else empty), the ice's kinetic
// energy (the share's own, `energy` [J], summed over the ranks against runaway_energy_limit() of the whole ice's
// dynamic mass, then named by runaway_energy()), the deepest overlap (`overlap`). Throws nothing.
struct ShareCheck {
  std::string motion, overlap;
  double energy = 0.0;  // kinetic energy of the share's dynamic bodies, translation + rotation [J]
};
ShareCheck check_share(const dynamics::World& world, const dynamics::StepReport& r, double dt, double reference_speed);
// The most kinetic energy a planar ice of dynamic mass `mass` [kg] may hold [J]: every dynamic body at 10 x
// max(1 m/s, reference_speed).
double runaway_energy_limit(double mass, double reference_speed);
// The share's most energetic dynamic body (ghosts left out; the lowest id of equals): its kinetic energy [J] and
// id; {-1, 0} where the share has none.
std::pair<double, dynamics::BodyId> most_energetic(const dynamics::World& world);
// The message of a runaway energy: the ice holds `energy` [J] over `limit` [J], its most energetic body `worst`
// (`worst_energy` [J]); at world's time and step, with what to change for the step `dt` [s].
std::string runaway_energy(const dynamics::World& world, double energy, double limit, dynamics::BodyId worst,
                           double worst_energy, double dt);

}  // namespace polyfloe::run
