// Level-ice sheets: a rectangle tiled by the Voronoi cells of uniform random sites (Boost.Polygon through
// geometry/voronoi.h), optionally made more even by Lloyd's relaxation (each iteration moves every site to its
// cell's centroid). The cells share their edges exactly (the same Voronoi vertices), so the sheet has no gap and no
// overlap; they are the elements that [bonds] freezes together.
//
//   cell count  n = round(region area / (pi cell_size^2 / 4)), at least 1
//   sites       uniform in the region (std::mt19937_64 with the portable mapping of scene/floe_field.h)
#pragma once

#include <vector>

#include "dynamics/body.h"
#include "scene/scene.h"

namespace polyfloe::scene {

// World-frame counter-clockwise cells tiling the region, in site order. Throws SceneError (prefixed with
// spec.source) for a bad spec or more than IceSheetSpec::kMaxCells cells.
std::vector<std::vector<Vec2>> voronoi_sheet(const IceSheetSpec& spec);

// The sheet's elements: its cells, or with elements = triangles each cell fanned from its centroid into triangles
// (triangle j of a cell: centroid, corner j, corner j + 1), and every edge two elements share (matched by its
// bit-identical end points), with the elements on either side.
struct SheetFace {
  int a = 0, b = 0;  // element indices, a < b
  Vec2 p0, p1;       // ends of the shared edge [m]
};
// Two elements that share only a corner, with the faces that meet at that corner (indices into faces).
struct SheetCorner {
  int a = 0, b = 0;
  std::vector<int> faces;
};
struct SheetElementsOut {
  std::vector<std::vector<Vec2>> polygons;  // world frame, counter-clockwise [m]
  std::vector<SheetFace> faces;
  std::vector<SheetCorner> corners;
};
SheetElementsOut ice_sheet_elements(const IceSheetSpec& spec);

// The sheet's elements as dynamic bodies of `density` [kg/m^3], ids first_id, first_id + 1, ... (in the order of
// ice_sheet_elements().polygons).
std::vector<dynamics::BodyDesc> ice_sheet_bodies(const IceSheetSpec& spec, double density, dynamics::BodyId first_id);

}  // namespace polyfloe::scene
