// VTK output of spatial scenes (io/vtk_writer.h, SpatialVtkSeriesWriter): every face of every polyhedron, and the
// contacts.
#include <vtkCellArray.h>
#include <vtkCellData.h>
#include <vtkDoubleArray.h>
#include <vtkIntArray.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkTypeUInt64Array.h>
#include <vtkUnsignedCharArray.h>

#include <system_error>
#include <vector>

#include "dynamics/spatial_world.h"
#include "formats/atomic_file.h"
#include "io/vtk_common.h"
#include "io/vtk_writer.h"

namespace polyfloe::io {

namespace fs = std::filesystem;
using namespace detail;

namespace {

vtkSmartPointer<vtkPolyData> spatial_bodies_polydata(const dynamics::SpatialWorld& world) {
  vtkIdType points = 0, cells = 0;
  for (int i = 0; i < static_cast<int>(world.size()); ++i) {
    points += static_cast<vtkIdType>(world.world_vertices(i).size());
    cells += static_cast<vtkIdType>(world.shape(i).faces().size());
  }
  vtkNew<vtkPoints> pts;
  pts->SetDataTypeToDouble();
  pts->SetNumberOfPoints(points);
  vtkNew<vtkCellArray> polys;
  auto id = make_array<vtkTypeUInt64Array>("id", 1, cells);
  auto motion = make_array<vtkUnsignedCharArray>("motion", 1, cells);
  auto vel = make_array<vtkDoubleArray>("velocity", 3, cells);
  auto speed = make_array<vtkDoubleArray>("speed", 1, cells);  // |velocity| [m/s], as the planar floes carry
  auto omega = make_array<vtkDoubleArray>("angular_velocity", 3, cells);
  vtkIdType p0 = 0, c = 0;
  std::vector<vtkIdType> loop;
  for (int i = 0; i < static_cast<int>(world.size()); ++i) {
    const auto w = world.world_vertices(i);
    for (std::size_t k = 0; k < w.size(); ++k) pts->SetPoint(p0 + static_cast<vtkIdType>(k), w[k].data());
    const geometry::Vec3 v = world.velocity(i), om = world.angular_velocity(i);
    for (const auto& f : world.shape(i).faces()) {
      loop.clear();
      for (int k : f.loop) loop.push_back(p0 + k);
      polys->InsertNextCell(static_cast<vtkIdType>(loop.size()), loop.data());
      id->SetValue(c, world.id(i));
      motion->SetValue(c, static_cast<unsigned char>(world.motion(i)));
      vel->SetTuple(c, v.data());
      speed->SetValue(c, v.norm());
      omega->SetTuple(c, om.data());
      ++c;
    }
    p0 += static_cast<vtkIdType>(w.size());
  }
  auto pd = vtkSmartPointer<vtkPolyData>::New();
  pd->SetPoints(pts);
  pd->SetPolys(polys);
  pd->GetCellData()->AddArray(id);
  pd->GetCellData()->AddArray(motion);
  pd->GetCellData()->AddArray(vel);
  pd->GetCellData()->AddArray(speed);
  pd->GetCellData()->AddArray(omega);
  add_time(pd, world.time(), world.step_count());
  return pd;
}

vtkSmartPointer<vtkPolyData> spatial_contacts_polydata(const dynamics::SpatialWorld& world) {
  const auto& cs = world.contacts();
  const auto n = static_cast<vtkIdType>(cs.size());
  vtkNew<vtkPoints> pts;
  pts->SetDataTypeToDouble();
  pts->SetNumberOfPoints(n);
  auto normal = make_array<vtkDoubleArray>("normal", 3, n);
  auto force = make_array<vtkDoubleArray>("force", 3, n);
  auto depth = make_array<vtkDoubleArray>("depth", 1, n);
  auto points = make_array<vtkIntArray>("manifold_points", 1, n);
  for (vtkIdType k = 0; k < n; ++k) {
    const auto& c = cs[static_cast<std::size_t>(k)];
    pts->SetPoint(k, c.point.data());
    normal->SetTuple(k, c.normal.data());
    force->SetTuple(k, c.force.data());
    depth->SetValue(k, c.depth);
    points->SetValue(k, c.manifold_points);
  }
  auto pd = vtkSmartPointer<vtkPolyData>::New();
  pd->SetPoints(pts);
  vtkNew<vtkCellArray> verts;
  verts->SetData(iota(n + 1), iota(n));
  pd->SetVerts(verts);
  pd->GetPointData()->AddArray(normal);
  pd->GetPointData()->AddArray(force);
  pd->GetPointData()->AddArray(depth);
  pd->GetPointData()->AddArray(points);
  add_time(pd, world.time(), world.step_count());
  return pd;
}

}  // namespace

SpatialVtkSeriesWriter::SpatialVtkSeriesWriter(const fs::path& dir, bool write_contacts, OutputManifest* manifest)
    : dir_(dir),
      write_contacts_(write_contacts),
      manifest_(manifest),
      bodies_pvd_(dir / "bodies.pvd", manifest),
      contacts_pvd_(dir / "contacts.pvd", manifest) {
  std::error_code ec;
  bodies_pvd_.record("bodies/");
  fs::create_directories(dir / "bodies", ec);
  if (!ec && write_contacts_) {
    contacts_pvd_.record("contacts/");
    fs::create_directories(dir / "contacts", ec);
  }
  if (ec) throw IoError("cannot create VTK output folders in " + dir.string() + ": " + ec.message());
}

void SpatialVtkSeriesWriter::write_frame(const dynamics::SpatialWorld& world) {
  const std::string bodies_file = "bodies/" + frame_name("bodies", frames_);
  bodies_pvd_.record(bodies_file);
  write_polydata(spatial_bodies_polydata(world), dir_ / bodies_file);
  std::string contacts_file;
  if (write_contacts_) {
    contacts_file = "contacts/" + frame_name("contacts", frames_);
    contacts_pvd_.record(contacts_file);
    write_polydata(spatial_contacts_polydata(world), dir_ / contacts_file);
  }
  bodies_pvd_.add(world.time(), bodies_file);
  if (write_contacts_) contacts_pvd_.add(world.time(), contacts_file);
  ++frames_;
}

void SpatialVtkSeriesWriter::resume(std::span<const double> frame_times) {
  const int frames = static_cast<int>(frame_times.size());
  // The collections first, then the frames they no longer list (VtkSeriesWriter::resume).
  bodies_pvd_.resume(frame_times, "bodies", ".vtp");
  if (write_contacts_) contacts_pvd_.resume(frame_times, "contacts", ".vtp");
  remove_frames_from(dir_, "bodies", ".vtp", frames, manifest_);
  remove_frames_from(dir_, "contacts", ".vtp", frames, manifest_);
  frames_ = frames;
}

}  // namespace polyfloe::io
