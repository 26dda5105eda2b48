// Reading an OpenFOAM case through VTK's OpenFOAM reader: the mesh and the velocity U at the chosen times, as
// MeshSnapshots (a cell locator and cell values) in the transformed coordinates; tutorial-style files that VTK
// cannot parse are first written out plainly by OpenFOAM itself into a scratch copy. Where the case keeps which
// times: case_layout.cpp.
#include "openfoam_case.h"

#include "case_detail.h"

#include <vtkLogger.h>
#include <vtkObjectFactory.h>
#include <vtkOutputWindow.h>
#include <vtkCellData.h>
#include <vtkCompositeDataSet.h>
#include <vtkDataArray.h>
#include <vtkDoubleArray.h>
#include <vtkDummyController.h>
#include <vtkGenericCell.h>
#include <vtkMultiBlockDataSet.h>
#include <vtkNew.h>
#include <vtkPOpenFOAMReader.h>
#include <vtkPoints.h>
#include <vtkPointData.h>
#include <vtkSmartPointer.h>
#include <vtkStaticCellLocator.h>
#include <vtkUnstructuredGrid.h>

#include <stdlib.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <limits>
#include <sstream>

namespace polyfloe::coupling {

namespace fs = std::filesystem;
using detail::fail;
using detail::same_time;
using detail::times_text;

namespace {

// VTK's messages while a case is read, kept instead of printed (VTK prints them with colour codes and source lines,
// from the reader's internal objects too): the first error goes into our message, as one clear line.
class CapturingWindow : public vtkOutputWindow {
 public:
  static CapturingWindow* New();
  vtkTypeMacro(CapturingWindow, vtkOutputWindow);
  void DisplayText(const char* text) override {
    std::string m = text ? text : "";
    for (std::size_t at = m.find('\x1b'); at != std::string::npos; at = m.find('\x1b')) {  // colour codes
      const std::size_t end = m.find('m', at);
      m.erase(at, end == std::string::npos ? std::string::npos : end - at + 1);
    }
    if (const std::size_t cut = m.rfind("): "); cut != std::string::npos) m.erase(0, cut + 3);  // "vtkX (0x..): "
    std::replace(m.begin(), m.end(), '\n', ' ');
    while (!m.empty() && m.back() == ' ') m.pop_back();
    if (!m.empty()) messages.push_back(m);
  }
  std::vector<std::string> messages;
};
vtkStandardNewMacro(CapturingWindow);

class VtkMessages {
 public:
  // VTK 9 also logs errors to stderr itself (vtkLogger): off while the case is read.
  VtkMessages() : previous_(vtkOutputWindow::GetInstance()), verbosity_(vtkLogger::GetCurrentVerbosityCutoff()) {
    vtkOutputWindow::SetInstance(window_);
    vtkLogger::SetStderrVerbosity(vtkLogger::VERBOSITY_OFF);
  }
  ~VtkMessages() {
    vtkOutputWindow::SetInstance(previous_);
    vtkLogger::SetStderrVerbosity(verbosity_);
  }
  VtkMessages(const VtkMessages&) = delete;
  VtkMessages& operator=(const VtkMessages&) = delete;
  // "; VTK's OpenFOAM reader said: ..." with the first message, or nothing.
  std::string said() const {
    return window_->messages.empty() ? std::string() : "; VTK's OpenFOAM reader said: " + window_->messages.front();
  }

 private:
  vtkSmartPointer<vtkOutputWindow> previous_;
  vtkLogger::Verbosity verbosity_;
  vtkNew<CapturingWindow> window_;
};

// The static mesh and its locator, shared by the snapshots of a case (OpenFOAM's constant/polyMesh).
struct Mesh {
  vtkSmartPointer<vtkUnstructuredGrid> grid;
  vtkSmartPointer<vtkStaticCellLocator> locator;
  int max_cell_size = 0;
  std::vector<double> centres;  // 3 per cell: the cell's parametric centre [m]
  double min_horizontal = 0.0;  // [m]
  bool one_layer = false;       // every cell spans the mesh's whole depth (a 2-D, depth-averaged case)
};

}  // namespace

struct MeshSnapshot::Impl {
  std::shared_ptr<const Mesh> mesh;
  std::vector<double> u;       // 3 per mesh point [m/s]
  std::vector<double> cell_u;  // 3 per cell: OpenFOAM's own values [m/s]
};

MeshSnapshot::MeshSnapshot() = default;
MeshSnapshot::~MeshSnapshot() = default;
MeshSnapshot::MeshSnapshot(MeshSnapshot&&) noexcept = default;
MeshSnapshot& MeshSnapshot::operator=(MeshSnapshot&&) noexcept = default;

double MeshSnapshot::min_cell_size() const { return impl_ ? impl_->mesh->min_horizontal : 0.0; }
bool MeshSnapshot::depth_averaged() const { return impl_ && impl_->mesh->one_layer; }

std::size_t MeshSnapshot::cells() const {
  return impl_ ? static_cast<std::size_t>(impl_->mesh->grid->GetNumberOfCells()) : 0;
}

Eigen::Vector3d MeshSnapshot::cell_centre(std::size_t c) const {
  return Eigen::Vector3d(impl_->mesh->centres.data() + 3 * c);
}

Eigen::Vector3d MeshSnapshot::cell_velocity(std::size_t c) const {
  return impl_->cell_u.empty() ? Eigen::Vector3d::Zero() : Eigen::Vector3d(impl_->cell_u.data() + 3 * c);
}

bool MeshSnapshot::has_cell_velocities() const { return impl_ && !impl_->cell_u.empty(); }

Eigen::Vector2d MeshSnapshot::cell_z_range(std::size_t c) const {
  double b[6];
  impl_->mesh->grid->GetCellBounds(static_cast<vtkIdType>(c), b);
  return {b[4], b[5]};
}

bool MeshSnapshot::sample(const Eigen::Vector3d& p, Eigen::Vector3d& u) const {
  // One VTK cell and weight buffer per thread: FindCell with a caller's vtkGenericCell only reads the locator and
  // the mesh, so threads may sample at once.
  thread_local vtkSmartPointer<vtkGenericCell> cell = vtkSmartPointer<vtkGenericCell>::New();
  thread_local std::vector<double> weights;
  const Mesh& m = *impl_->mesh;
  if (weights.size() < static_cast<std::size_t>(m.max_cell_size))
    weights.resize(static_cast<std::size_t>(m.max_cell_size));
  double x[3] = {p.x(), p.y(), p.z()}, pcoords[3];
  const vtkIdType id = m.locator->FindCell(x, 0.0, cell, pcoords, weights.data());
  if (id < 0) return false;
  vtkIdList* ids = cell->GetPointIds();
  u.setZero();
  for (vtkIdType k = 0; k < ids->GetNumberOfIds(); ++k) {
    const double* v = impl_->u.data() + 3 * ids->GetId(k);
    u += weights[static_cast<std::size_t>(k)] * Eigen::Vector3d(v[0], v[1], v[2]);
  }
  return true;
}

bool CaseTransform::identity() const {
  return scale == Eigen::Vector3d::Ones() && rotate == 0.0 && translate == Eigen::Vector3d::Zero() &&
         velocity_scale == 1.0;
}

// Builds snapshots from the reader's output (a friend of MeshSnapshot).
struct SnapshotBuilder {
  static MeshSnapshot make(std::shared_ptr<const Mesh> mesh, std::vector<double> u, std::vector<double> cell_u,
                           double t) {
    MeshSnapshot s;
    s.impl_ = std::make_unique<MeshSnapshot::Impl>();
    s.impl_->mesh = std::move(mesh);
    s.impl_->u = std::move(u);
    s.impl_->cell_u = std::move(cell_u);
    s.time_ = t;
    double b[6];
    s.impl_->mesh->grid->GetBounds(b);
    for (int k = 0; k < 6; ++k) s.bounds_[k] = b[k];
    return s;
  }
};

namespace {

// A scratch folder removed with everything in it (links are removed, never followed).
struct ScratchDir {
  fs::path path;
  ScratchDir() {
    std::string tmpl = (fs::temp_directory_path() / "polyfloe-foam.XXXXXX").string();
    if (!mkdtemp(tmpl.data()))
      throw CouplingError("cannot create a scratch folder under " + fs::temp_directory_path().string());
    path = tmpl;
  }
  ~ScratchDir() {
    std::error_code ec;
    fs::remove_all(path, ec);
  }
  ScratchDir(const ScratchDir&) = delete;
  ScratchDir& operator=(const ScratchDir&) = delete;
};

std::string shell_quoted(const std::string& s) {
  std::string q = "'";
  for (const char c : s) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return q + "'";
}

// An OpenFOAM tool on PATH, or empty.
fs::path find_tool(const char* name) {
  const char* path = std::getenv("PATH");
  std::stringstream dirs(path ? path : "");
  std::string d;
  std::error_code ec;
  while (std::getline(dirs, d, ':'))
    if (!d.empty() && fs::is_regular_file(fs::path(d) / name, ec)) return fs::path(d) / name;
  return {};
}

std::string slurp(const fs::path& p) {
  std::ifstream in(p);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

// A copy of the case that VTK's reader can read: constant/ linked, every chosen time's U copied and written again by
// OpenFOAM itself (`postProcess -func 'writeObjects(U)'`): its #include, #includeEtc, $macros, #calc and
// patch-group entries resolved into one plain entry per patch, in binary (no digit lost). system/ is the scratch's
// own: the case's function objects do not run and its fvSchemes need not be complete.
void expand_into(const fs::path& scratch, const fs::path& dir, const CaseLayout& layout,
                 const std::vector<double>& chosen, const fs::path& tool) {
  const fs::path case_abs = fs::absolute(dir);
  fs::create_directory(scratch / "system");
  const std::string header = "FoamFile { version 2.0; format ascii; class dictionary; object ";
  std::ofstream(scratch / "system" / "controlDict")
      << header
      << "controlDict; }\napplication postProcess;\nstartFrom latestTime;\nstopAt endTime;\nendTime 0;\n"
         "deltaT 1;\nwriteControl timeStep;\nwriteInterval 1;\nwriteFormat binary;\nwritePrecision 17;\n"
         "writeCompression off;\ntimeFormat general;\ntimePrecision 17;\n";
  std::ofstream(scratch / "system" / "fvSchemes")
      << header
      << "fvSchemes; }\nddtSchemes { default Euler; }\ngradSchemes { default Gauss linear; }\n"
         "divSchemes { default none; }\nlaplacianSchemes { default Gauss linear corrected; }\n"
         "interpolationSchemes { default linear; }\nsnGradSchemes { default corrected; }\n";
  std::ofstream(scratch / "system" / "fvSolution") << header << "fvSolution; }\n";
  fs::create_directory_symlink(case_abs / "constant", scratch / "constant");
  for (const double t : chosen) {
    const std::size_t k = static_cast<std::size_t>(
        std::find_if(layout.times.begin(), layout.times.end(), [t](double a) { return same_time(a, t); }) -
        layout.times.begin());
    const fs::path from = case_abs / layout.names.at(k), to = scratch / layout.names[k];
    fs::create_directory(to);
    const char* file = fs::exists(from / "U") ? "U" : "U.gz";
    fs::copy_file(from / file, to / file);
  }
  // OpenFOAM's tools need to know where their etc/ is (Debian's: /usr/share/openfoam).
  const std::string env = std::string(std::getenv("FOAM_ETC") ? "" : "FOAM_ETC=/usr/share/openfoam/etc ") +
                          (std::getenv("WM_PROJECT_DIR") ? "" : "WM_PROJECT_DIR=/usr/share/openfoam ");
  const fs::path log = scratch / "log.postProcess";
  const std::string cmd = env + shell_quoted(tool.string()) + " -case " + shell_quoted(scratch.string()) +
                          " -fields '(U)' -func 'writeObjects(U)' > " + shell_quoted(log.string()) + " 2>&1";
  const int rc = std::system(cmd.c_str());
  const std::string said = slurp(log);
  if (rc != 0 || said.find("FOAM FATAL") != std::string::npos) {
    std::size_t at = said.find("FOAM FATAL");
    std::string first = said.substr(at == std::string::npos ? 0 : at, 600);
    std::replace(first.begin(), first.end(), '\n', ' ');
    fail(dir,
         "VTK's reader cannot read the velocity files, and OpenFOAM could not write them out "
         "plainly (`postProcess -fields '(U)' -func 'writeObjects(U)'` on a copy: " +
             first + ")");
  }
}

// The internal mesh, transformed, and its locator and cell geometry.
std::shared_ptr<Mesh> build_mesh(vtkUnstructuredGrid* grid, const CaseTransform& tf) {
  auto mesh = std::make_shared<Mesh>();
  mesh->grid = vtkSmartPointer<vtkUnstructuredGrid>::New();
  mesh->grid->CopyStructure(grid);
  if (!tf.identity()) {  // own points: the reader's are cached and shared
    const double c = std::cos(tf.rotate * M_PI / 180.0), s = std::sin(tf.rotate * M_PI / 180.0);
    vtkNew<vtkPoints> points;
    points->SetDataTypeToDouble();
    points->SetNumberOfPoints(grid->GetNumberOfPoints());
    for (vtkIdType k = 0; k < grid->GetNumberOfPoints(); ++k) {
      double p[3];
      grid->GetPoint(k, p);
      const double x = tf.scale.x() * p[0], y = tf.scale.y() * p[1], z = tf.scale.z() * p[2];
      points->SetPoint(k, c * x - s * y + tf.translate.x(), s * x + c * y + tf.translate.y(), z + tf.translate.z());
    }
    mesh->grid->SetPoints(points);
  }
  mesh->locator = vtkSmartPointer<vtkStaticCellLocator>::New();
  mesh->locator->SetDataSet(mesh->grid);
  mesh->locator->BuildLocator();
  mesh->max_cell_size = mesh->grid->GetMaxCellSize();
  mesh->min_horizontal = std::numeric_limits<double>::infinity();
  double mb[6];
  mesh->grid->GetBounds(mb);
  const double depth = mb[5] - mb[4];
  mesh->one_layer = true;
  mesh->centres.resize(3 * static_cast<std::size_t>(mesh->grid->GetNumberOfCells()));
  vtkNew<vtkGenericCell> cell;
  std::vector<double> w(static_cast<std::size_t>(std::max(mesh->max_cell_size, 1)));
  for (vtkIdType c = 0; c < mesh->grid->GetNumberOfCells(); ++c) {
    mesh->grid->GetCell(c, cell);
    double pc[3], x[3];
    cell->GetParametricCenter(pc);
    int sub = 0;
    cell->EvaluateLocation(sub, pc, x, w.data());
    std::copy(x, x + 3, mesh->centres.begin() + 3 * c);
    double cb[6];
    mesh->grid->GetCellBounds(c, cb);
    mesh->min_horizontal = std::min({mesh->min_horizontal, cb[1] - cb[0], cb[3] - cb[2]});
    if (cb[5] - cb[4] < depth * (1.0 - 1e-6)) mesh->one_layer = false;
  }
  return mesh;
}

// 3 values per tuple of a velocity array, rotated and scaled; `what` names it in the error for a value that is not
// finite.
std::vector<double> velocities(vtkDataArray* a, const CaseTransform& tf, const fs::path& dir, double t,
                               const char* what) {
  const double c = std::cos(tf.rotate * M_PI / 180.0), s = std::sin(tf.rotate * M_PI / 180.0), k = tf.velocity_scale;
  std::vector<double> out(3 * static_cast<std::size_t>(a->GetNumberOfTuples()));
  for (vtkIdType i = 0; i < a->GetNumberOfTuples(); ++i) {
    double v[3];
    a->GetTuple(i, v);
    if (!std::isfinite(v[0]) || !std::isfinite(v[1]) || !std::isfinite(v[2]))
      fail(dir, "U at time " + times_text({t}) + " is not finite at " + what + " " + std::to_string(i));
    double* o = out.data() + 3 * static_cast<std::size_t>(i);
    o[0] = k * (c * v[0] - s * v[1]);
    o[1] = k * (s * v[0] + c * v[1]);
    o[2] = k * v[2];
  }
  return out;
}

// Reads `read_dir` (the case, or its expanded scratch copy) at `chosen`. A velocity file the reader cannot parse
// (a directive, a patch-group entry, a regular expression for patch names) sets *retry (when given) to what the reader
// said and returns nothing; every other problem throws, naming `dir`.
std::vector<MeshSnapshot> read_times(const fs::path& read_dir, const fs::path& dir, const CaseLayout& layout,
                                     const std::vector<double>& chosen, const CaseTransform& tf, std::string* retry) {
  vtkNew<vtkPOpenFOAMReader> reader;
  const VtkMessages vtk_said;
  vtkNew<vtkDummyController> one_process;  // this process reads every processor's part
  reader->SetController(one_process);
  reader->SetCaseType(layout.decomposed ? vtkPOpenFOAMReader::DECOMPOSED_CASE : vtkPOpenFOAMReader::RECONSTRUCTED_CASE);
  reader->SetFileName((read_dir / "system" / "controlDict").c_str());
  reader->SkipZeroTimeOff();
  reader->UpdateInformation();
  reader->DisableAllPatchArrays();
  reader->SetPatchArrayStatus("internalMesh", 1);
  reader->DisableAllCellArrays();
  reader->SetCellArrayStatus("U", 1);  // only U: other fields may hold macros the reader cannot expand
  reader->DisableAllPointArrays();
  reader->DisableAllLagrangianArrays();
  reader->CreateCellToPointOn();

  std::shared_ptr<Mesh> mesh;
  std::vector<MeshSnapshot> out;
  for (const double t : chosen) {
    reader->UpdateTimeStep(t);
    auto* blocks = vtkMultiBlockDataSet::SafeDownCast(reader->GetOutput());
    vtkUnstructuredGrid* grid =
        blocks && blocks->GetNumberOfBlocks() > 0 ? vtkUnstructuredGrid::SafeDownCast(blocks->GetBlock(0)) : nullptr;
    if (!grid || grid->GetNumberOfCells() == 0)
      fail(dir, "VTK's OpenFOAM reader found no internal mesh" + vtk_said.said());
    vtkDataArray* u = grid->GetPointData()->GetArray("U");
    if (!u || u->GetNumberOfComponents() != 3) {
      const std::string said = vtk_said.said();
      if (retry) {  // OpenFOAM may write it plainly: try again on that copy
        *retry = said;
        return {};
      }
      std::string why = "no velocity U at time " + times_text({t}) + " (the reader could not read " + times_text({t}) +
                        "/U" + said + ")";
      if (said.find("directive") != std::string::npos)
        why +=
            "; VTK's reader cannot expand this directive, and OpenFOAM (its postProcess), which would, is not on "
            "PATH: install OpenFOAM (bash scripts/setup.sh), or write the field out plainly with OpenFOAM's "
            "`postProcess -fields '(U)' -func 'writeObjects(U)'` on a copy of the case" +
            std::string(t == 0.0 ? ", or skip the initial condition (--times latest, or a range of the "
                                   "solution times A:B)"
                                 : "");
      fail(dir, why);
    }
    if (!mesh || mesh->grid->GetNumberOfPoints() != grid->GetNumberOfPoints() ||
        mesh->grid->GetNumberOfCells() != grid->GetNumberOfCells())
      mesh = build_mesh(grid, tf);
    // OpenFOAM's own cell values (the reader keeps them beside the points' interpolation): what `compare` measures
    // the whole chain against.
    vtkDataArray* cu = grid->GetCellData()->GetArray("U");
    std::vector<double> cell_u;
    if (cu && cu->GetNumberOfComponents() == 3 && cu->GetNumberOfTuples() == grid->GetNumberOfCells())
      cell_u = velocities(cu, tf, dir, t, "cell");
    out.push_back(SnapshotBuilder::make(mesh, velocities(u, tf, dir, t, "mesh point"), std::move(cell_u), t));
  }
  return out;
}

}  // namespace

std::vector<MeshSnapshot> read_openfoam_case(const fs::path& dir, const TimeSelection& which, const CaseTransform& tf,
                                             CaseNotes* notes) {
  if (!(tf.scale.array() > 0.0).all() || !tf.scale.allFinite() || !std::isfinite(tf.rotate) ||
      !tf.translate.allFinite() || !std::isfinite(tf.velocity_scale))
    fail(dir, "the transform's scale must be > 0 and every number finite");
  const CaseLayout layout = case_layout(dir);
  const bool steady = case_is_steady(dir);
  const std::vector<double> chosen = choose_times(dir, layout, which, steady);
  CaseNotes local;
  CaseNotes& n = notes ? *notes : local;
  n.layout = layout;
  n.read = chosen;
  n.initial_skipped = which.kind == TimeSelection::Kind::automatic && !steady && chosen.size() < layout.times.size();
  n.expanded = false;
  const fs::path tool = find_tool("postProcess");
  std::string unreadable;
  std::vector<MeshSnapshot> out = read_times(dir, dir, layout, chosen, tf, tool.empty() ? nullptr : &unreadable);
  if (unreadable.empty()) return out;
  // A file VTK's reader cannot parse (#includeEtc and patch-group entries in almost every tutorial's boundary
  // conditions): read a copy OpenFOAM wrote out plainly. decomposePar and parallel solvers write plain files.
  if (layout.decomposed)
    fail(dir, "a decomposed case whose velocity files VTK's reader cannot read" + unreadable +
                  ": reconstruct it with `reconstructPar -case " + dir.string() +
                  "` and import the reconstructed case");
  const ScratchDir scratch;
  expand_into(scratch.path, dir, layout, chosen, tool);
  n.expanded = true;
  return read_times(scratch.path, dir, layout, chosen, tf, nullptr);
}

}  // namespace polyfloe::coupling
