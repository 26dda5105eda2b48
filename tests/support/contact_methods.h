// Every contact method of the code behind one call, for the failure map (tests/bench/bench_failure_map.cpp) and the
// failure-mode test (tests/unit/test_contact_failure_modes.cpp): the planar methods get the polygons, the 3-D ones
// the prisms; each answer is put in one form.
#pragma once

#include <algorithm>
#include <cmath>
#include <span>
#include <vector>

#include "contact/narrow_phase_ccd.h"
#include "contact/narrow_phase_gjk2d.h"
#include "contact/narrow_phase_planar.h"
#include "contact/narrow_phase_sat3d.h"
#include "geometry/polyhedron.h"
#include "statistics.h"

namespace polyfloe::tsupport {

enum ContactMethod { kPlanar, kGjk2d, kCcdEpa, kCcdTie, kCcdMpr, kSat, kContactMethods };
inline bool is_planar_method(int m) { return m == kPlanar || m == kGjk2d; }

enum class MethodStatus { separated, contact, failed };

struct MethodResult {
  MethodStatus status = MethodStatus::separated;
  double depth = 0.0;                    // [m]
  geometry::Vec3 normal{0.0, 0.0, 0.0};  // unit, A to B (z = 0 for the planar methods)
  geometry::Vec3 point{0.0, 0.0, 0.0};   // [m]
  const char* reason = "";               // why it failed (static string)
};

// One pair as every method needs it: world polygons, and the prisms (shapes, world vertices, centroids).
struct MethodInput {
  std::span<const geometry::Vec2> a, b;
  std::span<const geometry::Vec3> a3, b3;
  const geometry::ConvexPolyhedron* sa = nullptr;
  const geometry::ConvexPolyhedron* sb = nullptr;
  geometry::Vec3 ca{0.0, 0.0, 0.0}, cb{0.0, 0.0, 0.0};
};

inline MethodResult run_contact_method(int m, const MethodInput& p) {
  MethodResult r;
  auto status = [](bool contact, bool failed) {
    return contact ? MethodStatus::contact : failed ? MethodStatus::failed : MethodStatus::separated;
  };
  auto in_plane = [](const geometry::Vec2& v) { return geometry::Vec3(v.x(), v.y(), 0.0); };
  switch (m) {
    case kPlanar: {
      contact::PlanarContact c;
      if (contact::planar_overlap(p.a, p.b, c))
        r = {MethodStatus::contact, c.depth, in_plane(c.normal), in_plane(c.point)};
      break;
    }
    case kGjk2d: {
      const contact::Gjk2dContact c = contact::gjk_epa_2d(p.a, p.b);
      r = {status(c.status == contact::Gjk2dStatus::contact, c.status == contact::Gjk2dStatus::failed), c.depth,
           in_plane(c.normal), in_plane(c.point), c.reason};
      break;
    }
    case kCcdEpa:
    case kCcdTie:
    case kCcdMpr: {
      const auto method = m == kCcdEpa   ? contact::CcdMethod::gjk_epa
                          : m == kCcdTie ? contact::CcdMethod::gjk_epa_tiebreak
                                         : contact::CcdMethod::mpr;
      const contact::CcdContact c = contact::ccd_penetration(p.a3, p.b3, method);
      r = {status(c.status == contact::CcdStatus::contact, c.status == contact::CcdStatus::failed), c.depth, c.normal,
           c.point, c.reason};
      break;
    }
    default: {
      const geometry::Mat3 id = geometry::Mat3::Identity();
      const contact::SatContact c = contact::sat_penetration(*p.sa, id, p.a3, p.ca, *p.sb, id, p.b3, p.cb);
      if (c.hit) r = {MethodStatus::contact, c.depth, c.normal, c.point};
    }
  }
  return r;
}

}  // namespace polyfloe::tsupport
