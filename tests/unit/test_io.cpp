// Output module: VTK series (.vtp + .pvd), the HDF5 results series (the formats beneath them: test_formats.cpp;
// the progress display: test_progress.cpp).
// Every file written is read back with the readers users have (VTK's XML reader, the HDF5 C API).
#include <gtest/gtest.h>

#include "scratch_dir.h"
#include "text_file.h"
#include "pvd.h"

#include <hdf5.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>
#include <vtkCellData.h>
#include <vtkDataArray.h>
#include <vtkFieldData.h>
#include <vtkIdList.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPolyData.h>
#include <vtkXMLPolyDataReader.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "dynamics/world.h"
#include "formats/atomic_file.h"
#include "formats/hdf5_file.h"
#include "io/hdf5_writer.h"
#include "io/vtk_writer.h"

namespace fs = std::filesystem;
using namespace polyfloe;

namespace {

constexpr double kWater = 1025.0;  // [kg/m^3]
constexpr double kIce = 920.0;     // [kg/m^3]
constexpr double kDt = 1e-3;       // [s]

using TempDir = tsupport::TestDir;

// Three hexagons: two dynamic ones overlapping a little (a contact) and a fixed one apart.
std::unique_ptr<dynamics::World> make_world() {
  auto world = std::make_unique<dynamics::World>(dynamics::WorldSettings{});
  auto hex = std::make_shared<const geometry::ConvexPolygon>(geometry::ConvexPolygon::regular(6, 5.0));
  dynamics::BodyDesc d;
  d.shape = hex;
  d.density = kIce;
  d.id = 7;
  d.position = {0.0, 0.0};
  d.velocity = {0.5, 0.25};
  d.angular_velocity = 0.1;
  d.thickness = 1.0;
  world->add_body(d);
  d.id = 3;
  d.position = {8.5, 0.0};
  d.yaw = 0.3;
  d.velocity = {-0.2, 0.0};
  d.angular_velocity = -0.05;
  d.thickness = 2.0;
  world->add_body(d);
  d.id = 100;
  d.position = {0.0, 30.0};
  d.yaw = 0.0;
  d.velocity = {0.0, 0.0};
  d.angular_velocity = 0.0;
  d.thickness = 1.5;
  d.motion = dynamics::Motion::fixed;
  world->add_body(d);
  world->compute_forces(kDt);
  return world;
}

// What a frame held when it was written.
struct FrameRecord {
  double time = 0.0;
  std::vector<double> speed;
  std::size_t contacts = 0;
};

FrameRecord record(const dynamics::World& w) {
  FrameRecord r;
  r.time = w.time();
  for (const auto& v : w.velocities()) r.speed.push_back(v.norm());
  r.contacts = w.contacts().size();
  return r;
}

vtkSmartPointer<vtkPolyData> read_vtp(const fs::path& file) {
  vtkNew<vtkXMLPolyDataReader> reader;
  reader->SetFileName(file.c_str());
  reader->Update();
  EXPECT_EQ(reader->GetErrorCode(), 0u) << file;
  vtkSmartPointer<vtkPolyData> out = reader->GetOutput();
  return out;
}

using tsupport::slurp;

// (timestep, file) of every DataSet of a .pvd.
std::vector<std::pair<double, std::string>> parse_pvd(const fs::path& file) {
  const std::string text = slurp(file);
  EXPECT_NE(text.find("<VTKFile type=\"Collection\""), std::string::npos);
  EXPECT_NE(text.find("</VTKFile>"), std::string::npos);
  return polyfloe::tsupport::read_pvd(file);
}

// Newell normal of a polygon cell (not normalised).
std::array<double, 3> cell_normal(vtkPolyData* pd, vtkIdType cell, std::array<double, 3>& centre) {
  vtkNew<vtkIdList> ids;
  pd->GetCellPoints(cell, ids);
  std::array<double, 3> n{0, 0, 0};
  centre = {0, 0, 0};
  const vtkIdType m = ids->GetNumberOfIds();
  for (vtkIdType k = 0; k < m; ++k) {
    double p[3], q[3];
    pd->GetPoint(ids->GetId(k), p);
    pd->GetPoint(ids->GetId((k + 1) % m), q);
    n[0] += (p[1] - q[1]) * (p[2] + q[2]);
    n[1] += (p[2] - q[2]) * (p[0] + q[0]);
    n[2] += (p[0] - q[0]) * (p[1] + q[1]);
    for (int c = 0; c < 3; ++c) centre[c] += p[c] / static_cast<double>(m);
  }
  return n;
}

// --- small HDF5 C API helpers for reading back independently of the wrapper ---
std::vector<hsize_t> h5_dims(hid_t file, const char* name) {
  const hid_t d = H5Dopen2(file, name, H5P_DEFAULT);
  EXPECT_GE(d, 0) << name;
  const hid_t s = H5Dget_space(d);
  std::vector<hsize_t> dims(static_cast<std::size_t>(H5Sget_simple_extent_ndims(s)));
  H5Sget_simple_extent_dims(s, dims.data(), nullptr);
  H5Sclose(s);
  H5Dclose(d);
  return dims;
}

template <class T>
std::vector<T> h5_read(hid_t file, const char* name, hid_t memtype) {
  std::size_t n = 1;
  for (auto d : h5_dims(file, name)) n *= d;
  std::vector<T> out(n);
  const hid_t d = H5Dopen2(file, name, H5P_DEFAULT);
  EXPECT_GE(H5Dread(d, memtype, H5S_ALL, H5S_ALL, H5P_DEFAULT, out.data()), 0) << name;
  H5Dclose(d);
  return out;
}

bool h5_has_attr(hid_t file, const char* object, const char* attr) {
  return H5Aexists_by_name(file, object, attr, H5P_DEFAULT) > 0;
}

}  // namespace

TEST(IoWriters, ThreeFramesWrittenToVtkAndHdf5ReadBackAsTheWorldWasAtEachFrame) {
  TempDir dir;
  auto world = make_world();
  const auto n = static_cast<int>(world->size());
  io::VtkSeriesWriter vtk(dir.path() / "vtk", true, kWater);
  io::RunInfo info{"scenes/test.yaml", "name: test\nlong: " + std::string(100000, 'x') + "\n", "0.1.0 (test)",
                   "dt=0.001\nt_end=1", kDt};
  io::Hdf5Writer h5(dir.path() / "out" / "run.h5", *world, info, kWater);

  std::vector<FrameRecord> frames;
  for (int f = 0; f < 3; ++f) {
    if (f > 0) {
      for (int s = 0; s < 5; ++s) world->step(kDt);
    }
    vtk.write_frame(*world);
    h5.write_frame(*world);
    frames.push_back(record(*world));
  }
  EXPECT_EQ(vtk.frames(), 3);
  EXPECT_EQ(h5.frames(), 3);
  ASSERT_GT(frames[0].contacts, 0u) << "the scene was meant to have a contact";

  // ---- floes .vtp ----
  int cells = 0, points = 0;
  for (int i = 0; i < n; ++i) {
    cells += world->shape(i).size() + 2;
    points += 2 * world->shape(i).size();
  }
  for (int f = 0; f < 3; ++f) {
    char name[64];
    std::snprintf(name, sizeof name, "floes/floes_%06d.vtp", f);
    auto pd = read_vtp(dir.path() / "vtk" / name);
    ASSERT_EQ(pd->GetNumberOfCells(), cells);
    ASSERT_EQ(pd->GetNumberOfPoints(), points);
    auto* id = pd->GetCellData()->GetArray("id");
    auto* speed = pd->GetCellData()->GetArray("speed");
    auto* velocity = pd->GetCellData()->GetArray("velocity");
    auto* omega = pd->GetCellData()->GetArray("angular_velocity");
    auto* thickness = pd->GetCellData()->GetArray("thickness");
    auto* motion = pd->GetCellData()->GetArray("motion");
    ASSERT_TRUE(id && speed && velocity && omega && thickness && motion);
    EXPECT_EQ(velocity->GetNumberOfComponents(), 3);
    auto* time = pd->GetFieldData()->GetArray("TIME");
    ASSERT_TRUE(time);
    EXPECT_DOUBLE_EQ(time->GetTuple1(0), frames[f].time);
    vtkIdType c = 0;
    for (const int i : world->id_order()) {  // the bodies in id order (its ids run against the indices)
      const int m = world->shape(i).size();
      for (int k = 0; k < m + 2; ++k, ++c) {
        EXPECT_EQ(static_cast<std::uint64_t>(id->GetTuple1(c)), world->id(i));
        EXPECT_NEAR(speed->GetTuple1(c), frames[f].speed[i], 1e-12);
        EXPECT_DOUBLE_EQ(thickness->GetTuple1(c), world->thickness(i));
        EXPECT_EQ(static_cast<int>(motion->GetTuple1(c)), static_cast<int>(world->motion(i)));
      }
    }
  }

  // Prism geometry of the last frame: floating draft, outward normals.
  {
    auto pd = read_vtp(dir.path() / "vtk" / "floes" / "floes_000002.vtp");
    vtkIdType c = 0, p = 0;
    for (const int i : world->id_order()) {
      const int m = world->shape(i).size();
      const double h = world->thickness(i);
      const double draft = h * kIce / kWater;
      const auto ring = world->world_vertices(i);
      for (int k = 0; k < m; ++k) {
        double bottom[3], top[3];
        pd->GetPoint(p + k, bottom);
        pd->GetPoint(p + m + k, top);
        EXPECT_NEAR(bottom[0], ring[k].x(), 1e-9);
        EXPECT_NEAR(top[1], ring[k].y(), 1e-9);
        EXPECT_NEAR(bottom[2], -draft, 1e-12);
        EXPECT_NEAR(top[2], h - draft, 1e-12);
      }
      const double body_centre[3] = {world->positions()[i].x(), world->positions()[i].y(), 0.5 * h - draft};
      for (int k = 0; k < m + 2; ++k, ++c) {
        std::array<double, 3> centre;
        const auto nrm = cell_normal(pd, c, centre);
        double outward = 0.0;
        for (int q = 0; q < 3; ++q) outward += nrm[q] * (centre[q] - body_centre[q]);
        EXPECT_GT(outward, 0.0) << "body " << i << " cell " << k;
      }
      p += 2 * m;
    }
  }

  // ---- contacts .vtp ----
  for (int f = 0; f < 3; ++f) {
    char name[64];
    std::snprintf(name, sizeof name, "contacts/contacts_%06d.vtp", f);
    auto pd = read_vtp(dir.path() / "vtk" / name);
    ASSERT_EQ(pd->GetNumberOfPoints(), static_cast<vtkIdType>(frames[f].contacts));
    EXPECT_EQ(pd->GetNumberOfVerts(), static_cast<vtkIdType>(frames[f].contacts));
    for (const char* a :
         {"force", "normal_force", "tangential_force", "normal", "depth", "overlap_area", "id_a", "id_b", "sliding"}) {
      EXPECT_TRUE(pd->GetPointData()->GetArray(a)) << a;
    }
  }
  {
    auto pd = read_vtp(dir.path() / "vtk" / "contacts" / "contacts_000002.vtp");
    const auto& contacts = world->contacts();
    ASSERT_EQ(pd->GetNumberOfPoints(), static_cast<vtkIdType>(contacts.size()));
    for (vtkIdType k = 0; k < pd->GetNumberOfPoints(); ++k) {
      const auto& r = contacts[static_cast<std::size_t>(k)];
      double x[3];
      pd->GetPoint(k, x);
      EXPECT_NEAR(x[0], r.geometry.point.x(), 1e-12);
      // On the higher top face of the two floes (above the water by h (1 - rho_ice / rho_water)), where ParaView
      // shows it over the floes, not inside them.
      const double top = std::max(world->thickness(r.a), world->thickness(r.b)) * (1.0 - kIce / kWater);
      EXPECT_NEAR(x[2], top, 1e-12);
      EXPECT_EQ(static_cast<std::uint64_t>(pd->GetPointData()->GetArray("id_a")->GetTuple1(k)), world->id(r.a));
      EXPECT_EQ(static_cast<std::uint64_t>(pd->GetPointData()->GetArray("id_b")->GetTuple1(k)), world->id(r.b));
      EXPECT_NEAR(pd->GetPointData()->GetArray("force")->GetComponent(k, 0), r.force_on_b().x(), 1e-9);
      EXPECT_NEAR(pd->GetPointData()->GetArray("depth")->GetTuple1(k), r.geometry.depth, 1e-15);
    }
  }

  // ---- .pvd collections ----
  for (const char* stem : {"floes", "contacts"}) {
    const auto entries = parse_pvd(dir.path() / "vtk" / (std::string(stem) + ".pvd"));
    ASSERT_EQ(entries.size(), 3u) << stem;
    for (std::size_t k = 0; k < entries.size(); ++k) {
      EXPECT_DOUBLE_EQ(entries[k].first, frames[k].time);
      if (k > 0) {
        EXPECT_GT(entries[k].first, entries[k - 1].first);
      }
      EXPECT_TRUE(fs::path(entries[k].second).is_relative());
      EXPECT_TRUE(fs::exists(dir.path() / "vtk" / entries[k].second)) << entries[k].second;
    }
  }
  // No temporary files left behind.
  for (const auto& e : fs::recursive_directory_iterator(dir.path() / "vtk")) {
    EXPECT_EQ(e.path().filename().string().find(".tmp"), std::string::npos) << e.path();
  }

  // ---- HDF5, read with the C API ----
  h5.flush();
  const std::string h5_path = (dir.path() / "out" / "run.h5").string();
  const hid_t file = H5Fopen(h5_path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  ASSERT_GE(file, 0);
  const auto N = static_cast<hsize_t>(n);
  EXPECT_EQ(h5_dims(file, "/time"), (std::vector<hsize_t>{3}));
  EXPECT_EQ(h5_dims(file, "/state/position"), (std::vector<hsize_t>{3, N, 3}));
  EXPECT_EQ(h5_dims(file, "/state/orientation"), (std::vector<hsize_t>{3, N, 4}));
  EXPECT_EQ(h5_dims(file, "/state/velocity"), (std::vector<hsize_t>{3, N, 3}));
  EXPECT_EQ(h5_dims(file, "/state/angular_velocity"), (std::vector<hsize_t>{3, N, 3}));
  EXPECT_EQ(h5_dims(file, "/diagnostics/linear_momentum"), (std::vector<hsize_t>{3, 2}));
  const auto t = h5_read<double>(file, "/time", H5T_NATIVE_DOUBLE);
  for (int f = 0; f < 3; ++f) EXPECT_DOUBLE_EQ(t[f], frames[f].time);
  // Every per-body row in id order: row k is body order[k] (the ids 7, 3, 100 of bodies 0, 1, 2: rows 1, 0, 2).
  const auto order = world->id_order();
  std::vector<std::size_t> row(static_cast<std::size_t>(n));
  for (int k = 0; k < n; ++k) row[static_cast<std::size_t>(order[k])] = static_cast<std::size_t>(k);
  ASSERT_EQ(row, (std::vector<std::size_t>{1, 0, 2}));
  const auto ids = h5_read<std::uint64_t>(file, "/floes/id", H5T_NATIVE_UINT64);
  ASSERT_EQ(ids.size(), N);
  EXPECT_TRUE(std::is_sorted(ids.begin(), ids.end()));
  for (int i = 0; i < n; ++i) EXPECT_EQ(ids[row[i]], world->id(i));
  const auto offsets = h5_read<std::int64_t>(file, "/floes/polygon_offsets", H5T_NATIVE_INT64);
  ASSERT_EQ(offsets.size(), N + 1);
  EXPECT_EQ(offsets[0], 0);
  for (int i = 0; i < n; ++i) EXPECT_EQ(offsets[row[i] + 1] - offsets[row[i]], world->shape(i).size());
  EXPECT_EQ(h5_dims(file, "/floes/polygon_xy"), (std::vector<hsize_t>{static_cast<hsize_t>(offsets[n]), 2}));
  const auto xy = h5_read<double>(file, "/floes/polygon_xy", H5T_NATIVE_DOUBLE);
  EXPECT_DOUBLE_EQ(xy[2 * offsets[row[1]]], world->shape(1).vertices()[0].x());
  const auto motion = h5_read<int>(file, "/floes/motion", H5T_NATIVE_INT);
  EXPECT_EQ(motion[row[2]], 1);
  EXPECT_EQ(motion[row[0]], 0);
  const auto q = h5_read<double>(file, "/state/orientation", H5T_NATIVE_DOUBLE);
  for (std::size_t k = 0; k < q.size(); k += 4) {
    EXPECT_NEAR(q[k] * q[k] + q[k + 1] * q[k + 1] + q[k + 2] * q[k + 2] + q[k + 3] * q[k + 3], 1.0, 1e-12);
  }
  // Last frame, body 1: yaw and position.
  const std::size_t last = 2 * N * 4 + 4 * row[1];
  EXPECT_NEAR(2.0 * std::atan2(q[last + 3], q[last]), world->yaws()[1], 1e-12);
  const auto pos = h5_read<double>(file, "/state/position", H5T_NATIVE_DOUBLE);
  EXPECT_DOUBLE_EQ(pos[2 * N * 3 + 3 * row[1]], world->positions()[1].x());
  EXPECT_NEAR(pos[2 * N * 3 + 3 * row[1] + 2], 0.5 * 2.0 - 2.0 * kIce / kWater, 1e-12);
  const auto w = h5_read<double>(file, "/state/angular_velocity", H5T_NATIVE_DOUBLE);
  EXPECT_DOUBLE_EQ(w[2 * N * 3 + 3 * row[0] + 2], world->angular_velocities()[0]);
  const auto contact_count = h5_read<std::int64_t>(file, "/diagnostics/contact_count", H5T_NATIVE_INT64);
  for (int f = 0; f < 3; ++f) EXPECT_EQ(contact_count[f], static_cast<std::int64_t>(frames[f].contacts));
  const auto ke = h5_read<double>(file, "/diagnostics/kinetic_energy", H5T_NATIVE_DOUBLE);
  EXPECT_DOUBLE_EQ(ke[2], world->kinetic_energy());
  const auto max_speed = h5_read<double>(file, "/diagnostics/max_speed", H5T_NATIVE_DOUBLE);
  EXPECT_DOUBLE_EQ(max_speed[0], std::max(frames[0].speed[0], frames[0].speed[1]));

  for (const char* a : {"scene_path", "scene_text", "code_version", "overrides", "dt", "created_by"}) {
    EXPECT_TRUE(h5_has_attr(file, "/", a)) << a;
  }
  for (const char* d :
       {"/time", "/floes/id", "/floes/thickness", "/floes/mass", "/floes/inertia", "/floes/motion",
        "/floes/polygon_offsets", "/floes/polygon_xy", "/state/position", "/state/orientation", "/state/velocity",
        "/state/angular_velocity", "/diagnostics/kinetic_energy", "/diagnostics/contact_count",
        "/diagnostics/max_speed", "/diagnostics/mean_speed", "/diagnostics/max_overlap_depth",
        "/diagnostics/linear_momentum", "/diagnostics/angular_momentum"}) {
    EXPECT_TRUE(h5_has_attr(file, d, "units")) << d;
  }
  H5Fclose(file);

  // The same file through the wrapper: attributes round-trip.
  io::hdf5::File in(h5_path, io::hdf5::File::Mode::read_only);
  EXPECT_EQ(in.root().string_attribute("created_by"), "PolyFloe");
  EXPECT_EQ(in.root().string_attribute("scene_text"), info.scene_text);
  EXPECT_EQ(in.root().string_attribute("overrides"), info.overrides);
  EXPECT_DOUBLE_EQ(in.root().double_attribute("dt"), kDt);
  EXPECT_EQ(in.root().open_dataset("state/velocity").string_attribute("units"), "m/s");
}

TEST(IoWriters, FrameWithoutContactsIsAValidFile) {
  TempDir dir;
  dynamics::World world(dynamics::WorldSettings{});
  dynamics::BodyDesc d;
  d.id = 1;
  d.shape = std::make_shared<const geometry::ConvexPolygon>(geometry::ConvexPolygon::rectangle(4.0, 2.0));
  world.add_body(d);
  world.compute_forces(kDt);
  io::VtkSeriesWriter vtk(dir.path(), true, kWater);
  vtk.write_frame(world);
  auto pd = read_vtp(dir.path() / "contacts" / "contacts_000000.vtp");
  EXPECT_EQ(pd->GetNumberOfPoints(), 0);
  ASSERT_TRUE(pd->GetPointData()->GetArray("force"));
  EXPECT_EQ(pd->GetPointData()->GetArray("force")->GetNumberOfComponents(), 3);
  EXPECT_EQ(parse_pvd(dir.path() / "contacts.pvd").size(), 1u);
  EXPECT_EQ(read_vtp(dir.path() / "floes" / "floes_000000.vtp")->GetNumberOfCells(), 6);
}

TEST(IoWriters, KilledRunLeavesReadableHdf5Frames) {
  TempDir dir;
  const fs::path path = dir.path() / "killed.h5";
  const pid_t child = ::fork();
  ASSERT_GE(child, 0);
  if (child == 0) {
    auto world = make_world();
    io::Hdf5Writer h5(path, *world, io::RunInfo{}, kWater);
    h5.write_frame(*world);
    world->step(kDt);
    h5.write_frame(*world);
    ::kill(::getpid(), SIGKILL);  // no destructors, no close
    ::_exit(1);
  }
  int status = 0;
  ::waitpid(child, &status, 0);
  ASSERT_TRUE(WIFSIGNALED(status));
  io::hdf5::File in(path, io::hdf5::File::Mode::read_only);
  EXPECT_EQ(in.root().open_dataset("time").read<double>().size(), 2u);
  EXPECT_EQ(in.root().open_dataset("state/position").dims(), (io::hdf5::Dims{2, 3, 3}));
}

TEST(IoWriters, BadWaterDensityThrows) {
  TempDir dir;
  EXPECT_THROW(io::VtkSeriesWriter(dir.path(), false, 0.0), io::IoError);
}

namespace {

TEST(IoWriters, BondsAndBoundaryForcesReadBack) {
  // Two squares bonded across x = 5, the left one fixed, the right one pulled: the bond stress, the intact flags,
  // the face as a VTK line where it is, the elements' mean bond stress, and the force on the fixed body.
  TempDir dir;
  dynamics::WorldSettings ws;
  ws.drift = forcing::DriftSettings::none();
  dynamics::World w(ws);
  const std::vector<geometry::Vec2> corners{{-5, -5}, {5, -5}, {5, 5}, {-5, 5}};
  auto sq = std::make_shared<const geometry::ConvexPolygon>(geometry::ConvexPolygon::from_vertices(corners));
  w.add_body({.id = 10, .shape = sq, .position = {0, 0}, .motion = dynamics::Motion::fixed});
  w.add_body({.id = 11, .shape = sq, .position = {10, 0}});
  bonds::BondSet b(bonds::BondMaterial{.points_per_face = 3});
  b.add_face({.a = 0,
              .b = 1,
              .id_a = 10,
              .id_b = 11,
              .p0 = {5, -5},
              .p1 = {5, 5},
              .thickness = 1.0,
              .centre_a = {0, 0},
              .centre_b = {10, 0}});
  w.set_bonds(std::move(b));
  const double F = 1.0e5;  // [N]: sigma = F / (10 m x 1 m) = 10 kPa once settled
  w.set_external_load(1, {F, 0.0}, 0.0);
  io::VtkSeriesWriter vtk(dir.path(), false, kWater);
  {
    io::Hdf5Writer h5(dir.path() / "run.h5", w, io::RunInfo{}, kWater);
    vtk.write_frame(w);
    h5.write_frame(w);
    for (int k = 0; k < 3000; ++k) w.step(2e-4);
    vtk.write_frame(w);
    h5.write_frame(w);
  }
  io::hdf5::File f(dir.path() / "run.h5", io::hdf5::File::Mode::read_only);
  const auto bonds = f.root().open_group("bonds");
  EXPECT_EQ(bonds.int_attribute("points_per_face"), 3);
  EXPECT_EQ(bonds.open_dataset("face_id_a").read<std::uint64_t>(), std::vector<std::uint64_t>{10});
  EXPECT_EQ(bonds.open_dataset("face_length").read<double>(), std::vector<double>{10.0});
  EXPECT_EQ(bonds.open_dataset("intact_faces").read<std::int64_t>(), (std::vector<std::int64_t>{1, 1}));
  EXPECT_EQ(bonds.open_dataset("point_intact").dims(), (io::hdf5::Dims{2, 3}));
  const auto tension = bonds.open_dataset("max_tensile_stress").read<double>();
  EXPECT_NEAR(tension[1], F / 10.0, 0.02 * F / 10.0);
  const auto diag = f.root().open_group("diagnostics");
  EXPECT_EQ(diag.open_dataset("boundary_ids").read<std::uint64_t>(), std::vector<std::uint64_t>{10});
  const auto load = diag.open_dataset("boundary_force").read<double>();  // [T, 1, 2]
  ASSERT_EQ(load.size(), 4u);
  EXPECT_NEAR(load[2], F, 0.02 * F) << "the bond pulls the fixed square towards +x";

  auto lines = read_vtp(dir.path() / "bonds" / "bonds_000001.vtp");
  ASSERT_EQ(lines->GetNumberOfCells(), 1);
  double p0[3], p1[3];
  lines->GetPoint(0, p0);
  lines->GetPoint(1, p1);
  EXPECT_NEAR(p0[0], 5.0, 1e-3);
  EXPECT_NEAR(std::abs(p1[1] - p0[1]), 10.0, 1e-6) << "the whole face";
  // On the ice's top face (1 m of ice at the default 920 kg/m^3 floats 0.102 m above the water), over the floes.
  EXPECT_NEAR(p0[2], 1.0 - 920.0 / kWater, 1e-12);
  EXPECT_NEAR(p1[2], 1.0 - 920.0 / kWater, 1e-12);
  EXPECT_EQ(lines->GetCellData()->GetArray("intact")->GetTuple1(0), 1.0);
  EXPECT_NEAR(lines->GetCellData()->GetArray("normal_stress")->GetTuple1(0), F / 10.0, 0.02 * F / 10.0);
  auto floes = read_vtp(dir.path() / "floes" / "floes_000001.vtp");
  auto* shear = floes->GetCellData()->GetArray("bond_shear_stress");
  auto* normal = floes->GetCellData()->GetArray("bond_normal_stress");
  ASSERT_TRUE(shear && normal);
  EXPECT_NEAR(normal->GetTuple1(0), F / 10.0, 0.02 * F / 10.0);
  EXPECT_TRUE(fs::exists(dir.path() / "bonds.pvd"));
}

}  // namespace
