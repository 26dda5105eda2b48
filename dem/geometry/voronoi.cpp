#include "geometry/voronoi.h"

#include <boost/polygon/voronoi.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>

namespace polyfloe::geometry {

namespace {

using IPoint = boost::polygon::point_data<std::int32_t>;
constexpr double kGrid = 268435456.0;  // 2^28 cells across the box's larger side; mirrors stay within int32

}  // namespace

std::vector<std::vector<Vec2>> voronoi_cells(std::span<const Vec2> sites, const Aabb& box) {
  const Vec2 size = box.hi - box.lo;
  if (!(size.x() > 0.0) || !(size.y() > 0.0) || !size.allFinite())
    throw VoronoiError("voronoi_cells: the box must have positive, finite width and height");
  const double step = std::max(size.x(), size.y()) / kGrid;  // [m] per integer unit
  const auto nx = static_cast<std::int64_t>(std::llround(size.x() / step));
  const auto ny = static_cast<std::int64_t>(std::llround(size.y() / step));
  // Snapped sites; the box in integer units is [0, nx] x [0, ny], mapped exactly with a scale per axis.
  const double sx = size.x() / static_cast<double>(nx), sy = size.y() / static_cast<double>(ny);
  std::vector<IPoint> pts;
  pts.reserve(5 * sites.size());
  for (std::size_t i = 0; i < sites.size(); ++i) {
    const Vec2 q{(sites[i].x() - box.lo.x()) / sx, (sites[i].y() - box.lo.y()) / sy};
    if (!(q.x() > 0.0 && q.y() > 0.0 && q.x() < static_cast<double>(nx) && q.y() < static_cast<double>(ny)))
      throw VoronoiError("voronoi_cells: site " + std::to_string(i) + " is not strictly inside the box");
    pts.emplace_back(static_cast<std::int32_t>(std::llround(q.x())), static_cast<std::int32_t>(std::llround(q.y())));
  }
  {
    std::vector<std::pair<std::int64_t, std::size_t>> keys;
    keys.reserve(pts.size());
    for (std::size_t i = 0; i < pts.size(); ++i) keys.emplace_back((std::int64_t(pts[i].x()) << 32) | pts[i].y(), i);
    std::sort(keys.begin(), keys.end());
    for (std::size_t k = 1; k < keys.size(); ++k)
      if (keys[k].first == keys[k - 1].first)
        throw VoronoiError("voronoi_cells: sites " + std::to_string(keys[k - 1].second) + " and " +
                           std::to_string(keys[k].second) + " coincide (closer than " + std::to_string(step) + " m)");
  }
  const std::size_t n = pts.size();
  for (std::size_t i = 0; i < n; ++i) {  // mirrors across x = 0, x = nx, y = 0, y = ny
    const std::int64_t x = pts[i].x(), y = pts[i].y();
    pts.emplace_back(static_cast<std::int32_t>(-x), static_cast<std::int32_t>(y));
    pts.emplace_back(static_cast<std::int32_t>(2 * nx - x), static_cast<std::int32_t>(y));
    pts.emplace_back(static_cast<std::int32_t>(x), static_cast<std::int32_t>(-y));
    pts.emplace_back(static_cast<std::int32_t>(x), static_cast<std::int32_t>(2 * ny - y));
  }
  boost::polygon::voronoi_diagram<double> vd;
  boost::polygon::construct_voronoi(pts.begin(), pts.end(), &vd);

  std::vector<std::vector<Vec2>> cells(n);
  for (const auto& cell : vd.cells()) {
    const std::size_t site = cell.source_index();
    if (site >= n) continue;  // a mirror
    const auto* e0 = cell.incident_edge();
    const auto* e = e0;
    std::vector<Vec2>& out = cells[site];
    do {
      // Every edge of an inside site's cell is finite (the mirrors enclose it).
      if (!e->is_primary() || e->vertex0() == nullptr)
        throw VoronoiError("voronoi_cells: unbounded cell for site " + std::to_string(site));
      out.emplace_back(box.lo.x() + e->vertex0()->x() * sx, box.lo.y() + e->vertex0()->y() * sy);
      e = e->next();
    } while (e != e0);
    // Boost walks cell boundaries counter-clockwise; drop repeated vertices (degenerate, zero-length edges).
    std::vector<Vec2> clean;
    for (const Vec2& v : out)
      if (clean.empty() || (v - clean.back()).norm() > 1e-9 * step * kGrid) clean.push_back(v);
    while (clean.size() > 1 && (clean.front() - clean.back()).norm() <= 1e-9 * step * kGrid) clean.pop_back();
    out.swap(clean);
  }
  return cells;
}

}  // namespace polyfloe::geometry
