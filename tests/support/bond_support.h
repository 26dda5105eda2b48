// What the bond validations share (tests/validation/test_bonds.cpp, test_frozen_sheet.cpp): the sea ice of the
// paper's Tab. 1, a bond material, and a time step safely inside the bonds' critical one.
#pragma once

#include <limits>
#include <vector>

#include "bonds/bond_set.h"
#include "dynamics/world.h"

namespace polyfloe::tsupport::bond {

inline constexpr double kE = 1.0e9, kNu = 0.3, kRho = 920.0, kH = 1.0;  // [Pa], [-], [kg/m^3], [m]

// Tensile strength [Pa] as given, shear strength 1.5 MPa, damping ratio 0.7.
inline bonds::BondMaterial material(double tensile = 1.5e6) {
  bonds::BondMaterial m;
  m.youngs_modulus = kE;
  m.poisson_ratio = kNu;
  m.tensile_strength = tensile;
  m.shear_strength = 1.5e6;
  m.damping_ratio = 0.7;
  return m;
}

// Half the bonds' critical time step for the World's elements (fixed ones count as infinitely heavy) [s].
inline double safe_dt(const dynamics::World& w) {
  std::vector<double> mass, inertia;
  for (std::size_t i = 0; i < w.size(); ++i) {
    mass.push_back(w.motion(static_cast<int>(i)) == dynamics::Motion::dynamic ? w.mass(static_cast<int>(i))
                                                                             : std::numeric_limits<double>::infinity());
    inertia.push_back(w.inertia(static_cast<int>(i)));
  }
  return 0.5 * w.bonds()->critical_time_step(mass, inertia);
}

}  // namespace polyfloe::tsupport::bond
