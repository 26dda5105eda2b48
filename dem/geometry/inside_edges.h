// Whether a point lies inside every edge of a convex polygon by a margin: the narrow phase's check that a kept
// overlap topology still holds (docs/model.md, "Kept topologies"): some 15 % of a dense pack's step once
// vectorised, 29 % before. Vectorised over the edges; every variant gives the same answer, bit for bit.
#pragma once

#include <span>

#include "geometry/vec2.h"

namespace polyfloe::geometry {

// Which instructions inside_all_edges uses: two edges at a time (SSE2, every x86-64), four (AVX2), or the widest
// this processor has (`best`, the default; chosen once at start-up).
enum class EdgeSimd { sse2, avx2, best };

// Whether the processor (and the operating system) can run the AVX2 variant.
bool has_avx2();

// Whether v, relative to `origin`, lies inside every edge of the counter-clockwise polygon `poly` by more than
// `margin` [-] times the edge's length: perp_right(e) . (v - q0) < -margin |e|^2 for each edge from q0 to q1
// (poly[k - 1] to poly[k], both relative to `origin`; e = q1 - q0). Every variant does each edge's operations in
// this order, so all give the same answer; a NaN anywhere fails. `avx2` where has_avx2() is false runs `sse2`.
bool inside_all_edges(std::span<const Vec2> poly, const Vec2& origin, const Vec2& v, double margin,
                      EdgeSimd simd = EdgeSimd::best);

}  // namespace polyfloe::geometry
