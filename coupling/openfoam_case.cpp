#include "openfoam_case.h"

#include <vtkLogger.h>
#include <vtkObjectFactory.h>
#include <vtkOutputWindow.h>
#include <vtkCellData.h>
#include <vtkCompositeDataSet.h>
#include <vtkDataArray.h>
#include <vtkDoubleArray.h>
#include <vtkGenericCell.h>
#include <vtkMultiBlockDataSet.h>
#include <vtkNew.h>
#include <vtkOpenFOAMReader.h>
#include <vtkPointData.h>
#include <vtkSmartPointer.h>
#include <vtkStaticCellLocator.h>
#include <vtkUnstructuredGrid.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <fstream>
#include <limits>
#include <sstream>

namespace polyfloe::coupling {

namespace fs = std::filesystem;

namespace {

[[noreturn]] void fail(const fs::path& dir, const std::string& what) {
  throw CouplingError(dir.string() + ": " + what);
}

void check_case(const fs::path& dir) {
  std::error_code ec;
  if (!fs::is_directory(dir, ec)) fail(dir, "no such folder (expected an OpenFOAM case)");
  if (!fs::is_regular_file(dir / "system" / "controlDict", ec))
    fail(dir, "not an OpenFOAM case (no system/controlDict)");
  if (!fs::is_directory(dir / "constant" / "polyMesh", ec))
    fail(dir, "no mesh (constant/polyMesh is missing): run the case's Allrun, or blockMesh, first");
}

std::string times_text(const std::vector<double>& t) {
  std::ostringstream os;
  for (std::size_t i = 0; i < t.size(); ++i) os << (i ? ", " : "") << t[i];
  return os.str();
}

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
  if (weights.size() < static_cast<std::size_t>(m.max_cell_size)) weights.resize(static_cast<std::size_t>(m.max_cell_size));
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

namespace {

// The time directories of `dir` (a case or one of its processor*/ folders) that hold U, increasing.
std::vector<double> times_with_u(const fs::path& dir) {
  std::vector<double> times;
  std::error_code ec;
  for (const fs::directory_entry& e : fs::directory_iterator(dir, ec)) {
    if (!e.is_directory(ec)) continue;
    const std::string name = e.path().filename().string();
    double t = 0.0;
    const auto [end, err] = std::from_chars(name.data(), name.data() + name.size(), t);
    if (err != std::errc() || end != name.data() + name.size() || !std::isfinite(t)) continue;
    if (fs::is_regular_file(e.path() / "U", ec) || fs::is_regular_file(e.path() / "U.gz", ec)) times.push_back(t);
  }
  std::sort(times.begin(), times.end());
  return times;
}

}  // namespace

std::vector<double> case_times(const fs::path& dir) {
  check_case(dir);
  const std::vector<double> times = times_with_u(dir);
  // A decomposed case (decomposePar, then a solver run with -parallel) writes its solution into processor*/ only:
  // the case's own time directories then hold the initial condition alone. Reading them would import t = 0 as if
  // it were the flow; the solution must be reconstructed first.
  std::error_code ec;
  if (fs::is_directory(dir / "processor0", ec)) {
    const std::vector<double> decomposed = times_with_u(dir / "processor0");
    if (!decomposed.empty() && (times.empty() || decomposed.back() > times.back()))
      fail(dir, "a decomposed case: its solution (t = " + times_text(decomposed) + " in processor*/) is not "
                "reconstructed, and " + (times.empty() ? std::string("the case itself holds no U") :
                "the case's own U is only at t = " + times_text(times) + " (the initial condition)") +
                "; reconstruct it first with OpenFOAM's `reconstructPar -case " + dir.string() + "`, then import");
  }
  if (times.empty()) fail(dir, "no time directory holds a velocity field U");
  return times;
}

bool case_is_steady(const fs::path& dir) {
  std::ifstream in(dir / "system" / "fvSchemes");
  std::stringstream ss;
  ss << in.rdbuf();
  // ddtSchemes { ... default steadyState; ... } (a plain scan: GCC 12 warns inside <regex> under the sanitizers)
  const std::string text = ss.str();
  const std::size_t key = text.find("ddtSchemes");
  if (key == std::string::npos) return false;
  const std::size_t open = text.find('{', key), close = text.find('}', key);
  if (open == std::string::npos || close == std::string::npos || close < open) return false;
  std::istringstream block(text.substr(open + 1, close - open - 1));
  std::string word, previous;
  while (block >> word) {
    if (previous == "default" && word.rfind("steadyState", 0) == 0) return true;
    previous = word;
  }
  return false;
}

std::vector<MeshSnapshot> read_openfoam_case(const fs::path& dir, const TimeSelection& which) {
  const std::vector<double> available = case_times(dir);
  std::vector<double> chosen;
  using Kind = TimeSelection::Kind;
  const Kind kind = which.kind == Kind::automatic ? (case_is_steady(dir) ? Kind::latest : Kind::all) : which.kind;
  switch (kind) {
    case Kind::automatic:
    case Kind::all: chosen = available; break;
    case Kind::latest: chosen = {available.back()}; break;
    case Kind::listed:
      if (which.times.empty()) fail(dir, "no time chosen");
      for (const double t : which.times) {
        const auto it = std::find_if(available.begin(), available.end(),
                                     [t](double a) { return std::abs(a - t) <= 1e-6 * std::max(1.0, std::abs(t)); });
        if (it == available.end())
          fail(dir, "no time directory " + times_text({t}) + " with U (the case has " + times_text(available) + ")");
        chosen.push_back(*it);
      }
      std::sort(chosen.begin(), chosen.end());
      chosen.erase(std::unique(chosen.begin(), chosen.end()), chosen.end());
      break;
    case Kind::range: {
      if (which.times.size() != 2) fail(dir, "a time range needs its two ends");
      const double lo = which.times[0], hi = which.times[1];  // an open end is infinite
      for (const double a : available)
        if (a >= lo - 1e-6 * std::max(1.0, std::abs(a)) && a <= hi + 1e-6 * std::max(1.0, std::abs(a)))
          chosen.push_back(a);
      if (chosen.empty())
        fail(dir, "no time directory with U in " + times_text({lo}) + ":" + times_text({hi}) + " (the case has " +
                      times_text(available) + ")");
      break;
    }
  }

  vtkNew<vtkOpenFOAMReader> reader;
  const VtkMessages vtk_said;
  reader->SetFileName((dir / "system" / "controlDict").c_str());
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
    if (!grid || grid->GetNumberOfCells() == 0) fail(dir, "VTK's OpenFOAM reader found no internal mesh" + vtk_said.said());
    vtkDataArray* u = grid->GetPointData()->GetArray("U");
    if (!u || u->GetNumberOfComponents() != 3) {
      std::string why = "no velocity U at time " + times_text({t}) + " (the reader could not read " + times_text({t}) +
                        "/U" + vtk_said.said() + ")";
      if (why.find("include") != std::string::npos)
        why += "; VTK's reader cannot expand #include / #includeEtc: expand the file with OpenFOAM's "
               "`foamDictionary -expand`" + std::string(t == 0.0 ? ", or skip the initial condition (--times latest, "
               "or the solution times T1,T2,...)" : "");
      fail(dir, why);
    }
    if (!mesh || mesh->grid->GetNumberOfPoints() != grid->GetNumberOfPoints() ||
        mesh->grid->GetNumberOfCells() != grid->GetNumberOfCells()) {
      mesh = std::make_shared<Mesh>();
      mesh->grid = vtkSmartPointer<vtkUnstructuredGrid>::New();
      mesh->grid->CopyStructure(grid);
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
    }
    MeshSnapshot s;
    s.impl_ = std::make_unique<MeshSnapshot::Impl>();
    s.impl_->mesh = mesh;
    s.impl_->u.resize(3 * static_cast<std::size_t>(u->GetNumberOfTuples()));
    for (vtkIdType k = 0; k < u->GetNumberOfTuples(); ++k)
      for (int c = 0; c < 3; ++c) {
        const double v = u->GetComponent(k, c);
        if (!std::isfinite(v)) fail(dir, "U at time " + times_text({t}) + " is not finite at mesh point " + std::to_string(k));
        s.impl_->u[3 * static_cast<std::size_t>(k) + static_cast<std::size_t>(c)] = v;
      }
    // OpenFOAM's own cell values (the reader keeps them beside the points' interpolation): what `compare` measures
    // the whole chain against.
    vtkDataArray* cu = grid->GetCellData()->GetArray("U");
    if (cu && cu->GetNumberOfComponents() == 3 && cu->GetNumberOfTuples() == grid->GetNumberOfCells()) {
      s.impl_->cell_u.resize(3 * static_cast<std::size_t>(cu->GetNumberOfTuples()));
      for (vtkIdType k = 0; k < cu->GetNumberOfTuples(); ++k)
        for (int c = 0; c < 3; ++c) s.impl_->cell_u[3 * static_cast<std::size_t>(k) + static_cast<std::size_t>(c)] = cu->GetComponent(k, c);
    }
    s.time_ = t;
    double b[6];
    mesh->grid->GetBounds(b);
    for (int k = 0; k < 6; ++k) s.bounds_[k] = b[k];
    out.push_back(std::move(s));
  }
  return out;
}

}  // namespace polyfloe::coupling
