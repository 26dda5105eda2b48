// The VTK writers of a planar World: floes, bonds and contacts per frame (VtkSeriesWriter) and image grids
// (VtkImageSeriesWriter); their shared pieces and the .pvd collection are in vtk_common.cpp.
#include "io/vtk_writer.h"

#include "formats/output_manifest.h"

#include <vtkCellArray.h>
#include <vtkLine.h>
#include <vtkCellData.h>
#include <vtkDoubleArray.h>
#include <vtkFloatArray.h>
#include <vtkIdTypeArray.h>
#include <vtkImageData.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkSmartPointer.h>
#include <vtkTypeInt32Array.h>
#include <vtkTypeUInt64Array.h>
#include <vtkXMLImageDataWriter.h>
#include <vtkDataSetAttributes.h>
#include <vtkUnsignedCharArray.h>

#include <cmath>
#include <system_error>

#include "dynamics/world.h"
#include "formats/atomic_file.h"
#include "io/vtk_common.h"

namespace polyfloe::io {
namespace fs = std::filesystem;
using geometry::Vec2;
using namespace detail;

namespace {

void add_world_time(vtkDataObject* data, const dynamics::World& world) {
  detail::add_time(data, world.time(), world.step_count());
}

// Body i's draft [m] at its equilibrium in still water (0 where its density is unknown).
double draft_of(const dynamics::World& world, int i, double water_density) {
  const double h = world.thickness(i);                                 // [m]
  const double volume = world.shape(i).area() * h;                     // [m^3]
  const double density = volume > 0.0 ? world.mass(i) / volume : 0.0;  // [kg/m^3]
  const double draft = h * density / water_density;
  return std::isfinite(draft) ? draft : 0.0;
}

// The height of body i's top face [m]: where marks on the ice are drawn so that ParaView shows them over the floes.
double top_of(const dynamics::World& world, int i, double water_density) {
  return world.thickness(i) - draft_of(world, i, water_density);
}

// The bodies a frame shows, in id order: those `world` owns (a whole World: every body; a rank's: all but its
// ghosts), or none (`header_only`: the frame's arrays, empty, as a .pvtp lists them).
std::vector<int> shown_bodies(const dynamics::World& world, bool header_only) {
  std::vector<int> shown;
  if (header_only) return shown;
  shown.reserve(world.size());
  for (const int i : world.id_order())
    if (!world.is_ghost(i)) shown.push_back(i);
  return shown;
}

// The mean normal and |shear| stress over each element's intact bond points, on all its cells (a body of n
// vertices has n + 2 cells, in the order of `shown`: floes_polydata).
void add_bond_stress(vtkPolyData& data, const dynamics::World& world, const bonds::BondSet& b,
                     const std::vector<int>& shown, vtkIdType n_cells) {
  const int bodies = static_cast<int>(world.size());
  std::vector<double> sigma(static_cast<std::size_t>(bodies), 0.0), tau(sigma.size(), 0.0), count(sigma.size(), 0.0);
  const auto per = static_cast<std::size_t>(b.material().points_per_face);
  for (std::size_t f = 0; f < b.faces() && !shown.empty(); ++f) {  // (none shown: a .pvtp's arrays only)
    for (std::size_t p = b.face_first_point(f); p < b.face_first_point(f) + per; ++p) {
      if (!b.point_intact(p)) continue;
      for (int e : {b.face_a(f), b.face_b(f)}) {
        sigma[static_cast<std::size_t>(e)] += b.point_sigma(p);
        tau[static_cast<std::size_t>(e)] += std::abs(b.point_tau(p));
        count[static_cast<std::size_t>(e)] += 1.0;
      }
    }
  }
  auto normal = make_array<vtkDoubleArray>("bond_normal_stress", 1, n_cells);
  auto shear = make_array<vtkDoubleArray>("bond_shear_stress", 1, n_cells);
  vtkIdType c = 0;
  for (const int i : shown) {
    const auto k = static_cast<std::size_t>(i);
    const double sn = count[k] > 0 ? sigma[k] / count[k] : 0.0, st = count[k] > 0 ? tau[k] / count[k] : 0.0;
    for (std::size_t j = 0; j < world.world_vertices(i).size() + 2; ++j, ++c) {
      normal->SetValue(c, sn);
      shear->SetValue(c, st);
    }
  }
  data.GetCellData()->AddArray(normal);
  data.GetCellData()->AddArray(shear);
}

// One prism into the arrays of floes_polydata: its 2n points from p0 (the bottom ring at z = bottom, then the top
// ring at z = top) into xyz, its n + 2 cells (the top, the bottom reversed to face down, one quad per side facing
// out) from `cell`, their connectivity from k; cell and k are advanced.
void add_prism(std::span<const Vec2> ring, double bottom, double top, vtkIdType p0, double* xyz, vtkIdTypeArray& conn,
               vtkIdTypeArray& offsets, vtkIdType& cell, vtkIdType& k) {
  const auto n = static_cast<vtkIdType>(ring.size());
  for (vtkIdType j = 0; j < n; ++j) {
    const auto& v = ring[static_cast<std::size_t>(j)];
    double* b = xyz + 3 * (p0 + j);
    double* t = xyz + 3 * (p0 + n + j);
    b[0] = t[0] = v.x();
    b[1] = t[1] = v.y();
    b[2] = bottom;
    t[2] = top;
  }
  auto close_cell = [&] { offsets.SetValue(++cell, k); };
  for (vtkIdType j = 0; j < n; ++j) conn.SetValue(k++, p0 + n + j);  // top, counter-clockwise from above
  close_cell();
  for (vtkIdType j = n - 1; j >= 0; --j) conn.SetValue(k++, p0 + j);  // bottom, reversed: faces down
  close_cell();
  for (vtkIdType j = 0; j < n; ++j) {  // side j: edge j -> j+1, outward to the right of the edge
    const vtkIdType j1 = (j + 1) % n;
    conn.SetValue(k++, p0 + j);
    conn.SetValue(k++, p0 + j1);
    conn.SetValue(k++, p0 + n + j1);
    conn.SetValue(k++, p0 + n + j);
    close_cell();
  }
}

}  // namespace

// Every body the World owns as a prism floating at its equilibrium draft, in id order: points are the bottom ring
// then the top ring of each body; cells are the top polygon, the bottom polygon (reversed) and one quad per edge, all
// facing outward.
vtkSmartPointer<vtkPolyData> detail::floes_polydata(const dynamics::World& world, double water_density,
                                                    bool header_only) {
  const std::vector<int> shown = shown_bodies(world, header_only);
  vtkIdType n_points = 0, n_cells = 0, n_conn = 0;
  for (const int i : shown) {
    const auto n = static_cast<vtkIdType>(world.world_vertices(i).size());
    n_points += 2 * n;
    n_cells += n + 2;
    n_conn += 6 * n;  // top n + bottom n + 4 per side
  }

  auto coords = make_array<vtkDoubleArray>("Points", 3, n_points);
  auto offsets = vtkSmartPointer<vtkIdTypeArray>::New();
  offsets->SetNumberOfValues(n_cells + 1);
  auto conn = vtkSmartPointer<vtkIdTypeArray>::New();
  conn->SetNumberOfValues(n_conn);

  auto id = make_array<vtkTypeUInt64Array>("id", 1, n_cells);
  auto velocity = make_array<vtkDoubleArray>("velocity", 3, n_cells);
  auto speed = make_array<vtkDoubleArray>("speed", 1, n_cells);
  auto omega = make_array<vtkDoubleArray>("angular_velocity", 1, n_cells);
  auto thickness = make_array<vtkDoubleArray>("thickness", 1, n_cells);
  auto motion = make_array<vtkTypeInt32Array>("motion", 1, n_cells);

  const auto vel = world.velocities();
  const auto ang = world.angular_velocities();
  double* xyz = coords->GetPointer(0);
  vtkIdType p0 = 0, cell = 0, k = 0;
  offsets->SetValue(0, 0);
  for (const int i : shown) {
    const auto ring = world.world_vertices(i);
    const auto n = static_cast<vtkIdType>(ring.size());
    const double h = world.thickness(i);  // [m]
    const double draft = draft_of(world, i, water_density);
    const vtkIdType c0 = cell;
    add_prism(ring, -draft, h - draft, p0, xyz, *conn, *offsets, cell, k);
    p0 += 2 * n;

    const auto& u = vel[static_cast<std::size_t>(i)];
    const double w = ang[static_cast<std::size_t>(i)];
    const double s = u.norm();
    const double vel3[3] = {u.x(), u.y(), 0.0};
    for (vtkIdType c = c0; c < cell; ++c) {
      id->SetValue(c, world.id(i));
      velocity->SetTypedTuple(c, vel3);
      speed->SetValue(c, s);
      omega->SetValue(c, w);
      thickness->SetValue(c, h);
      motion->SetValue(c, static_cast<int>(world.motion(i)));
    }
  }

  auto data = vtkSmartPointer<vtkPolyData>::New();
  vtkNew<vtkPoints> points;
  points->SetData(coords);
  data->SetPoints(points);
  vtkNew<vtkCellArray> polys;
  polys->SetData(offsets, conn);
  data->SetPolys(polys);
  for (vtkDataArray* a :
       {static_cast<vtkDataArray*>(id), static_cast<vtkDataArray*>(velocity), static_cast<vtkDataArray*>(speed),
        static_cast<vtkDataArray*>(omega), static_cast<vtkDataArray*>(thickness), static_cast<vtkDataArray*>(motion)}) {
    data->GetCellData()->AddArray(a);
  }
  if (const bonds::BondSet* b = world.bonds()) add_bond_stress(*data, world, *b, shown, n_cells);
  data->GetCellData()->SetActiveScalars("speed");
  add_world_time(data, world);
  return data;
}

// One line per bond face, where the face is now (along element a's side of it), with its state as cell data: the
// faces whose lower-id element the World owns (a whole World: every face), or none (`header_only`).
vtkSmartPointer<vtkPolyData> detail::bonds_polydata(const dynamics::World& world, double water_density,
                                                    bool header_only) {
  const bonds::BondSet& b = *world.bonds();
  std::vector<std::size_t> shown;
  for (std::size_t f = 0; f < b.faces() && !header_only; ++f)
    if (!world.is_ghost(world.index_of(std::min(b.face_id_a(f), b.face_id_b(f))))) shown.push_back(f);
  const auto n = static_cast<vtkIdType>(shown.size());
  const std::size_t per = static_cast<std::size_t>(b.material().points_per_face);
  auto coords = make_array<vtkDoubleArray>("Points", 3, 2 * n);
  auto intact = make_array<vtkTypeInt32Array>("intact", 1, n);
  auto normal = make_array<vtkDoubleArray>("normal_stress", 1, n);
  auto shear = make_array<vtkDoubleArray>("shear_stress", 1, n);
  auto points = make_array<vtkTypeInt32Array>("intact_points", 1, n);
  auto broken = make_array<vtkDoubleArray>("broken_time", 1, n);
  const auto pos = world.positions();
  const auto yaw = world.yaws();
  for (vtkIdType f = 0; f < n; ++f) {
    const std::size_t fu = shown[static_cast<std::size_t>(f)];
    const auto a = static_cast<std::size_t>(b.face_a(fu));
    const double c = std::cos(yaw[a]), s = std::sin(yaw[a]);
    const std::size_t p0 = b.face_first_point(fu), p1 = p0 + per - 1;
    // The points sit at the middles of equal segments: extend by half a segment to the face's ends.
    const Vec2 first = geometry::rotate(b.point_anchor_a(p0), c, s),
               last = geometry::rotate(b.point_anchor_a(p1), c, s);
    const Vec2 half = (last - first) / (2.0 * static_cast<double>(per - 1));
    const Vec2 e0 = pos[a] + first - half, e1 = pos[a] + last + half;
    const double z = top_of(world, static_cast<int>(a), water_density);  // on the ice's top face
    const double x0[3] = {e0.x(), e0.y(), z}, x1[3] = {e1.x(), e1.y(), z};
    coords->SetTypedTuple(2 * f, x0);
    coords->SetTypedTuple(2 * f + 1, x1);
    double sn = 0.0, st = 0.0;
    int k = 0;
    for (std::size_t p = p0; p <= p1; ++p) {
      if (!b.point_intact(p)) continue;
      sn += b.point_sigma(p);
      st += std::abs(b.point_tau(p));
      ++k;
    }
    intact->SetValue(f, b.face_intact(fu) ? 1 : 0);
    points->SetValue(f, k);
    normal->SetValue(f, k ? sn / k : 0.0);
    shear->SetValue(f, k ? st / k : 0.0);
    broken->SetValue(f, b.face_broken_time(fu));
  }
  auto data = vtkSmartPointer<vtkPolyData>::New();
  vtkNew<vtkPoints> pts;
  pts->SetData(coords);
  data->SetPoints(pts);
  auto offsets = vtkSmartPointer<vtkIdTypeArray>::New();
  offsets->SetNumberOfValues(n + 1);
  for (vtkIdType f = 0; f <= n; ++f) offsets->SetValue(f, 2 * f);
  vtkNew<vtkCellArray> lines;
  lines->SetData(offsets, iota(2 * n));
  data->SetLines(lines);
  for (vtkDataArray* a :
       {static_cast<vtkDataArray*>(intact), static_cast<vtkDataArray*>(points), static_cast<vtkDataArray*>(normal),
        static_cast<vtkDataArray*>(shear), static_cast<vtkDataArray*>(broken)})
    data->GetCellData()->AddArray(a);
  data->GetCellData()->SetActiveScalars("intact");
  add_world_time(data, world);
  return data;
}

// One vertex per contact of the World's last evaluation (a rank's: those it evaluated) at its point, on the higher
// of the two bodies' top faces (where ParaView shows it over the floes), with the contact's forces and geometry as
// point data; none for `header_only`.
vtkSmartPointer<vtkPolyData> detail::contacts_polydata(const dynamics::World& world, double water_density,
                                                       bool header_only) {
  const auto& contacts = world.contacts();
  const auto n = header_only ? vtkIdType{0} : static_cast<vtkIdType>(contacts.size());
  auto coords = make_array<vtkDoubleArray>("Points", 3, n);
  auto force = make_array<vtkDoubleArray>("force", 3, n);
  auto normal_force = make_array<vtkDoubleArray>("normal_force", 1, n);
  auto tangential_force = make_array<vtkDoubleArray>("tangential_force", 1, n);
  auto normal = make_array<vtkDoubleArray>("normal", 3, n);
  auto depth = make_array<vtkDoubleArray>("depth", 1, n);
  auto area = make_array<vtkDoubleArray>("overlap_area", 1, n);
  auto id_a = make_array<vtkTypeUInt64Array>("id_a", 1, n);
  auto id_b = make_array<vtkTypeUInt64Array>("id_b", 1, n);
  auto sliding = make_array<vtkTypeInt32Array>("sliding", 1, n);
  for (vtkIdType c = 0; c < n; ++c) {
    const auto& r = contacts[static_cast<std::size_t>(c)];
    const auto f = r.force_on_b();
    const double z = std::max(top_of(world, r.a, water_density), top_of(world, r.b, water_density));
    const double p[3] = {r.geometry.point.x(), r.geometry.point.y(), z};
    const double f3[3] = {f.x(), f.y(), 0.0};
    const double n3[3] = {r.geometry.normal.x(), r.geometry.normal.y(), 0.0};
    coords->SetTypedTuple(c, p);
    force->SetTypedTuple(c, f3);
    normal->SetTypedTuple(c, n3);
    normal_force->SetValue(c, r.normal_force);
    tangential_force->SetValue(c, r.tangential_force);
    depth->SetValue(c, r.geometry.depth);
    area->SetValue(c, r.geometry.area);
    id_a->SetValue(c, world.id(r.a));
    id_b->SetValue(c, world.id(r.b));
    sliding->SetValue(c, r.sliding ? 1 : 0);
  }

  auto data = vtkSmartPointer<vtkPolyData>::New();
  vtkNew<vtkPoints> points;
  points->SetData(coords);
  data->SetPoints(points);
  vtkNew<vtkCellArray> verts;
  verts->SetData(iota(n + 1), iota(n));  // offsets 0..n, connectivity 0..n-1
  data->SetVerts(verts);
  for (vtkDataArray* a :
       {static_cast<vtkDataArray*>(force), static_cast<vtkDataArray*>(normal_force),
        static_cast<vtkDataArray*>(tangential_force), static_cast<vtkDataArray*>(normal),
        static_cast<vtkDataArray*>(depth), static_cast<vtkDataArray*>(area), static_cast<vtkDataArray*>(id_a),
        static_cast<vtkDataArray*>(id_b), static_cast<vtkDataArray*>(sliding)}) {
    data->GetPointData()->AddArray(a);
  }
  data->GetPointData()->SetActiveScalars("normal_force");
  add_world_time(data, world);
  return data;
}

VtkSeriesWriter::VtkSeriesWriter(const fs::path& dir, bool write_contacts, double water_density,
                                 OutputManifest* manifest, int pieces)
    : dir_(dir),
      write_contacts_(write_contacts),
      water_density_(water_density),
      manifest_(manifest),
      pieces_(pieces),
      floes_pvd_(dir / "floes.pvd", manifest),
      contacts_pvd_(dir / "contacts.pvd", manifest),
      bonds_pvd_(dir / "bonds.pvd", manifest) {
  if (!(water_density > 0.0) || !std::isfinite(water_density)) {
    throw IoError("VTK output " + dir.string() + ": water density must be positive, got " + exact(water_density));
  }
  std::error_code ec;
  floes_pvd_.record("floes/");
  fs::create_directories(dir / "floes", ec);
  if (!ec && write_contacts_) {
    contacts_pvd_.record("contacts/");
    fs::create_directories(dir / "contacts", ec);
  }
  if (ec) throw IoError("cannot create VTK output folders in " + dir.string() + ": " + ec.message());
}

void VtkSeriesWriter::write_frame(const dynamics::World& world) {
  // One series' frame: the whole World's in one file, or the list of its pieces (the arrays from an empty one).
  auto write = [&](PvdCollection& pvd, const std::string& stem, auto&& polydata) {
    const std::string file = stem + "/" + frame_name(stem, frames_, pieces_ > 0 ? ".pvtp" : ".vtp");
    pvd.record(file);
    if (pieces_ == 0) {
      write_polydata(polydata(world, water_density_, false), dir_ / file);
      return file;
    }
    std::vector<std::string> pieces;
    for (int k = 0; k < pieces_; ++k) {
      pieces.push_back(piece_name(stem, frames_, k));
      if (!fs::exists(dir_ / stem / pieces.back()))
        throw IoError("cannot write " + (dir_ / file).string() + ": its piece " + pieces.back() + " is missing");
    }
    write_pvtp(polydata(world, water_density_, true), pieces, dir_ / file);
    return file;
  };
  const std::string floes_file = write(floes_pvd_, "floes", floes_polydata);
  std::string contacts_file, bonds_file;
  if (write_contacts_) contacts_file = write(contacts_pvd_, "contacts", contacts_polydata);
  if (world.bonds()) {
    make_bonds_folder();
    bonds_file = write(bonds_pvd_, "bonds", bonds_polydata);
  }
  // Collections last: they only ever list frames that are complete on disk.
  floes_pvd_.add(world.time(), floes_file);
  if (write_contacts_) contacts_pvd_.add(world.time(), contacts_file);
  if (world.bonds()) bonds_pvd_.add(world.time(), bonds_file);
  ++frames_;
}

void VtkSeriesWriter::resume(std::span<const double> frame_times, bool bonds) {
  const int frames = static_cast<int>(frame_times.size());
  // The collections first, then the frames they no longer list: a kill between the two leaves unlisted files,
  // never a collection that lists a missing one.
  floes_pvd_.resume(frame_times, "floes", ".vtp");
  if (write_contacts_) contacts_pvd_.resume(frame_times, "contacts", ".vtp");
  if (bonds) bonds_pvd_.resume(frame_times, "bonds", ".vtp");
  remove_frames_from(dir_, "floes", ".vtp", frames, manifest_);
  remove_frames_from(dir_, "contacts", ".vtp", frames, manifest_);
  remove_frames_from(dir_, "bonds", ".vtp", frames, manifest_);
  frames_ = frames;
}

VtkImageSeriesWriter::VtkImageSeriesWriter(const fs::path& dir, std::string stem, const ImageGrid& grid,
                                           OutputManifest* manifest)
    : dir_(dir), stem_(std::move(stem)), grid_(grid), manifest_(manifest), pvd_(dir / (stem_ + ".pvd"), manifest) {
  if (grid.nx < 1 || grid.ny < 1 || !(grid.cell > 0.0) || !std::isfinite(grid.cell))
    throw IoError("VTK image output " + (dir / stem_).string() + ": the grid needs positive cell size and counts");
  std::error_code ec;
  pvd_.record(stem_ + "/");
  fs::create_directories(dir / stem_, ec);
  if (ec) throw IoError("cannot create VTK output folder " + (dir / stem_).string() + ": " + ec.message());
}

void VtkImageSeriesWriter::write_frame(double time, std::uint64_t step, std::span<const CellField> fields) {
  const std::string file = stem_ + "/" + frame_name(stem_, frames_, ".vti");
  pvd_.record(file);
  const auto cells = static_cast<vtkIdType>(grid_.nx) * grid_.ny;
  auto image = vtkSmartPointer<vtkImageData>::New();
  image->SetDimensions(grid_.nx + 1, grid_.ny + 1, 1);  // points at the cell corners
  image->SetOrigin(grid_.x0, grid_.y0, 0.0);
  image->SetSpacing(grid_.cell, grid_.cell, 1.0);
  for (const CellField& f : fields) {
    if (f.components < 1 || f.values.size() != static_cast<std::size_t>(cells * f.components))
      throw IoError("cannot write " + (dir_ / file).string() + ": array '" + f.name + "' has " +
                    std::to_string(f.values.size()) + " values for " + std::to_string(cells) + " cells x " +
                    std::to_string(f.components) + " components");
    const int out_components = f.components == 2 ? 3 : f.components;
    auto a = make_array<vtkFloatArray>(f.name.c_str(), out_components, cells);
    float* dst = a->GetPointer(0);
    for (vtkIdType c = 0; c < cells; ++c) {
      for (int k = 0; k < f.components; ++k)
        dst[c * out_components + k] = f.values[static_cast<std::size_t>(c * f.components + k)];
      if (out_components != f.components) dst[c * out_components + 2] = 0.0f;
    }
    image->GetCellData()->AddArray(a);
  }
  // Cells with a NaN (no ice sampled there) hidden through VTK's ghost array: ParaView leaves them out instead of
  // drawing NaN's colour over the water.
  auto ghost = make_array<vtkUnsignedCharArray>(vtkDataSetAttributes::GhostArrayName(), 1, cells);
  for (vtkIdType c = 0; c < cells; ++c) {
    bool nan = false;
    for (const CellField& f : fields)
      for (int k = 0; k < f.components; ++k)
        nan = nan || std::isnan(f.values[static_cast<std::size_t>(c * f.components + k)]);
    ghost->SetValue(c, nan ? vtkDataSetAttributes::HIDDENCELL : 0);
  }
  image->GetCellData()->AddArray(ghost);
  add_time(image, time, step);
  vtkNew<vtkXMLImageDataWriter> writer;
  write_xml(writer, image, dir_ / file);
  pvd_.add(time, file);
  ++frames_;
}

void VtkImageSeriesWriter::resume(std::span<const double> frame_times) {
  const int frames = static_cast<int>(frame_times.size());
  pvd_.resume(frame_times, stem_, ".vti");  // as above: the collection before the frames it drops
  remove_frames_from(dir_, stem_, ".vti", frames, manifest_);
  frames_ = frames;
}

}  // namespace polyfloe::io
