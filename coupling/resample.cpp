#include "resample.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <sstream>

namespace polyfloe::coupling {

namespace {

// Nodes from a to b at spacing h, the last one at or beyond b.
std::vector<double> nodes(double a, double b, double h) {
  const std::size_t n = static_cast<std::size_t>(std::ceil((b - a) / h - 1e-9)) + 1;
  std::vector<double> v(std::max<std::size_t>(n, 2));
  for (std::size_t i = 0; i < v.size(); ++i) v[i] = a + h * static_cast<double>(i);
  return v;
}

}  // namespace

std::string grid_spec_error(const GridSpec& g) {
  if (!(g.cell >= 0.0) || !std::isfinite(g.cell)) return "the cell size must be > 0 m (or 0: the mesh's finest cell)";
  if (g.bounds) {
    const Eigen::Vector4d& b = *g.bounds;
    if (!b.allFinite() || !(b[2] > b[0]) || !(b[3] > b[1]))
      return "the bounds must be x0, y0, x1, y1 with x1 > x0 and y1 > y0";
    if ((b[2] - b[0]) / g.cell > 1e5 || (b[3] - b[1]) / g.cell > 1e5) return "more than 100,000 nodes along an axis";
  }
  if (g.z.empty()) return "no z level";
  for (const double z : g.z)
    if (!std::isfinite(z)) return "the z levels must be finite";
  return {};
}

namespace {

// The node count (and so the memory and the file) estimated before anything is allocated: a graded mesh's finest
// cell (the automatic spacing) or a spacing in the wrong unit asks for billions of nodes. Throws CouplingError.
void check_node_count(const std::vector<MeshSnapshot>& snapshots, const GridSpec& spec, const Eigen::Vector4d& b,
                      double cell, const std::string& source) {
  const double nx = std::max(2.0, std::ceil((b[2] - b[0]) / cell - 1e-9) + 1.0);
  const double ny = std::max(2.0, std::ceil((b[3] - b[1]) / cell - 1e-9) + 1.0);
  // A 2-D case (one cell through the depth) is sampled at one level whatever --z lists.
  const double levels = snapshots.front().depth_averaged() ? 1.0 : static_cast<double>(spec.z.size());
  const double total = nx * ny * levels * static_cast<double>(snapshots.size());
  if (total <= spec.max_nodes) return;
  std::ostringstream why;
  why << source << ": a grid of " << nx << " x " << ny << " nodes at " << cell << " m spacing"
      << (spec.cell > 0.0 ? "" : " (the mesh's finest cell)") << ", x " << levels << " level(s) x " << snapshots.size()
      << " time(s) is " << total << " nodes, about " << std::ceil(total * 48.0 / 1048576.0) << " MiB in memory and "
      << std::ceil(total * 24.0 / 1048576.0) << " MiB of velocities in the file (at most " << spec.max_nodes
      << " nodes): choose a larger --cell (" << cell * std::sqrt(total / spec.max_nodes)
      << " m fits), smaller --bounds, fewer --z levels or --times, or allow it with --max-nodes N";
  throw CouplingError(why.str());
}

// The grid's levels, heights below the water surface `surface`, sorted and without repeats; a level outside the
// mesh's depth [zlo, zhi] is refused (clamped, it would take the seabed's, or the lid's, velocity for the
// surface's). A 2-D case (`flat`) has one velocity through its depth: any level samples it, one is kept.
std::vector<double> grid_levels(const GridSpec& spec, double surface, double zlo, double zhi, bool flat,
                                const std::string& source) {
  const double tol = 1e-9 * std::max(1.0, std::abs(zhi) + std::abs(zlo));
  if (!std::isfinite(surface)) throw CouplingError(source + ": the water surface must be a finite z [m]");
  std::vector<double> levels;
  for (const double z : spec.z) {
    if (!flat && (surface + z < zlo - tol || surface + z > zhi + tol)) {
      std::ostringstream why;
      why << source << ": level " << z << " m lies at z = " << surface + z << " m, outside the mesh's depth [" << zlo
          << ", " << zhi << "] m (the water surface taken at z = " << surface
          << (spec.surface ? " m, --surface" : " m, the top of the mesh") << "); give levels from " << zlo - surface
          << " to " << zhi - surface << " m (--z), or the surface (--surface Z)";
      throw CouplingError(why.str());
    }
    levels.push_back(z);
  }
  std::sort(levels.begin(), levels.end());
  levels.erase(std::unique(levels.begin(), levels.end(), [](double a, double c) { return std::abs(a - c) < 1e-9; }),
               levels.end());
  if (flat) levels = {levels.back()};  // one velocity through the depth: one level, stored under the top one's height
  return levels;
}

// Samples every node of every snapshot at the height surface + level, clamped to [z_lo, z_hi]: the velocity where
// the mesh has a cell, the node marked wet.
void sample_nodes(const std::vector<MeshSnapshot>& snapshots, double surface, double z_lo, double z_hi,
                  const std::function<void(double)>& progress, io::FieldFile& f) {
  forcing::GridData& g = f.grid;
  const std::size_t per = g.nodes_per_snapshot();
  g.u.assign(per * g.t.size(), 0.0);
  g.v.assign(g.u.size(), 0.0);
  f.w.assign(g.u.size(), 0.0);
  g.wet.assign(per, 0);
  Eigen::Vector3d u;
  const double rows = static_cast<double>(snapshots.size() * g.z.size() * g.y.size());
  double row = 0.0;
  for (std::size_t it = 0; it < snapshots.size(); ++it)
    for (std::size_t iz = 0; iz < g.z.size(); ++iz)
      for (std::size_t iy = 0; iy < g.y.size(); ++iy, ++row) {
        if (progress) progress(row / rows);
        for (std::size_t ix = 0; ix < g.x.size(); ++ix) {
          if (!snapshots[it].sample({g.x[ix], g.y[iy], std::clamp(surface + g.z[iz], z_lo, z_hi)}, u)) continue;
          const std::size_t k = g.index(it, iz, iy, ix);
          g.u[k] = u.x();
          g.v[k] = u.y();
          f.w[k] = u.z();
          g.wet[k % per] = 1;
        }
      }
}

// A depth-averaged (2-D) case has the same velocity at every level (to the rounding of the interpolation through
// the one cell's depth): keep one, level 0's values under the top level's height.
void keep_one_level_if_all_same(io::FieldFile& f) {
  forcing::GridData& g = f.grid;
  double top = 0.0;
  for (std::size_t k = 0; k < g.u.size(); ++k) top = std::max(top, std::hypot(g.u[k], g.v[k]));
  const double same_tol = 1e-9 * std::max(top, 1e-30);
  bool same = g.z.size() > 1;
  const std::size_t nxy = g.x.size() * g.y.size();
  for (std::size_t it = 0; same && it < g.t.size(); ++it)
    for (std::size_t iz = 1; same && iz < g.z.size(); ++iz)
      for (std::size_t k = 0; same && k < nxy; ++k) {
        const std::size_t a = g.index(it, 0, 0, 0) + k, c = g.index(it, iz, 0, 0) + k;
        same = std::abs(g.u[a] - g.u[c]) <= same_tol && std::abs(g.v[a] - g.v[c]) <= same_tol &&
               g.wet[k] == g.wet[iz * nxy + k];
      }
  if (!same) return;
  // In place: snapshot it's level-0 block moves to block it of the one-level layout (it * nxy <= it * per_level:
  // no overlap ahead).
  const std::size_t per_level = g.nodes_per_snapshot();
  const auto first_level_only = [&](std::vector<double>& a) {
    for (std::size_t it = 0; it < g.t.size(); ++it)
      std::copy_n(a.begin() + static_cast<std::ptrdiff_t>(it * per_level), nxy,
                  a.begin() + static_cast<std::ptrdiff_t>(it * nxy));
    a.resize(g.t.size() * nxy);
  };
  first_level_only(g.u);
  first_level_only(g.v);
  first_level_only(f.w);
  g.wet.resize(nxy);
  g.z = {g.z.back()};
}

}  // namespace

io::FieldFile resample(const std::vector<MeshSnapshot>& snapshots, const GridSpec& spec, bool steady,
                       const std::string& source, const std::function<void(double)>& progress) {
  if (std::string e = grid_spec_error(spec); !e.empty()) throw CouplingError(source + ": " + e);
  if (snapshots.empty()) throw CouplingError(source + ": no snapshot to resample");
  const auto& mb = snapshots.front().bounds();
  const Eigen::Vector4d b = spec.bounds.value_or(Eigen::Vector4d(mb[0], mb[2], mb[1], mb[3]));
  const double cell = spec.cell > 0.0 ? spec.cell : snapshots.front().min_cell_size();
  if (!(cell > 0.0)) throw CouplingError(source + ": the mesh has cells of no horizontal extent; give the cell size");
  if ((b[2] - b[0]) / cell > 1e5 || (b[3] - b[1]) / cell > 1e5)
    throw CouplingError(source + ": more than 100,000 nodes along an axis; choose a larger cell");
  check_node_count(snapshots, spec, b, cell, source);

  io::FieldFile f;
  forcing::GridData& g = f.grid;
  g.x = nodes(b[0], b[2], cell);
  g.y = nodes(b[1], b[3], cell);
  // Levels are heights below the water surface (the mesh's top unless given): level L is sampled at surface + L,
  // a hair inside the mesh's top and bottom faces so that the locator finds a cell on the surface itself.
  const double zlo = mb[4], zhi = mb[5], inset = 1e-7 * std::max(1.0, zhi - zlo);
  const double surface = spec.surface.value_or(zhi);
  g.z = grid_levels(spec, surface, zlo, zhi, snapshots.front().depth_averaged(), source);
  for (const MeshSnapshot& s : snapshots) g.t.push_back(steady && snapshots.size() == 1 ? 0.0 : s.time());
  sample_nodes(snapshots, surface, zlo + inset, zhi - inset, progress, f);
  keep_one_level_if_all_same(f);
  f.info.source = source;
  return f;
}

}  // namespace polyfloe::coupling
