// What the bond validations share (tests/validation/test_bonds.cpp, test_frozen_sheet.cpp): the sea ice of the
// paper's Tab. 1, a bond material, a time step safely inside the bonds' critical one, and the loaded strips'
// mean displacement.
#pragma once

#include <algorithm>
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
    mass.push_back(w.motion(static_cast<int>(i)) == dynamics::Motion::dynamic
                       ? w.mass(static_cast<int>(i))
                       : std::numeric_limits<double>::infinity());
    inertia.push_back(w.inertia(static_cast<int>(i)));
  }
  return 0.5 * w.bonds()->critical_time_step(mass, inertia);
}

// Mean displacement of the `loaded` elements under a total load ramped to `load` [N] over `ramp` seconds (shared
// equally among them), then held for `hold` seconds; averaged over the last quarter of the hold [m]. Steps at
// safe_dt.
inline geometry::Vec2 mean_displacement_under_load(dynamics::World& w, const std::vector<int>& loaded,
                                                   geometry::Vec2 load, double ramp, double hold) {
  const double dt = safe_dt(w);
  const std::vector<geometry::Vec2> x0(w.positions().begin(), w.positions().end());
  geometry::Vec2 sum{0, 0};
  double n = 0;
  while (w.time() < ramp + hold) {
    const double f = std::min(1.0, w.time() / ramp);
    for (int e : loaded) w.set_external_load(e, f * load / static_cast<double>(loaded.size()), 0.0);
    w.step(dt);
    if (w.time() > ramp + 0.75 * hold) {
      for (int e : loaded) sum += w.positions()[static_cast<std::size_t>(e)] - x0[static_cast<std::size_t>(e)];
      n += static_cast<double>(loaded.size());
    }
  }
  return sum / n;
}

}  // namespace polyfloe::tsupport::bond
