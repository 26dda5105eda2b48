// A convex polyhedron's vertices placed in the world frame: rotation r, then translation x.
#pragma once

#include <vector>

#include "geometry/polyhedron.h"

namespace polyfloe::tsupport {

inline std::vector<geometry::Vec3> placed(const geometry::ConvexPolyhedron& s, const geometry::Mat3& r,
                                          const geometry::Vec3& x) {
  std::vector<geometry::Vec3> w;
  for (const auto& v : s.vertices()) w.push_back(r * v + x);
  return w;
}

}  // namespace polyfloe::tsupport
