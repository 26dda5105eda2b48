// Resampling a case's snapshots onto the rectilinear grid of an ocean field file (dem/io/field_file.h).
#pragma once

#include <Eigen/Core>
#include <optional>
#include <string>
#include <vector>

#include "io/field_file.h"
#include "openfoam_case.h"

namespace polyfloe::coupling {

struct GridSpec {
  std::optional<Eigen::Vector4d> bounds;    // x0, y0, x1, y1 [m]; default: the mesh's horizontal bounds
  double cell = 0.0;                         // node spacing in x and y [m], > 0; 0 = the mesh's finest cell
  std::vector<double> z{-2.0, -1.0, -0.5, 0.0};  // levels [m] spanning floe drafts; clamped into the mesh
};

// Empty when `g` is usable, else what is wrong ("cell must be > 0 m").
std::string grid_spec_error(const GridSpec& g);

// U of every snapshot at every node. Nodes outside the mesh are land (mask 0, U = 0). Levels are clamped into the
// mesh's z range and made unique; when every level holds the same velocity at every node (a 2-D case: one cell
// through the depth) one level is kept. A single snapshot of a steady case gets t = 0. Throws CouplingError for an
// unusable spec or no snapshot.
io::FieldFile resample(const std::vector<MeshSnapshot>& snapshots, const GridSpec& spec, bool steady,
                       const std::string& source);

}  // namespace polyfloe::coupling
