// The elastic-foundation contact potential of two overlapping convex polygons A and B (docs/model.md §3):
//
//   W = kappa * I,   I = ∫_P (d_A + d_B) dA        [m^3],  P = A ∩ B,
//
// d_A(x) the distance from x to A's boundary (for x in A: min over A's edges of the distance to the edge's line),
// d_B likewise. Across a contact d_A + d_B is the local thickness of the overlap, so I is the Winkler energy
// ∫ thickness^2 ds of the overlap without a chosen direction. I is continuously differentiable in both bodies'
// positions and rotations through every change of the overlap's shape (a corner entering or leaving, an edge
// turning parallel, one polygon wholly inside the other); its exact gradient is a line load on the overlap's
// boundary:
//
//   dI/dt = ∫_{∂P∩∂B} d_A (u_B - u_A)·ν ds - ∫_{∂P∩∂A} d_B (u_B - u_A)·ν ds,
//
// ν the outward normal of P, u_A, u_B the rigid velocity fields of the bodies. The force on B is the resultant of
// that load with its sign changed, the force on A its opposite (momentum and angular momentum are kept exactly).
// Round contacts (effective radius R, overlap thickness δ) give I = 16/15 sqrt(2R) δ^2.5, so kappa = E*/(2 sqrt 2)
// gives the Hertz force 4/3 E* sqrt(R) δ^1.5; a flat face pressed on a face gives I = L δ^2 (length L) and with it
// a restoring tilt stiffness.
#pragma once

#include <span>

#include "contact/narrow_phase_planar.h"
#include "geometry/vec2.h"

namespace polyfloe::contact::detail {

using geometry::Vec2;

struct FoundationTerms {
  double energy = 0.0;   // I [m^3]
  Vec2 force{0.0, 0.0};  // -dI/dx_B: the force on B per unit kappa [m^2]
  double moment = 0.0;   // its moment about `g` (the torque on B about g per unit kappa) [m^3]
  double extent = 0.0;   // the overlap's extent along the force [m]
  double breadth = 0.0;  // and across it [m]
};

// `p[0..n)`: the overlap polygon relative to `origin`, counter-clockwise; `edge[k]` says which edge the polygon's
// edge p[k] -> p[k+1] lies on: A's edge edge[k] (a[i] -> a[i+1]) when < na, else B's edge edge[k] - na
// (b[j-1] -> b[j]). `g`: P's centroid relative to `origin` (moments are taken about it), `area` its area [m^2].
// `lines_a`, `lines_b`: the
// polygons' edge lines (EdgeLines), or null to compute them here.
FoundationTerms foundation_terms(std::span<const Vec2> a, std::span<const Vec2> b, const EdgeLines* lines_a,
                                 const EdgeLines* lines_b, const Vec2& origin, const Vec2* p, const int* edge, int n,
                                 const Vec2& g, double area);

}  // namespace polyfloe::contact::detail
