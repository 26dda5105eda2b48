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
    all,        // every time directory with U, 0 included
    latest,     // the last one
    listed,     // `times`, each matched to a time directory within 1e-6 s
    range,      // every time directory in [times[0], times[1]] (OpenFOAM's -time A:B)
  };
  Kind kind = Kind::automatic;
  std::vector<double> times;
};

// The case's time directories that hold U, increasing [s]; throws CouplingError for a folder that is not a case,
// and for a decomposed case whose solution is only in processor*/ (naming reconstructPar as the fix).
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

  double time() const { return time_; }                    // [s]
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
  friend std::vector<MeshSnapshot> read_openfoam_case(const std::filesystem::path&, const TimeSelection&);
  struct Impl;
  std::unique_ptr<Impl> impl_;
  double time_ = 0.0;
  Eigen::Matrix<double, 6, 1> bounds_ = Eigen::Matrix<double, 6, 1>::Zero();
};

// Reads U on the internal mesh at the selected times (patches and every other field are not read). Throws
// CouplingError naming the case and the problem: no such folder, no system/controlDict, no mesh, no U, a listed
// time that is not there.
std::vector<MeshSnapshot> read_openfoam_case(const std::filesystem::path& case_dir, const TimeSelection& which);

}  // namespace polyfloe::coupling
