// The paper's contact method brought into the plane: GJK to decide overlap, then EPA for the penetration depth and
// normal, on two convex polygons (level floes). Kept for comparison with the exact planar method
// (narrow_phase_planar.h), which measures the overlap polygon itself; selected per scene with
// `contact.narrow_phase: gjk_epa`.
//
// Depth and normal are those of the minimum translation that separates the polygons (the Minkowski difference's
// closest boundary point to the origin); the contact point is the midpoint of the two witness points (the deepest
// point of each polygon inside the other along the normal). Iterations are bounded; a query that hits the bound or
// meets a degenerate simplex is reported as failed, never as a number.
//
// Details: GJK and EPA run on D = A - B (the normal is the outward normal of D's edge nearest the origin). The
// witnesses are taken on A's deepest feature along +normal and B's along -normal (a vertex or a face each), at the
// middle of the range where the two features face each other: for a vertex against a face the point lies opposite
// the vertex, for parallel faces at the middle of their common part. EPA stops when the nearest edge moves out by
// no more than tolerance x size (size: the larger side of the pair's bounding box), so the depth is low by at most
// that. A depth within round-off of the coordinates (64 eps x the largest |coordinate|) counts as touching.
#pragma once

#include <span>

#include "geometry/vec2.h"

namespace polyfloe::contact {

using geometry::Vec2;

struct Gjk2dSettings {
  int max_gjk_iterations = 64;   // [-]
  int max_epa_iterations = 128;  // [-]
  double tolerance = 1e-9;       // EPA convergence, relative to the pair's size [-]
};

enum class Gjk2dStatus { separated, contact, failed };

struct Gjk2dContact {
  Gjk2dStatus status = Gjk2dStatus::separated;
  double depth = 0.0;       // [m]
  Vec2 normal{1.0, 0.0};    // unit, from A to B
  Vec2 point{0.0, 0.0};     // [m]
  int iterations = 0;       // GJK + EPA iterations used [-]
  const char* reason = "";  // why it failed (static string)
};

// `a`, `b`: world-frame vertices, counter-clockwise, convex. Touching (zero depth) counts as separated.
Gjk2dContact gjk_epa_2d(std::span<const Vec2> a, std::span<const Vec2> b, const Gjk2dSettings& settings = {});

}  // namespace polyfloe::contact
