// Ocean field files (HDF5): a velocity field on a rectilinear grid of snapshots, written by `polyfloe field
// import` (coupling/) and read by scenes with `forcing.ocean.field: {type: file}`. Layout (docs/scene-reference.md):
//
//   /            attributes format = "polyfloe-ocean-field", format_version = 1, source, created_by
//   /x /y /z     float64 [nx], [ny], [nz]: node coordinates [m], strictly increasing; z = height (<= 0 in water)
//   /t           float64 [nt]: snapshot times [s], strictly increasing
//   /U           float64 [nt, nz, ny, nx, 3]: velocity [m/s] (the DEM uses the horizontal components)
//   /mask        uint8 [nz, ny, nx]: 1 = water, 0 = land or outside the fluid mesh (U = 0 there)
#pragma once

#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>

#include "forcing/gridded_field.h"

namespace polyfloe::io {

// A file that is missing, not HDF5, not a field file, or whose arrays do not match: the message names the file
// and the problem ("field.h5: /U has shape [2, 3, 4, 5, 3], expected [nt, nz, ny, nx, 3] = [2, 3, 4, 6, 3]").
class FieldFileError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct FieldFileInfo {
  std::string source;      // what the field came from (an OpenFOAM case, a script)
  std::string created_by;  // the program and version that wrote it
};

// The grid with its vertical velocity (w, [m/s], same indexing as u; empty = zero), as written and read.
struct FieldFile {
  forcing::GridData grid;
  std::vector<double> w;
  FieldFileInfo info;
};

// Writes `f` to `path` atomically (a temporary file renamed into place); throws FieldFileError for a grid that
// grid_data_error() rejects or a w of the wrong size, and io errors as the HDF5 wrapper reports them.
void write_field_file(const std::filesystem::path& path, const FieldFile& f);
// Reads and checks a field file; throws FieldFileError naming `path` and the problem.
FieldFile read_field_file(const std::filesystem::path& path);

}  // namespace polyfloe::io
