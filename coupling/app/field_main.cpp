// polyfloe-field (also run as `polyfloe field ...`): OpenFOAM velocity -> ocean field files.
// Exit codes: 0 done, 2 bad input (arguments, case, file), 1 anything else.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <functional>
#include <iostream>
#include <optional>
#include <random>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

#include "field_args.h"
#include "field_vtk.h"
#include "forcing/gridded_field.h"
#include "formats/field_file.h"
#include "openfoam_case.h"
#include "probed_field.h"
#include "resample.h"

#ifndef POLYFLOE_VERSION
#define POLYFLOE_VERSION "unknown"
#endif

namespace {

using namespace polyfloe;
namespace fs = std::filesystem;
using coupling::app::Args;
using coupling::app::UsageError;

const char* kUsage = R"(polyfloe field: ocean currents from OpenFOAM for PolyFloe scenes.

Usage:
  polyfloe field import CASE -o FILE [options]   resample CASE's velocity U onto a grid: an ocean field file
                                                 (HDF5, FILE.h5) and FILE's .pvd series for ParaView; CASE is
                                                 the case folder (or its case.foam / system/controlDict)
  polyfloe field info FILE                       what a field file holds
  polyfloe field compare CASE FILE [options]     the gridding error: FILE's interpolation against probing
                                                 CASE's mesh directly, at random points in the water, and
                                                 against OpenFOAM's own cell values at the cell centres

Import options:
  -o, --output FILE       the field file to write (required), e.g. field.h5; FILE.pvd goes beside it
  --cell M|auto           grid spacing in x and y [m], > 0 (default auto: the mesh's finest horizontal
                          cell, which resolves what the mesh resolves; see docs/performance.md)
  --bounds X0,Y0,X1,Y1    the grid's extent [m] (default: the mesh's)
  --z Z1,Z2,...           levels [m], heights relative to the water surface (<= 0 in the water) spanning
                          the floe drafts (default -2,-1,-0.5,0); each must lie in the mesh (never clamped);
                          a 2-D case (one cell through the depth) keeps one
  --surface Z             the water surface's height in the case [m] (default: the top of the mesh)
  --max-nodes N           the most grid nodes (x * y * levels * times) to allocate (default 5e7: some 2.4 GB
                          in memory); a larger grid is refused with its size before anything is allocated
  --times WHICH           auto (default: the latest time of a steady case; every time of a transient one
                          but t = 0, its initial condition, when later times exist), all, latest, a list
                          T1,T2,... [s] of time directories, or a range A:B [s] (the time directories from
                          A to B; A: or :B leave an end open)
  --scale S|SX,SY,SZ      scale the mesh by S, or per axis [-] (> 0; default 1): e.g. 1000 to make a
                          tutorial's millimetre-sized geometry metres
  --rotate DEG            rotate the mesh and the velocities about the vertical z axis [degree],
                          counter-clockwise seen from above (default 0); after --scale
  --translate X,Y,Z       shift the mesh [m] (default 0,0,0); after --rotate. --bounds, --surface and the
                          levels are in the transformed coordinates
  --velocity-scale K      multiply the velocities by K [-] (default 1)
  --no-vtk                write no .pvd/.vtr series
Compare options (also --times, --surface and the transforms, as the import was made):
  --points N              random points per snapshot and level (default 20000)
  --seed S                random seed (default 1)

The file layout is in docs/scene-reference.md ("Field files"); a scene uses it with
  forcing: {ocean: {field: {type: file, path: FILE, outside: clamp}}}
Exit codes: 0 done, 2 bad input (arguments, case or file), 1 other failure.
)";

double wet_fraction(const forcing::GridData& g) {
  std::size_t wet = 0;
  for (const auto m : g.wet) wet += m;
  return static_cast<double>(wet) / static_cast<double>(g.wet.size());
}

double max_speed(const forcing::GridData& g) {
  double s = 0.0;
  for (std::size_t k = 0; k < g.u.size(); ++k) s = std::max(s, std::hypot(g.u[k], g.v[k]));
  return s;
}

// "0.5, 1, 1.5" (the first and last three of a long list).
std::string times_list(const std::vector<double>& t) {
  std::ostringstream os;
  for (std::size_t i = 0; i < t.size(); ++i) {
    if (t.size() > 8 && i == 3) {
      os << ", ... (" << t.size() << " times)";
      i = t.size() - 4;
      continue;
    }
    os << (i ? ", " : "") << t[i];
  }
  return os.str();
}

std::string axis_text(const std::vector<double>& a, const char* unit) {
  std::ostringstream os;
  os << a.size() << " from " << a.front() << " to " << a.back() << " " << unit;
  if (a.size() > 1 && a.size() <= 12) {
    os << " (";
    for (std::size_t i = 0; i < a.size(); ++i) os << (i ? ", " : "") << a[i];
    os << ")";
  }
  return os.str();
}

void describe(const io::FieldFile& f) {
  const forcing::GridData& g = f.grid;
  std::cout << "  x: " << axis_text(g.x, "m") << "\n  y: " << axis_text(g.y, "m") << "\n  z: " << axis_text(g.z, "m")
            << "\n  t: " << axis_text(g.t, "s") << (g.t.size() == 1 ? " (steady)" : "")
            << "\n  water: " << 100.0 * wet_fraction(g) << " % of the nodes; speed up to " << max_speed(g) << " m/s\n";
}

int import(const Args& a) {
  const auto t0 = std::chrono::steady_clock::now();
  const fs::path case_dir = a.positional[0];
  const bool steady = coupling::case_is_steady(case_dir);
  coupling::CaseNotes notes;
  const std::vector<coupling::MeshSnapshot> snaps =
      coupling::read_openfoam_case(case_dir, a.times, a.transform, &notes);
  // A long import says how far it is, every 2 s after the first 2 (stderr: the summary stays on stdout).
  auto last = std::chrono::steady_clock::now();
  const auto progress = [&](double done) {
    const auto now = std::chrono::steady_clock::now();
    if (now - last < std::chrono::seconds(2)) return;
    last = now;
    std::cerr << "polyfloe field: sampling the grid, " << static_cast<int>(100.0 * done) << " % after "
              << static_cast<int>(std::chrono::duration<double>(now - t0).count()) << " s\n";
  };
  io::FieldFile f =
      coupling::resample(snaps, a.grid, steady, fs::absolute(case_dir).lexically_normal().string(), progress);
  f.info.created_by = std::string("polyfloe field import ") + POLYFLOE_VERSION;
  io::write_field_file(a.output, f);
  std::size_t frames = 0;
  fs::path pvd = a.output;
  pvd.replace_extension(".pvd");
  if (a.vtk) frames = coupling::write_field_vtk(pvd, f);
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  const auto& b = snaps.front().bounds();
  std::cout << "Imported " << case_dir.string() << " (" << snaps.front().cells() << " cells, the finest "
            << snaps.front().min_cell_size() << " m across, " << (steady ? "steady" : "transient") << ", "
            << snaps.size() << " time(s)"
            << (notes.layout.decomposed
                    ? ", decomposed: read from " + std::to_string(notes.layout.processors) + " processor folders"
                    : std::string())
            << ") into " << a.output.string() << " in " << wall << " s:\n";
  std::cout << "  times read: " << times_list(notes.read) << " s of the case's " << times_list(notes.layout.times)
            << " s" << (notes.initial_skipped ? " (t = 0, the initial condition, left out; --times all keeps it)" : "")
            << "\n";
  if (notes.expanded)
    std::cout << "  VTK's reader could not parse the velocity files (#includeEtc, patch groups, ...): read from a "
                 "copy OpenFOAM wrote out plainly (postProcess -func 'writeObjects(U)')\n";
  if (!a.transform.identity())
    std::cout << "  transformed: scale " << a.transform.scale.transpose() << ", rotated " << a.transform.rotate
              << " degrees about z, shifted by " << a.transform.translate.transpose() << " m, velocities x "
              << a.transform.velocity_scale << "\n";
  std::cout << "  mesh: x " << b[0] << " to " << b[1] << " m, y " << b[2] << " to " << b[3] << " m, z " << b[4]
            << " to " << b[5] << " m"
            << (snaps.front().depth_averaged() ? " (one cell through the depth: a 2-D case)" : "")
            << "; water surface at z = " << a.grid.surface.value_or(b[5])
            << (a.grid.surface ? " m (--surface)\n" : " m (the top of the mesh; --surface to change)\n");
  if (!steady && snaps.size() == 1 && snaps.front().time() == 0.0)
    std::cout << "  note: the only velocity imported is t = 0, a transient case's initial condition, not a "
                 "solution: run the case first\n";
  describe(f);
  if (frames) std::cout << "  ParaView: " << pvd.string() << " (" << frames << " frame(s))\n";
  return 0;
}

int info(const Args& a) {
  const io::FieldFile f = io::read_field_file(a.positional[0]);
  std::cout << a.positional[0] << ": ocean field from " << (f.info.source.empty() ? "?" : f.info.source)
            << ", written by " << (f.info.created_by.empty() ? "?" : f.info.created_by) << "\n";
  describe(f);
  return 0;
}

// Differences between the grid and a reference velocity: RMS, largest, the reference's top speed, the count.
struct Differences {
  double sum2 = 0.0, max = 0.0, top = 0.0;
  long n = 0;
  void add(const forcing::Vec2& grid, const Eigen::Vector2d& reference) {
    const double e = (grid - reference).norm();
    sum2 += e * e;
    max = std::max(max, e);
    top = std::max(top, reference.norm());
    ++n;
  }
  double rms() const { return n ? std::sqrt(sum2 / static_cast<double>(n)) : 0.0; }
};

int compare(const Args& a) {
  const fs::path case_dir = a.positional[0], file = a.positional[1];
  const io::FieldFile f = io::read_field_file(file);
  const forcing::GridData& g = f.grid;
  auto snaps = std::make_shared<std::vector<coupling::MeshSnapshot>>(
      coupling::read_openfoam_case(case_dir, a.times, a.transform));
  if (snaps->size() != g.t.size())
    throw coupling::CouplingError(file.string() + " holds " + std::to_string(g.t.size()) + " snapshot(s), " +
                                  case_dir.string() + " " + std::to_string(snaps->size()) +
                                  " (choose the same with --times)");
  forcing::GriddedFieldOptions opt;
  opt.source = file.string();
  const forcing::GriddedField gridded(std::make_shared<const forcing::GridData>(g), opt);
  std::mt19937_64 rng(a.seed);
  std::uniform_real_distribution<double> ux(g.x.front(), g.x.back()), uy(g.y.front(), g.y.back());
  // The file's levels are heights below the water surface: the mesh is probed at surface + z, inside the mesh.
  const auto& mb = snaps->front().bounds();
  const double surface = a.grid.surface.value_or(mb[5]), inset = 1e-7 * std::max(1.0, mb[5] - mb[4]);
  std::cout << "Gridding error of " << file.string() << " against " << case_dir.string() << " (" << a.points
            << " random points in the water per snapshot and level):\n";
  double worst = 0.0;
  for (std::size_t it = 0; it < g.t.size(); ++it)
    for (const double z : g.z) {
      Differences d;
      const double t_file = g.t[it];
      for (long tries = 0; d.n < a.points && tries < 50 * a.points; ++tries) {
        const forcing::Vec3 p{ux(rng), uy(rng), z};
        Eigen::Vector3d ref3;
        if (!(*snaps)[it].sample({p.x(), p.y(), std::clamp(surface + z, mb[4] + inset, mb[5] - inset)}, ref3)) continue;
        forcing::Vec2 grid_u;
        try {
          grid_u = gridded.at(p, t_file);
        } catch (const forcing::FieldError&) {
          continue;  // in the mesh but not in the grid's water: the land mask's edge, measured separately
        }
        d.add(grid_u, ref3.head<2>());
      }
      worst = std::max(worst, d.max);
      std::cout << "  t = " << t_file << " s, z = " << z << " m: RMS " << d.rms() << " m/s, max " << d.max
                << " m/s (the speed reaches " << d.top << " m/s; " << d.n << " points)\n";
    }
  std::cout << "Largest difference: " << worst << " m/s\n";

  // The whole chain against OpenFOAM's own values: the grid at every cell centre in the water (at the level's
  // height, for cells whose depth holds the level) against the cell's value. This includes the reader's
  // cell-to-point interpolation, which the comparison above shares with the grid and so cannot see.
  if (!(*snaps)[0].has_cell_velocities()) return 0;
  std::cout << "Against OpenFOAM's cell values (cell centres in the grid's water):\n";
  double worst_cells = 0.0;
  for (std::size_t it = 0; it < g.t.size(); ++it) {
    const coupling::MeshSnapshot& s = (*snaps)[it];
    const bool flat = s.depth_averaged();
    for (const double z : g.z) {
      Differences d;
      for (std::size_t c = 0; c < s.cells(); ++c) {
        const Eigen::Vector2d zr = s.cell_z_range(c);
        if (!flat && !(surface + z >= zr[0] && surface + z <= zr[1])) continue;
        const Eigen::Vector3d centre = s.cell_centre(c), ref = s.cell_velocity(c);
        forcing::Vec2 grid_u;
        try {
          grid_u = gridded.at(forcing::Vec3{centre.x(), centre.y(), z}, g.t[it]);
        } catch (const forcing::FieldError&) {
          continue;  // outside the grid or beside land
        }
        d.add(grid_u, ref.head<2>());
      }
      worst_cells = std::max(worst_cells, d.max);
      std::cout << "  t = " << g.t[it] << " s, z = " << z << " m: RMS " << d.rms() << " m/s, max " << d.max
                << " m/s (the cells' speed reaches " << d.top << " m/s; " << d.n << " cells)\n";
    }
  }
  std::cout << "Largest difference from the cell values: " << worst_cells << " m/s\n";
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  // --help anywhere (polyfloe field import --help): the usage.
  if (std::any_of(argv + 1, argv + argc,
                  [](const char* x) { return std::string(x) == "--help" || std::string(x) == "-h"; })) {
    std::cout << kUsage;
    return 0;
  }
  Args a;
  try {
    a = coupling::app::parse(argc, argv);
  } catch (const UsageError& e) {
    std::cerr << "polyfloe field: " << e.what() << "\n\n" << kUsage;
    return 2;
  }
  try {
    if (a.command == "import") return import(a);
    if (a.command == "info") return info(a);
    return compare(a);
  } catch (const coupling::CouplingError& e) {
    std::cerr << "polyfloe field: error: " << e.what() << "\n";
    return 2;
  } catch (const io::FieldFileError& e) {
    std::cerr << "polyfloe field: error: " << e.what() << "\n";
    return 2;
  } catch (const std::exception& e) {
    std::cerr << "polyfloe field: error: " << e.what() << "\n";
    return 1;
  }
}
