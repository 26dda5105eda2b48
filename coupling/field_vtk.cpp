#include "field_vtk.h"

#include <vtkDataSetAttributes.h>
#include <vtkDoubleArray.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkRectilinearGrid.h>
#include <vtkUnsignedCharArray.h>
#include <vtkXMLRectilinearGridWriter.h>

#include <cmath>
#include <cstdio>
#include <sstream>

#include "formats/atomic_file.h"

namespace polyfloe::coupling {

namespace fs = std::filesystem;

namespace {

vtkNew<vtkDoubleArray> axis(const std::vector<double>& a) {
  vtkNew<vtkDoubleArray> v;
  v->SetNumberOfTuples(static_cast<vtkIdType>(a.size()));
  for (std::size_t i = 0; i < a.size(); ++i) v->SetValue(static_cast<vtkIdType>(i), a[i]);
  return v;
}

}  // namespace

std::size_t write_field_vtk(const fs::path& pvd, const io::FieldFile& f) {
  const forcing::GridData& g = f.grid;
  const fs::path folder = pvd.parent_path() / pvd.stem();
  fs::create_directories(folder);
  const std::size_t per = g.nodes_per_snapshot();
  std::ostringstream index;
  index << "<?xml version=\"1.0\"?>\n<VTKFile type=\"Collection\" version=\"0.1\" byte_order=\"LittleEndian\">\n"
        << "  <Collection>\n";
  for (std::size_t it = 0; it < g.t.size(); ++it) {
    vtkNew<vtkRectilinearGrid> grid;
    grid->SetDimensions(static_cast<int>(g.x.size()), static_cast<int>(g.y.size()), static_cast<int>(g.z.size()));
    grid->SetXCoordinates(axis(g.x));
    grid->SetYCoordinates(axis(g.y));
    grid->SetZCoordinates(axis(g.z));
    vtkNew<vtkDoubleArray> u, speed;
    vtkNew<vtkUnsignedCharArray> mask, ghost;
    u->SetName("U");
    u->SetNumberOfComponents(3);
    u->SetNumberOfTuples(static_cast<vtkIdType>(per));
    speed->SetName("speed");
    speed->SetNumberOfTuples(static_cast<vtkIdType>(per));
    mask->SetName("mask");
    mask->SetNumberOfTuples(static_cast<vtkIdType>(per));
    // Land is blanked (VTK's ghost array: ParaView hides cells with a hidden point), not shown as still water.
    ghost->SetName(vtkDataSetAttributes::GhostArrayName());
    ghost->SetNumberOfTuples(static_cast<vtkIdType>(per));
    // VTK's point order (x fastest, then y, then z) is the file's node order within a snapshot.
    for (std::size_t k = 0; k < per; ++k) {
      const std::size_t n = it * per + k;
      const double w = f.w.empty() ? 0.0 : f.w[n];
      const double uvw[3] = {g.u[n], g.v[n], w};
      u->SetTuple(static_cast<vtkIdType>(k), uvw);
      speed->SetValue(static_cast<vtkIdType>(k), std::hypot(g.u[n], g.v[n]));
      mask->SetValue(static_cast<vtkIdType>(k), g.wet[k]);
      ghost->SetValue(static_cast<vtkIdType>(k), g.wet[k] ? 0 : vtkDataSetAttributes::HIDDENPOINT);
    }
    grid->GetPointData()->AddArray(u);
    grid->GetPointData()->AddArray(speed);
    grid->GetPointData()->AddArray(mask);
    grid->GetPointData()->AddArray(ghost);
    grid->GetPointData()->SetActiveScalars("speed");
    char name[64];
    std::snprintf(name, sizeof name, "%s_%04zu.vtr", pvd.stem().c_str(), it);
    const fs::path target = folder / name;
    const fs::path tmp = io::temporary_sibling(target);
    vtkNew<vtkXMLRectilinearGridWriter> writer;
    writer->SetFileName(tmp.c_str());
    writer->SetInputData(grid);
    writer->SetDataModeToBinary();
    if (writer->Write() != 1) {
      std::error_code ec;
      fs::remove(tmp, ec);
      throw io::IoError(target.string() + ": VTK could not write it");
    }
    io::commit_file_atomic(tmp, target);
    index << "    <DataSet timestep=\"" << g.t[it] << "\" group=\"\" part=\"0\" file=\"" << (pvd.stem() / name).string()
          << "\"/>\n";
  }
  index << "  </Collection>\n</VTKFile>\n";
  io::write_file_atomic(pvd, index.str());
  return g.t.size();
}

}  // namespace polyfloe::coupling
