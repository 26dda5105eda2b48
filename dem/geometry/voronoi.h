// Voronoi tessellation of a rectangle (Boost.Polygon's sweep-line Voronoi): the cell of each site clipped to the
// box, for level-ice sheets ([bonds]) and floe shapes ([fields]).
//
// Boost.Polygon works on integer coordinates: sites are snapped to a grid of (box size) / 2^28 (~4e-9 of the box;
// 4 um for a 1 km box). Cells are clipped to the box exactly by mirroring every site across the four sides: the
// Voronoi cell of an inside site in the mirrored set is its cell within the box, with no unbounded cells to cut.
#pragma once

#include <span>
#include <stdexcept>
#include <vector>

#include "geometry/vec2.h"

namespace polyfloe::geometry {

class VoronoiError : public std::invalid_argument {
 public:
  using std::invalid_argument::invalid_argument;
};

// The cell of each site (same order), counter-clockwise, within `box`. Sites must lie strictly inside the box and
// be distinct after snapping; throws VoronoiError naming the offending site otherwise.
std::vector<std::vector<Vec2>> voronoi_cells(std::span<const Vec2> sites, const Aabb& box);

}  // namespace polyfloe::geometry
