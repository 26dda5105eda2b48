// Reading an OpenFOAM case's velocity with VTK's vtkOpenFOAMReader (no OpenFOAM needed to read): the internal mesh
// at each chosen time, with U, and a cell locator that samples it anywhere. VTK stays behind this header.
#pragma once

#include <Eigen/Core>
#include <filesystem>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

namespace polyfloe::coupling {

// A case that cannot be read: the message names the case folder and the problem.
class CouplingError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Which time directories to read.
struct TimeSelection {
  enum class Kind {
    automatic,  // steady cases (fvSchemes ddtSchemes steadyState): the latest time; transient cases: every time
                // but t = 0 (the initial condition) when later times exist
    all,        // every time directory with U, 0 included
    latest,     // the last one
    listed,     // `times`, each matched to a time directory within 1e-6 s
    range,      // every time directory in [times[0], times[1]] (OpenFOAM's -time A:B)
  };
  Kind kind = Kind::automatic;
  std::vector<double> times;
};

// Where a case keeps its solution. A decomposed case (decomposePar, then a solver run with -parallel) writes it
// into processor0/, processor1/, ... only: its own time directories hold the initial condition at most. It is read
// decomposed (every processor's cells) when processor0/ holds a later time with U than the case itself.
struct CaseLayout {
  bool decomposed = false;
  int processors = 0;              // processor*/ folders read (decomposed cases)
  std::vector<double> times;       // the time directories with U, increasing [s]
  std::vector<std::string> names;  // those directories' names as written ("0.5", "1e-05")
};
// Throws CouplingError for a folder that is not a case, or a case with no U anywhere.
CaseLayout case_layout(const std::filesystem::path& case_dir);
// The case's time directories that hold U, increasing [s] (case_layout's times).
std::vector<double> case_times(const std::filesystem::path& case_dir);
// True when the case's fvSchemes says ddtSchemes default steadyState (simpleFoam and friends).
bool case_is_steady(const std::filesystem::path& case_dir);

// One snapshot: U on the internal mesh (point values, which VTK's reader interpolates from OpenFOAM's cell values)
// and a static cell locator. sample() interpolates within the cell that holds p with the cell's own shape functions
// (trilinear on hexahedra): a continuous field, the reference the gridded file is measured against.
class MeshSnapshot {
 public:
  MeshSnapshot();
  ~MeshSnapshot();
  MeshSnapshot(MeshSnapshot&&) noexcept;
  MeshSnapshot& operator=(MeshSnapshot&&) noexcept;

  double time() const { return time_; }                                  // [s]
  const Eigen::Matrix<double, 6, 1>& bounds() const { return bounds_; }  // xmin, xmax, ymin, ymax, zmin, zmax [m]
  std::size_t cells() const;
  // Cell c's parametric centre [m], OpenFOAM's own velocity there [m/s] (zero when the reader gave no cell values)
  // and the cell's z extent [m]: the reference the gridding chain (cell -> point -> grid) is measured against.
  Eigen::Vector3d cell_centre(std::size_t c) const;
  Eigen::Vector3d cell_velocity(std::size_t c) const;
  Eigen::Vector2d cell_z_range(std::size_t c) const;
  bool has_cell_velocities() const;
  // The smallest horizontal extent (x or y) of a cell's bounding box [m]: the finest detail the mesh resolves.
  double min_cell_size() const;
  // True when every cell spans the mesh's whole depth: a 2-D case (one cell through the depth, OpenFOAM's `empty`
  // front and back), whose velocity is the same at every depth.
  bool depth_averaged() const;
  // U at p [m/s] into u; false where p is farther than the locator tolerance (1e-9 of the mesh diagonal) from
  // every cell. Safe to call from several threads at once (each thread keeps its own VTK cell and weights).
  bool sample(const Eigen::Vector3d& p, Eigen::Vector3d& u) const;

 private:
  friend struct SnapshotBuilder;
  struct Impl;
  std::unique_ptr<Impl> impl_;
  double time_ = 0.0;
  Eigen::Matrix<double, 6, 1> bounds_ = Eigen::Matrix<double, 6, 1>::Zero();
};

// The selected times among the layout's (which.kind automatic needs `steady`); throws CouplingError naming the case
// for a listed time that is not there or an empty range.
std::vector<double> choose_times(const std::filesystem::path& case_dir, const CaseLayout& layout,
                                 const TimeSelection& which, bool steady);

// A rigid placement and scaling of the case, applied as it is read: a mesh point p becomes R(rotate) (scale o p) +
// translate (scale per axis, then the rotation about the vertical z axis, counter-clockwise seen from above, then
// the shift), a velocity u becomes velocity_scale R u.
struct CaseTransform {
  Eigen::Vector3d scale = Eigen::Vector3d::Ones();      // [-], > 0
  double rotate = 0.0;                                  // [degree] about z
  Eigen::Vector3d translate = Eigen::Vector3d::Zero();  // [m]
  double velocity_scale = 1.0;                          // [-]
  bool identity() const;
};

// What reading a case found, for the summary a user reads.
struct CaseNotes {
  CaseLayout layout;
  std::vector<double> read;      // the times read [s]
  bool initial_skipped = false;  // t = 0 left out by the automatic choice of a transient case
  bool expanded = false;         // the velocity files were written out plainly by OpenFOAM for VTK's reader
};

// Reads U on the internal mesh at the selected times (patches and every other field are not read), decomposed cases
// from their processor*/ folders. Velocity files VTK's reader cannot parse (directives such as #includeEtc or
// #calc, patch-group entries) are written out plainly by OpenFOAM (`postProcess -func 'writeObjects(U)'`) into a
// scratch copy when OpenFOAM is installed. Throws
// CouplingError naming the case and the problem: no such folder, no system/controlDict, no mesh, no U, a listed
// time that is not there, a directive with no OpenFOAM to expand it (naming the file and the fix).
std::vector<MeshSnapshot> read_openfoam_case(const std::filesystem::path& case_dir, const TimeSelection& which,
                                             const CaseTransform& transform = {}, CaseNotes* notes = nullptr);

}  // namespace polyfloe::coupling
