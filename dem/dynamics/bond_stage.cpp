// Stage: bond forces between frozen elements, and their failure (bonds/bond_set.h).
#include <chrono>
#include <limits>

#include "dynamics/world.h"

namespace polyfloe::dynamics {

void World::set_bonds(bonds::BondSet bonds) {
  bonds_.emplace(std::move(bonds));
  bond_mass_.resize(size());
  for (std::size_t i = 0; i < size(); ++i)
    bond_mass_[i] = bodies_.is_dynamic[i] ? bodies_.mass[i] : std::numeric_limits<double>::infinity();
  forces_ready_ = false;
}

void World::bond_forces(double t) {
  const auto t0 = std::chrono::steady_clock::now();
  if (bond_mass_.size() != size()) set_bonds(std::move(*bonds_));  // bodies added after the bonds
  const bonds::ElementState s{bodies_.pos, bodies_.yaw, bodies_.vel_eval, bodies_.omega_eval, bond_mass_};
  bonds_failed_last_ = bonds_->apply(s, bodies_.force, bodies_.torque, t);
  profile_.bonds += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

}  // namespace polyfloe::dynamics
