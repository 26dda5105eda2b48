#include "contact/broad_phase.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace polyfloe::contact {

void GridBroadPhase::find_pairs(std::span<const geometry::Aabb> boxes, std::span<const std::uint8_t> is_dynamic,
                                std::vector<CandidatePair>& pairs) {
  pairs.clear();
  build(boxes, is_dynamic);
  scan_tiles(0, tiles_, pairs);
}

namespace {

// The grid over the boxes: its lower corner, cell size and cells along x and y (nx = 0: nothing to pair).
struct GridShape {
  geometry::Vec2 lo{0.0, 0.0};
  double cell = 1.0;
  int nx = 0, ny = 0;
};

// A non-finite box (a body whose state blew up; the run guard reports it) enters no cell: it has no pairs, and the
// others keep theirs.
bool finite_box(const geometry::Aabb& b) { return b.lo.allFinite() && b.hi.allFinite(); }

GridShape grid_shape(std::span<const geometry::Aabb> boxes, std::span<const std::uint8_t> is_dynamic,
                     double requested_cell, int tile) {
  const int n = static_cast<int>(boxes.size());
  // Extent of everything, and the cell size.
  geometry::Vec2 lo{std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity()};
  geometry::Vec2 hi = -lo;
  double extent_sum = 0.0;
  int dynamic_count = 0;
  for (int i = 0; i < n; ++i) {
    if (!finite_box(boxes[i])) continue;
    lo = lo.cwiseMin(boxes[i].lo);
    hi = hi.cwiseMax(boxes[i].hi);
    if (is_dynamic[i]) {
      extent_sum += (boxes[i].hi - boxes[i].lo).maxCoeff();
      ++dynamic_count;
    }
  }
  GridShape g;
  if (dynamic_count == 0) return g;
  g.lo = lo;
  double cell = requested_cell > 0.0 ? requested_cell : 2.0 * extent_sum / dynamic_count;
  const geometry::Vec2 span = hi - lo;
  // Keep the grid no larger than ~4 cells per body (bodies spread far apart, or a tiny requested cell).
  const double max_cells = 4.0 * n + 1024.0;
  // Cells are numbered tile by tile (see build()); a grid narrower than a tile has tiles as wide as the grid (no
  // padding along it); the cap counts the padding.
  auto padded = [&](double cells) {
    const double t = std::min(static_cast<double>(tile), cells);
    return std::ceil(cells / t) * t;
  };
  auto cells_for = [&](double c) {
    return padded(std::floor(span.x() / c) + 1.0) * padded(std::floor(span.y() / c) + 1.0);
  };
  // Boxes far from the origin can round to zero extent (a cell of 0 would never grow): start from the span then.
  if (!(cell > 0.0) || !std::isfinite(cell)) cell = std::max({span.x(), span.y(), 1.0});
  for (int grow = 0; grow < 4096 && cells_for(cell) > max_cells; ++grow) cell *= 1.5;
  if (!(cells_for(cell) <= max_cells)) cell = std::numeric_limits<double>::infinity();  // one cell holds all
  auto count = [&](double extent) {  // one cell where the span itself overflowed (boxes near +-1e308)
    const double c = std::floor(extent / cell) + 1.0;
    return c >= 1.0 && c <= max_cells ? static_cast<int>(c) : 1;
  };
  g.cell = cell;
  g.nx = count(span.x());
  g.ny = count(span.y());
  return g;
}

}  // namespace

void GridBroadPhase::build(std::span<const geometry::Aabb> boxes, std::span<const std::uint8_t> is_dynamic) {
  boxes_ = boxes;
  dynamic_ = is_dynamic;
  tiles_ = 0;
  const int n = static_cast<int>(boxes.size());
  if (n < 2) return;
  const GridShape g = grid_shape(boxes, is_dynamic, requested_cell_, kTile);
  if (g.nx == 0) return;
  cell_ = g.cell;
  const int nx = g.nx, ny = g.ny;
  // Cells are numbered tile by tile (kTile x kTile cells per tile, row-major inside a tile and between tiles), and
  // the pairs are found in that order: the bodies a tile's pairs read stay in cache while it is scanned, however
  // wide the field (a row-major scan of a 10 km field walks a whole row of cells before coming back).
  const int tw = std::min(kTile, nx), th = std::min(kTile, ny);
  const int ntx = (nx + tw - 1) / tw;
  const std::size_t tile_cells = static_cast<std::size_t>(tw) * th;
  const std::size_t padded_cells = static_cast<std::size_t>(ntx) * ((ny + th - 1) / th) * tile_cells;
  auto cell_id = [&](int x, int y) {
    return (static_cast<std::size_t>(y / th) * ntx + x / tw) * tile_cells + static_cast<std::size_t>(y % th) * tw +
           x % tw;
  };
  const double inv = 1.0 / cell_;
  // Clamped in double before the conversion (a NaN or an overflowed offset goes to cell 0, never to int UB).
  auto cell_of = [](double v, int cells) { return v >= 0.0 ? (v < cells ? static_cast<int>(v) : cells - 1) : 0; };
  auto cx = [&](double x) { return cell_of((x - g.lo.x()) * inv, nx); };
  auto cy = [&](double y) { return cell_of((y - g.lo.y()) * inv, ny); };

  // Counting sort of (body, cell) entries.
  ranges_.resize(4 * static_cast<std::size_t>(n));
  cell_start_.assign(padded_cells + 1, 0);
  for (int i = 0; i < n; ++i) {
    if (!finite_box(boxes[i])) {  // an empty range: no cell
      ranges_[4 * i] = ranges_[4 * i + 1] = 1;
      ranges_[4 * i + 2] = ranges_[4 * i + 3] = 0;
      continue;
    }
    const int x0 = cx(boxes[i].lo.x()), y0 = cy(boxes[i].lo.y()), x1 = cx(boxes[i].hi.x()), y1 = cy(boxes[i].hi.y());
    ranges_[4 * i] = x0;
    ranges_[4 * i + 1] = y0;
    ranges_[4 * i + 2] = x1;
    ranges_[4 * i + 3] = y1;
    for (int y = y0; y <= y1; ++y)
      for (int x = x0; x <= x1; ++x) ++cell_start_[cell_id(x, y) + 1];
  }
  for (std::size_t c = 1; c < cell_start_.size(); ++c) cell_start_[c] += cell_start_[c - 1];
  entries_.resize(static_cast<std::size_t>(cell_start_.back()));
  cursor_.assign(cell_start_.begin(), cell_start_.end() - 1);
  for (int i = 0; i < n; ++i) {
    for (int y = ranges_[4 * i + 1]; y <= ranges_[4 * i + 3]; ++y)
      for (int x = ranges_[4 * i]; x <= ranges_[4 * i + 2]; ++x)
        entries_[static_cast<std::size_t>(cursor_[cell_id(x, y)]++)] = i;
  }

  tw_ = tw;
  th_ = th;
  ntx_ = ntx;
  tiles_ = padded_cells / tile_cells;
}

void GridBroadPhase::scan_tiles(std::size_t t0, std::size_t t1, std::vector<CandidatePair>& pairs) const {
  // Pairs within each cell, tile by tile; reported only by the cell holding the lower corner of the boxes'
  // intersection.
  const std::size_t tile_cells = static_cast<std::size_t>(tw_) * th_;
  for (std::size_t c = t0 * tile_cells; c < std::min(t1, tiles_) * tile_cells; ++c) {
    const int begin = cell_start_[c], end = cell_start_[c + 1];
    if (end - begin < 2) continue;
    const int in_tile = static_cast<int>(c % tile_cells), tile = static_cast<int>(c / tile_cells);
    const int x = (tile % ntx_) * tw_ + in_tile % tw_, y = (tile / ntx_) * th_ + in_tile / tw_;
    for (int p = begin; p < end; ++p) {
      const int i = entries_[p];
      const geometry::Aabb& bi = boxes_[i];
      for (int q = p + 1; q < end; ++q) {
        const int j = entries_[q];
        if (!dynamic_[i] && !dynamic_[j]) continue;
        const geometry::Aabb& bj = boxes_[j];
        if (!bi.overlaps(bj)) continue;
        if (std::max(ranges_[4 * i], ranges_[4 * j]) != x || std::max(ranges_[4 * i + 1], ranges_[4 * j + 1]) != y)
          continue;
        pairs.push_back(i < j ? CandidatePair{i, j} : CandidatePair{j, i});
      }
    }
  }
}

}  // namespace polyfloe::contact
