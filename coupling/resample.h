// Resampling a case's snapshots onto the rectilinear grid of an ocean field file (dem/io/field_file.h).
#pragma once

#include <Eigen/Core>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "formats/field_file.h"
#include "openfoam_case.h"

namespace polyfloe::coupling {

struct GridSpec {
  std::optional<Eigen::Vector4d> bounds;         // x0, y0, x1, y1 [m]; default: the mesh's horizontal bounds
  double cell = 0.0;                             // node spacing in x and y [m], > 0; 0 = the mesh's finest cell
  std::vector<double> z{-2.0, -1.0, -0.5, 0.0};  // levels [m], heights relative to the water surface (<= 0 in the
                                                 // water), spanning floe drafts; each must lie in the mesh
  std::optional<double> surface;                 // the water surface's z in the case [m]; default: the mesh's top
  double max_nodes = 5e7;                        // x * y * z * times nodes allowed [-] (memory, file size)
};

// Empty when `g` is usable, else what is wrong ("cell must be > 0 m").
std::string grid_spec_error(const GridSpec& g);

// U of every snapshot at every node. Nodes outside the mesh are land (mask 0, U = 0). Level L is sampled at
// z = surface + L in the case and stored as L (the field file's z is a height relative to the water surface); a
// level outside the mesh's depth is an error (never clamped), except in a 2-D case (one cell through the depth),
// whose velocity is the same at every depth: one level is kept, as when every level holds the same velocity. A single
// snapshot of a steady case gets t = 0. Throws CouplingError for an
// unusable spec or no snapshot.
// `progress`, when given, is told the fraction of the nodes sampled so far, after every row of nodes.
io::FieldFile resample(const std::vector<MeshSnapshot>& snapshots, const GridSpec& spec, bool steady,
                       const std::string& source, const std::function<void(double)>& progress = {});

}  // namespace polyfloe::coupling
