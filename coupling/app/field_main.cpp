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

class UsageError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

std::vector<double> numbers(const std::string& opt, const std::string& text) {
  std::vector<double> v;
  std::stringstream ss(text);
  std::string item;
  while (std::getline(ss, item, ',')) {
    char* end = nullptr;
    const double x = std::strtod(item.c_str(), &end);
    if (item.empty() || *end != '\0' || !std::isfinite(x))
      throw UsageError(opt + ": expected numbers separated by commas, got '" + text + "'");
    v.push_back(x);
  }
  if (v.empty()) throw UsageError(opt + ": expected numbers separated by commas, got '" + text + "'");
  return v;
}

struct Args {
  std::string command;
  std::vector<std::string> positional;
  fs::path output;
  coupling::GridSpec grid;
  coupling::TimeSelection times;
  coupling::CaseTransform transform;
  bool vtk = true;
  long points = 20000;
  unsigned seed = 1;
};

// --times W: auto, all, latest, A:B (either end open) or a list of times [s].
coupling::TimeSelection parse_times(const std::string& o, const std::string& w) {
  using K = coupling::TimeSelection::Kind;
  coupling::TimeSelection t;
  if (w == "auto") {
    t.kind = K::automatic;
  } else if (w == "all") {
    t.kind = K::all;
  } else if (w == "latest") {
    t.kind = K::latest;
  } else if (const std::size_t colon = w.find(':'); colon != std::string::npos) {  // A:B, either end open
    t.kind = K::range;
    const std::string lo = w.substr(0, colon), hi = w.substr(colon + 1);
    t.times = {lo.empty() ? -std::numeric_limits<double>::infinity() : numbers(o, lo).at(0),
               hi.empty() ? std::numeric_limits<double>::infinity() : numbers(o, hi).at(0)};
    if (!(t.times[1] >= t.times[0]) || hi.find(',') != std::string::npos)
      throw UsageError("--times: a range is A:B with A <= B [s] (either end may be left out), got '" + w + "'");
  } else {
    t.kind = K::listed;
    t.times = numbers(o, w);
  }
  return t;
}

// The grid's options (--cell, --bounds, --z, --max-nodes, --surface) into g; false for any other option.
bool grid_option(const std::string& o, const std::function<std::string()>& value, coupling::GridSpec& g) {
  if (o == "--cell") {
    const std::string w = value();
    if (w == "auto") {
      g.cell = 0.0;
      return true;
    }
    const std::vector<double> c = numbers(o, w);
    if (c.size() != 1 || !(c[0] > 0.0)) throw UsageError("--cell: expected one spacing > 0 m");
    g.cell = c[0];
  } else if (o == "--bounds") {
    const std::vector<double> b = numbers(o, value());
    if (b.size() != 4 || !(b[2] > b[0]) || !(b[3] > b[1]))
      throw UsageError("--bounds: expected X0,Y0,X1,Y1 [m] with X1 > X0 and Y1 > Y0");
    g.bounds = Eigen::Vector4d(b[0], b[1], b[2], b[3]);
  } else if (o == "--z") {
    g.z = numbers(o, value());
  } else if (o == "--max-nodes") {
    const std::vector<double> n = numbers(o, value());
    if (n.size() != 1 || !(n[0] >= 1.0) || n[0] > 1e10) throw UsageError("--max-nodes: expected a count in [1, 1e10]");
    g.max_nodes = n[0];
  } else if (o == "--surface") {
    const std::vector<double> z = numbers(o, value());
    if (z.size() != 1) throw UsageError("--surface: expected one height [m]");
    g.surface = z[0];
  } else {
    return false;
  }
  return true;
}

// The case's transform (--scale, --rotate, --translate, --velocity-scale) into t; false for any other option.
bool transform_option(const std::string& o, const std::function<std::string()>& value, coupling::CaseTransform& t) {
  if (o == "--scale") {
    const std::vector<double> k = numbers(o, value());
    if ((k.size() != 1 && k.size() != 3) ||
        std::any_of(k.begin(), k.end(), [](double x) { return !(x > 0.0) || x > 1e9; }))
      throw UsageError("--scale: expected one factor S or three SX,SY,SZ, each in (0, 1e9]");
    t.scale = k.size() == 1 ? Eigen::Vector3d::Constant(k[0]) : Eigen::Vector3d(k[0], k[1], k[2]);
  } else if (o == "--rotate") {
    const std::vector<double> d = numbers(o, value());
    if (d.size() != 1 || std::abs(d[0]) > 360.0)
      throw UsageError("--rotate: expected one angle in [-360, 360] degrees");
    t.rotate = d[0];
  } else if (o == "--translate") {
    const std::vector<double> d = numbers(o, value());
    if (d.size() != 3 || std::any_of(d.begin(), d.end(), [](double x) { return std::abs(x) > 1e9; }))
      throw UsageError("--translate: expected X,Y,Z [m], each within 1e9 m");
    t.translate = Eigen::Vector3d(d[0], d[1], d[2]);
  } else if (o == "--velocity-scale") {
    const std::vector<double> k = numbers(o, value());
    if (k.size() != 1 || !(k[0] > 0.0) || k[0] > 1e6)
      throw UsageError("--velocity-scale: expected one factor in (0, 1e6]");
    t.velocity_scale = k[0];
  } else {
    return false;
  }
  return true;
}

// The arguments a command takes, and import's output file, checked before any (long) work; the case given as its
// folder.
void check_arguments(Args& a) {
  const std::size_t want = a.command == "compare" ? 2 : 1;
  if (a.positional.size() != want)
    throw UsageError(a.command + " takes " +
                     (want == 2             ? "CASE FILE"
                      : a.command == "info" ? "FILE"
                                            : "CASE") +
                     ", got " + std::to_string(a.positional.size()) + " argument(s)");
  if (a.command == "import" && a.output.empty()) throw UsageError("import needs -o FILE");
  if (a.command == "import") {
    // Checked before the (long) import: the file is HDF5 (.h5), its .pvd and .vtr frames go beside it.
    const std::string ext = a.output.extension().string();
    if (ext != ".h5" && ext != ".hdf5")
      throw UsageError("-o " + a.output.string() +
                       ": a field file is HDF5, named FILE.h5 (its ParaView series "
                       "FILE.pvd and FILE/ go beside it), got the extension '" +
                       ext + "'");
    std::error_code ec;
    const fs::path parent = fs::absolute(a.output, ec).parent_path();
    if (!fs::is_directory(parent, ec))
      throw UsageError("-o " + a.output.string() + ": the folder " + parent.string() + " does not exist");
    if (fs::is_directory(a.output, ec)) throw UsageError("-o " + a.output.string() + ": a folder, not a file name");
  }
  // The case may be given as its folder, or as a file in it that names it for ParaView (CASE/case.foam, any
  // *.foam) or its system/controlDict.
  if (a.command != "info" && !a.positional.empty()) {
    fs::path c = a.positional[0];
    std::error_code ec;
    if (c.extension() == ".foam" && !fs::is_directory(c, ec))
      c = c.parent_path();
    else if (c.filename() == "controlDict" && c.parent_path().filename() == "system")
      c = c.parent_path().parent_path();
    a.positional[0] = c.empty() ? "." : c.string();
  }
}

Args parse(int argc, char** argv) {
  Args a;
  std::vector<std::string> v(argv + 1, argv + argc);
  if (v.empty()) throw UsageError("no command given");
  a.command = v[0];
  if (a.command != "import" && a.command != "info" && a.command != "compare")
    throw UsageError("unknown command '" + a.command + "' (import, info, compare)");
  for (std::size_t i = 1; i < v.size(); ++i) {
    const std::string& o = v[i];
    const std::function<std::string()> value = [&]() -> std::string {
      if (i + 1 >= v.size()) throw UsageError(o + " needs a value");
      return v[++i];
    };
    if (grid_option(o, value, a.grid) || transform_option(o, value, a.transform)) continue;
    if (o == "-o" || o == "--output") {
      a.output = value();
    } else if (o == "--times") {
      a.times = parse_times(o, value());
    } else if (o == "--no-vtk") {
      a.vtk = false;
    } else if (o == "--points") {
      const std::vector<double> n = numbers(o, value());
      if (n.size() != 1 || !(n[0] >= 1.0) || n[0] > 1e8 || n[0] != std::floor(n[0]))
        throw UsageError("--points: expected a whole number in [1, 1e8]");
      a.points = static_cast<long>(n[0]);
    } else if (o == "--seed") {
      const std::vector<double> n = numbers(o, value());
      if (n.size() != 1 || n[0] < 0 || n[0] > 4e9 || n[0] != std::floor(n[0]))
        throw UsageError("--seed: expected a whole number in [0, 4e9]");
      a.seed = static_cast<unsigned>(n[0]);
    } else if (o == "-h" || o == "--help") {
      std::cout << kUsage;
      std::exit(0);
    } else if (!o.empty() && o[0] == '-') {
      throw UsageError("unknown option '" + o + "'");
    } else {
      a.positional.push_back(o);
    }
  }
  check_arguments(a);
  return a;
}

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
  if (argc >= 2 && (std::string(argv[1]) == "--help" || std::string(argv[1]) == "-h")) {
    std::cout << kUsage;
    return 0;
  }
  Args a;
  try {
    a = parse(argc, argv);
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
