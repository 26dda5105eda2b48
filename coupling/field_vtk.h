// An ocean field for ParaView: a .pvd series of VTK rectilinear grids (.vtr), one per snapshot, with point data
// U [m/s] (3 components), speed [m/s] and mask (1 water, 0 land), to open beside a run's floes.pvd.
#pragma once

#include <filesystem>

#include "formats/field_file.h"

namespace polyfloe::coupling {

// Writes `pvd` (e.g. field.pvd) and its frames in a folder named after it (field/field_0000.vtr, ...); each file
// appears whole or not at all. Returns the number of frames.
std::size_t write_field_vtk(const std::filesystem::path& pvd, const io::FieldFile& f);

}  // namespace polyfloe::coupling
