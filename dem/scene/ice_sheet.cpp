#include "scene/ice_sheet.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <set>
#include <memory>
#include <numbers>
#include <sstream>

#include "geometry/voronoi.h"
#include "scene/floe_field.h"

namespace polyfloe::scene {

namespace {

std::string prefix(const IceSheetSpec& spec) {
  return (spec.source.where.empty() ? std::string() : spec.source.where + ": ") + "ice_sheet: ";
}

// Collapses the edges of a tiling shorter than `shortest` (shortest first), keeping it a tiling: an edge's two
// vertices become one, at the edge's midpoint, in every cell that has either (a vertex on the region's boundary
// stays where it is; an edge along the boundary is kept), and only when every cell touched stays strictly convex.
// Poisson-Voronoi cells have edges down to a millionth of their size; elements that small would need time steps as
// small (their mass falls with their size, their bond stiffness does not).
void collapse_short_edges(std::vector<std::vector<Vec2>>& cells, const geometry::Aabb& box, double shortest) {
  // Shared vertices: the cells of a Voronoi tiling carry bit-identical copies of each vertex.
  std::map<std::pair<double, double>, int> ids;
  std::vector<Vec2> pos;
  std::vector<std::vector<int>> cell_ids(cells.size());
  for (std::size_t k = 0; k < cells.size(); ++k) {
    for (const Vec2& v : cells[k]) {
      const auto [it, fresh] = ids.emplace(std::make_pair(v.x(), v.y()), static_cast<int>(pos.size()));
      if (fresh) pos.push_back(v);
      cell_ids[k].push_back(it->second);
    }
  }
  std::vector<std::vector<int>> vertex_cells(pos.size());
  for (std::size_t k = 0; k < cell_ids.size(); ++k)
    for (int v : cell_ids[k]) vertex_cells[static_cast<std::size_t>(v)].push_back(static_cast<int>(k));
  const double tol = 1e-9 * (box.hi - box.lo).maxCoeff();
  auto on_boundary = [&](int v) {
    const Vec2& p = pos[static_cast<std::size_t>(v)];
    return p.x() <= box.lo.x() + tol || p.x() >= box.hi.x() - tol || p.y() <= box.lo.y() + tol ||
           p.y() >= box.hi.y() - tol;
  };
  std::vector<std::pair<double, std::pair<int, int>>> edges;
  for (const auto& c : cell_ids) {
    for (std::size_t j = 0; j < c.size(); ++j) {
      const int a = c[j], b = c[(j + 1) % c.size()];
      if (a < b)
        edges.push_back({(pos[static_cast<std::size_t>(a)] - pos[static_cast<std::size_t>(b)]).norm(), {a, b}});
    }
  }
  std::sort(edges.begin(), edges.end());
  std::vector<std::uint8_t> alive(pos.size(), 1);
  for (const auto& [length0, ab] : edges) {
    if (length0 >= shortest) break;
    const auto [a, b] = ab;
    if (!alive[static_cast<std::size_t>(a)] || !alive[static_cast<std::size_t>(b)]) continue;
    const bool ba = on_boundary(a), bb = on_boundary(b);
    if (ba && bb) continue;
    const Vec2 target = ba   ? pos[static_cast<std::size_t>(a)]
                        : bb ? pos[static_cast<std::size_t>(b)]
                             : 0.5 * (pos[static_cast<std::size_t>(a)] + pos[static_cast<std::size_t>(b)]);
    if ((pos[static_cast<std::size_t>(a)] - pos[static_cast<std::size_t>(b)]).norm() >= shortest) continue;
    // Every cell with a or b, rebuilt with b merged into a at the target: all must stay strictly convex.
    std::vector<int> touched = vertex_cells[static_cast<std::size_t>(a)];
    for (int k : vertex_cells[static_cast<std::size_t>(b)])
      if (std::find(touched.begin(), touched.end(), k) == touched.end()) touched.push_back(k);
    std::vector<std::vector<int>> rebuilt;
    bool ok = true;
    for (int k : touched) {
      std::vector<int> c;
      for (int v : cell_ids[static_cast<std::size_t>(k)]) {
        const int w = v == b ? a : v;
        if (c.empty() || c.back() != w) c.push_back(w);
      }
      while (c.size() > 1 && c.front() == c.back()) c.pop_back();
      std::vector<Vec2> xy;
      for (int v : c) xy.push_back(v == a ? target : pos[static_cast<std::size_t>(v)]);
      if (c.size() < 3 || !geometry::convexity_error(xy).empty()) {
        ok = false;
        break;
      }
      rebuilt.push_back(std::move(c));
    }
    if (!ok) continue;
    pos[static_cast<std::size_t>(a)] = target;
    alive[static_cast<std::size_t>(b)] = 0;
    for (std::size_t t = 0; t < touched.size(); ++t) cell_ids[static_cast<std::size_t>(touched[t])] = rebuilt[t];
    vertex_cells[static_cast<std::size_t>(a)] = touched;
  }
  for (std::size_t k = 0; k < cells.size(); ++k) {
    cells[k].clear();
    for (int v : cell_ids[k]) cells[k].push_back(pos[static_cast<std::size_t>(v)]);
  }
}

}  // namespace

std::vector<std::vector<Vec2>> voronoi_sheet(const IceSheetSpec& spec) {
  const Vec2 lo = spec.region_min, hi = spec.region_max;
  if (!(hi.x() > lo.x()) || !(hi.y() > lo.y()) || !lo.allFinite() || !hi.allFinite())
    throw SceneError(prefix(spec) + "region must have xmax > xmin and ymax > ymin");
  if (!(spec.cell_size > 0.0) || !std::isfinite(spec.cell_size))
    throw SceneError(prefix(spec) + "cell_size must be positive");
  if (spec.relaxation < 0) throw SceneError(prefix(spec) + "relaxation must be >= 0");
  const double area = (hi - lo).prod();
  const double cells = std::max(1.0, std::round(area / (0.25 * std::numbers::pi * spec.cell_size * spec.cell_size)));
  if (cells > IceSheetSpec::kMaxCells) {
    std::ostringstream msg;
    msg << prefix(spec) << "the region holds " << cells << " cells of size " << spec.cell_size << " m (at most "
        << IceSheetSpec::kMaxCells << "): raise ice_sheet.cell_size or shrink ice_sheet.region";
    throw SceneError(msg.str());
  }
  FieldRandom rng(spec.seed);
  std::vector<Vec2> sites(static_cast<std::size_t>(cells));
  for (Vec2& s : sites) s = {rng.uniform(lo.x(), hi.x()), rng.uniform(lo.y(), hi.y())};
  const geometry::Aabb box{lo, hi};
  std::vector<std::vector<Vec2>> out;
  try {
    out = geometry::voronoi_cells(sites, box);
    for (int it = 0; it < spec.relaxation; ++it) {
      for (std::size_t i = 0; i < sites.size(); ++i) sites[i] = geometry::polygon_properties(out[i]).centroid;
      out = geometry::voronoi_cells(sites, box);
    }
  } catch (const geometry::VoronoiError& e) {  // coinciding sites: 2^-28 of the region apart
    throw SceneError(prefix(spec) + e.what() + "; try another ice_sheet.seed");
  }
  collapse_short_edges(out, box, IceSheetSpec::kMinEdgeFraction * spec.cell_size);
  for (std::size_t i = 0; i < out.size(); ++i) {
    if (const std::string why = geometry::convexity_error(out[i]); !why.empty())
      throw SceneError(prefix(spec) + "cell " + std::to_string(i) + " is degenerate (" + why +
                       "); try another ice_sheet.seed or a larger ice_sheet.cell_size");
  }
  return out;
}

SheetElementsOut ice_sheet_elements(const IceSheetSpec& spec) {
  SheetElementsOut out;
  std::vector<std::vector<Vec2>> cells = voronoi_sheet(spec);
  if (spec.elements == SheetElements::triangles) {
    for (const std::vector<Vec2>& c : cells) {
      const Vec2 centre = geometry::polygon_properties(c).centroid;
      for (std::size_t j = 0; j < c.size(); ++j) out.polygons.push_back({centre, c[j], c[(j + 1) % c.size()]});
    }
  } else {
    out.polygons = std::move(cells);
  }
  // Shared edges: each appears once in each of its two elements, in opposite directions.
  using Key = std::pair<std::pair<double, double>, std::pair<double, double>>;
  std::map<Key, std::pair<int, int>> first;  // edge (start, end) -> (element, -)
  for (std::size_t e = 0; e < out.polygons.size(); ++e) {
    const auto& p = out.polygons[e];
    for (std::size_t j = 0; j < p.size(); ++j) {
      const Vec2 u = p[j], v = p[(j + 1) % p.size()];
      const auto it = first.find({{v.x(), v.y()}, {u.x(), u.y()}});  // the neighbour walks it the other way
      if (it != first.end()) {
        const int other = it->second.first;
        out.faces.push_back({std::min(other, static_cast<int>(e)), std::max(other, static_cast<int>(e)), u, v});
        first.erase(it);
      } else {
        first.emplace(Key{{u.x(), u.y()}, {v.x(), v.y()}}, std::make_pair(static_cast<int>(e), 0));
      }
    }
  }
  // Corner pairs: elements around a vertex that share no face, with the faces at that vertex.
  using Point = std::pair<double, double>;
  std::map<Point, std::vector<int>> at_vertex, faces_at;
  for (std::size_t e = 0; e < out.polygons.size(); ++e)
    for (const Vec2& v : out.polygons[e]) at_vertex[{v.x(), v.y()}].push_back(static_cast<int>(e));
  std::set<std::pair<int, int>> sharing_face;
  for (std::size_t f = 0; f < out.faces.size(); ++f) {
    const SheetFace& sf = out.faces[f];
    faces_at[{sf.p0.x(), sf.p0.y()}].push_back(static_cast<int>(f));
    faces_at[{sf.p1.x(), sf.p1.y()}].push_back(static_cast<int>(f));
    sharing_face.insert({sf.a, sf.b});
  }
  std::set<std::pair<int, int>> seen;
  for (const auto& [point, elements] : at_vertex) {
    for (std::size_t i = 0; i < elements.size(); ++i) {
      for (std::size_t j = i + 1; j < elements.size(); ++j) {
        const std::pair<int, int> key{std::min(elements[i], elements[j]), std::max(elements[i], elements[j])};
        if (sharing_face.count(key) || !seen.insert(key).second) continue;
        const auto it = faces_at.find(point);
        out.corners.push_back({key.first, key.second, it == faces_at.end() ? std::vector<int>{} : it->second});
      }
    }
  }
  return out;
}

std::vector<dynamics::BodyDesc> ice_sheet_bodies(const IceSheetSpec& spec, double density, dynamics::BodyId first_id) {
  const std::vector<std::vector<Vec2>> cells = ice_sheet_elements(spec).polygons;
  std::vector<dynamics::BodyDesc> bodies;
  bodies.reserve(cells.size());
  for (std::size_t i = 0; i < cells.size(); ++i) {
    dynamics::BodyDesc d;
    Vec2 centre{0.0, 0.0};
    d.shape =
        std::make_shared<const geometry::ConvexPolygon>(geometry::ConvexPolygon::from_vertices(cells[i], &centre));
    d.id = first_id + i;
    d.position = centre;
    d.velocity = spec.velocity;
    d.thickness = spec.thickness;
    d.density = density;
    d.motion = dynamics::Motion::dynamic;
    bodies.push_back(std::move(d));
  }
  return bodies;
}

}  // namespace polyfloe::scene
