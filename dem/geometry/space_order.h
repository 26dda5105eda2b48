// The order of space the step works in: cells of a given size anchored at the origin, numbered tile by tile
// (kSpaceTile x kSpaceTile cells per tile; row-major inside a tile and between tiles), as the grid broad phase
// numbers and scans its cells. The World sorts its bodies' slots by it every step, and a generated floe field is
// added to the World in it, so that bodies near each other in the ice are near each other in memory.
#pragma once

#include <cmath>
#include <cstdint>

#include "geometry/vec2.h"

namespace polyfloe::geometry {

constexpr int kSpaceTileBits = 4;

// The cell of the space order for bodies of a given mean equivalent radius [m]: 4 radii.
inline double space_order_cell(double mean_radius) { return 4.0 * mean_radius; }
constexpr int kSpaceTile = 1 << kSpaceTileBits;  // cells per tile side

// The key of a position on cells of `cell` [m]; a non-finite or far-out position (beyond 2^31 cells) sorts last.
inline std::uint64_t space_key(const Vec2& p, double cell) {
  const double inv = 1.0 / cell;
  const double x = std::floor(p.x() * inv), y = std::floor(p.y() * inv);
  constexpr double lim = 2147483647.0;
  if (!(std::abs(x) < lim) || !(std::abs(y) < lim)) return ~std::uint64_t{0};
  const auto ux = static_cast<std::uint64_t>(static_cast<std::int64_t>(x) + 2147483648LL);  // < 2^32
  const auto uy = static_cast<std::uint64_t>(static_cast<std::int64_t>(y) + 2147483648LL);
  constexpr std::uint64_t in_tile = kSpaceTile - 1;
  return ((uy >> kSpaceTileBits) << (32 + kSpaceTileBits)) | ((ux >> kSpaceTileBits) << (2 * kSpaceTileBits)) |
         ((uy & in_tile) << kSpaceTileBits) | (ux & in_tile);
}

}  // namespace polyfloe::geometry
