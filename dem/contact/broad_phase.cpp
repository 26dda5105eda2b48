#include "contact/broad_phase.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace polyfloe::contact {

void GridBroadPhase::find_pairs(std::span<const geometry::Aabb> boxes, std::span<const std::uint8_t> is_dynamic,
                                std::vector<CandidatePair>& pairs) {
  pairs.clear();
  const int n = static_cast<int>(boxes.size());
  if (n < 2) return;

  // Extent of everything, and the cell size.
  geometry::Vec2 lo{std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity()};
  geometry::Vec2 hi = -lo;
  double extent_sum = 0.0;
  int dynamic_count = 0;
  for (int i = 0; i < n; ++i) {
    lo = lo.cwiseMin(boxes[i].lo);
    hi = hi.cwiseMax(boxes[i].hi);
    if (is_dynamic[i]) {
      extent_sum += (boxes[i].hi - boxes[i].lo).maxCoeff();
      ++dynamic_count;
    }
  }
  if (dynamic_count == 0) return;
  // A non-finite box (a body whose state blew up) makes no grid; the run guard reports the body.
  if (!std::isfinite(lo.x()) || !std::isfinite(lo.y()) || !std::isfinite(hi.x()) || !std::isfinite(hi.y())) return;
  cell_ = requested_cell_ > 0.0 ? requested_cell_ : 2.0 * extent_sum / dynamic_count;
  const geometry::Vec2 span = hi - lo;
  // Keep the grid no larger than ~4 cells per body (bodies spread far apart, or a tiny requested cell).
  const double max_cells = 4.0 * n + 1024.0;
  auto cells_for = [&](double c) { return (std::floor(span.x() / c) + 1.0) * (std::floor(span.y() / c) + 1.0); };
  while (cells_for(cell_) > max_cells) cell_ *= 1.5;
  const int nx = static_cast<int>(std::floor(span.x() / cell_)) + 1;
  const int ny = static_cast<int>(std::floor(span.y() / cell_)) + 1;
  const double inv = 1.0 / cell_;
  auto cx = [&](double x) { return std::clamp(static_cast<int>((x - lo.x()) * inv), 0, nx - 1); };
  auto cy = [&](double y) { return std::clamp(static_cast<int>((y - lo.y()) * inv), 0, ny - 1); };

  // Counting sort of (body, cell) entries.
  ranges_.resize(4 * static_cast<std::size_t>(n));
  cell_start_.assign(static_cast<std::size_t>(nx) * ny + 1, 0);
  for (int i = 0; i < n; ++i) {
    const int x0 = cx(boxes[i].lo.x()), y0 = cy(boxes[i].lo.y()), x1 = cx(boxes[i].hi.x()), y1 = cy(boxes[i].hi.y());
    ranges_[4 * i] = x0; ranges_[4 * i + 1] = y0; ranges_[4 * i + 2] = x1; ranges_[4 * i + 3] = y1;
    for (int y = y0; y <= y1; ++y)
      for (int x = x0; x <= x1; ++x) ++cell_start_[static_cast<std::size_t>(y) * nx + x + 1];
  }
  for (std::size_t c = 1; c < cell_start_.size(); ++c) cell_start_[c] += cell_start_[c - 1];
  entries_.resize(static_cast<std::size_t>(cell_start_.back()));
  cursor_.assign(cell_start_.begin(), cell_start_.end() - 1);
  for (int i = 0; i < n; ++i) {
    for (int y = ranges_[4 * i + 1]; y <= ranges_[4 * i + 3]; ++y)
      for (int x = ranges_[4 * i]; x <= ranges_[4 * i + 2]; ++x)
        entries_[static_cast<std::size_t>(cursor_[static_cast<std::size_t>(y) * nx + x]++)] = i;
  }

  // Pairs within each cell; reported only by the cell holding the lower corner of the boxes' intersection.
  for (int y = 0; y < ny; ++y) {
    for (int x = 0; x < nx; ++x) {
      const std::size_t c = static_cast<std::size_t>(y) * nx + x;
      const int begin = cell_start_[c], end = cell_start_[c + 1];
      for (int p = begin; p < end; ++p) {
        const int i = entries_[p];
        const geometry::Aabb& bi = boxes[i];
        for (int q = p + 1; q < end; ++q) {
          const int j = entries_[q];
          if (!is_dynamic[i] && !is_dynamic[j]) continue;
          const geometry::Aabb& bj = boxes[j];
          if (!bi.overlaps(bj)) continue;
          if (std::max(ranges_[4 * i], ranges_[4 * j]) != x || std::max(ranges_[4 * i + 1], ranges_[4 * j + 1]) != y)
            continue;
          pairs.push_back(i < j ? CandidatePair{i, j} : CandidatePair{j, i});
        }
      }
    }
  }
}

}  // namespace polyfloe::contact
