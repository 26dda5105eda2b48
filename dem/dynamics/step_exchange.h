// What a World's step exchanges with the Worlds beside it when the ice is cut among them (a domain decomposition:
// domain/). Each World owns some bodies and holds ghosts, copies of the bodies others own that can touch its own
// (World::set_ghost). Three times in a step (and in compute_forces) the World hands itself to its exchange, which
// reads what this World's owned bodies give the others and writes what theirs give this one. Without an exchange
// (a World alone, the default) none of this happens and nothing of it costs.
#pragma once

namespace polyfloe::dynamics {

class World;

class StepExchange {
 public:
  virtual ~StepExchange() = default;
  // After the move (and before compute_forces' evaluation): every ghost's pose from its owner, through
  // World::set_ghost_pose; the owned bodies' poses (World::positions, yaws) are final for the step here.
  virtual void poses(World& w) = 0;
  // After the velocity prediction: every ghost's predicted velocity (World::set_ghost_prediction) from its
  // owner's World::predicted_velocity and predicted_omega.
  virtual void predictions(World& w) = 0;
  // After the contact pairs were evaluated: this World's World::outgoing_pair_forces to the owners of their
  // higher-id bodies, and theirs for this World's bodies into World::take_pair_forces.
  virtual void pair_forces(World& w) = 0;
};

}  // namespace polyfloe::dynamics
