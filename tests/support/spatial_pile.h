// A spatial scene with hundreds of bodies in contact, for the tests of the spatial driver (threads, restart): 17 x 17
// boxes (0.8 x 0.8 x 0.4 m, each tilted by 1-5 degrees about its own axis, 5 cm apart) thrown at 1 m/s onto a fixed
// plate under gravity, sliding sideways into each other at up to 0.5 m/s and spinning; friction 0.3, the manifold
// contact point. About 200 contacts once every box has landed (t = 0.15 s), 300 by t = 0.3 s; 290 bodies,
// so the move and the pairs run on every thread (the kicks stay on one: too little work).
#pragma once

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace polyfloe::tsupport {

inline constexpr int kPileSide = 17;

// The scene's text (its name: spatial_pile).
inline std::string spatial_pile_yaml() {
  std::ostringstream out;
  out << "name: spatial_pile\n"
         "run: {duration: 0.4, reference_speed: 2, steps_per_contact: 20}\n"
         "output: {interval: 0.02}\n"
         "contact: {friction: 0.3, restitution: 0.5}\n"
         "spatial:\n"
         "  gravity: [0, 0, -9.81]\n"
         "  contact_point: manifold\n"
         "  bodies:\n"
         "    - {box: [40, 40, 1], position: [0, 0, -0.5], motion: fixed}\n";
  const double mid = (kPileSide - 1) / 2.0;
  for (int i = 0; i < kPileSide; ++i) {
    for (int j = 0; j < kPileSide; ++j) {
      char line[400];
      std::snprintf(line, sizeof line,
                    "    - {box: [0.8, 0.8, 0.4], position: [%.4f, %.4f, 0.26], rotation: {axis: [1, %.1f, 0.3], "
                    "angle_deg: %d}, velocity: [%.3f, %.3f, -1], angular_velocity: [0.5, -0.3, %.1f]}\n",
                    (i - mid) * 0.85, (j - mid) * 0.85, 0.5 * ((i + j) % 3), 1 + (i * 7 + j * 3) % 5,
                    0.5 * std::sin(i * 1.3 + j), 0.5 * std::cos(i + j * 0.7), 0.2 * ((i - j + 3 * kPileSide) % 3));
      out << line;
    }
  }
  return out.str();
}

// Writes the scene to `file` and returns its path as a string.
inline std::string write_spatial_pile(const std::filesystem::path& file) {
  std::ofstream(file) << spatial_pile_yaml();
  return file.string();
}

}  // namespace polyfloe::tsupport
