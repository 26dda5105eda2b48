#include "scene/ice_sheet.h"

#include <cmath>
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
  for (std::size_t i = 0; i < out.size(); ++i) {
    if (const std::string why = geometry::convexity_error(out[i]); !why.empty())
      throw SceneError(prefix(spec) + "cell " + std::to_string(i) + " is degenerate (" + why +
                       "); try another ice_sheet.seed or a larger ice_sheet.cell_size");
  }
  return out;
}

std::vector<dynamics::BodyDesc> ice_sheet_bodies(const IceSheetSpec& spec, double density, dynamics::BodyId first_id) {
  const std::vector<std::vector<Vec2>> cells = voronoi_sheet(spec);
  std::vector<dynamics::BodyDesc> bodies;
  bodies.reserve(cells.size());
  for (std::size_t i = 0; i < cells.size(); ++i) {
    dynamics::BodyDesc d;
    Vec2 centre{0.0, 0.0};
    d.shape = std::make_shared<const geometry::ConvexPolygon>(geometry::ConvexPolygon::from_vertices(cells[i], &centre));
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
