// Placing floes without overlap (internal to dem/scene; the floe-field generator's): polygons prepared for repeated
// separating-axis tests, a uniform grid over the region, and the set of polygons placed so far with the test of a
// new one against them.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <span>
#include <vector>

#include "geometry/vec2.h"

namespace polyfloe::scene::detail {

using geometry::Vec2;

// A convex polygon prepared for repeated separating-axis tests: unit outward edge normals n_i and offsets
// d_i = n_i . v_i, so that n_i . x - d_i is the signed distance of x from edge line i.
struct PreparedPolygon {
  std::vector<Vec2> v;    // [m]
  std::vector<Vec2> n;    // [-]
  std::vector<double> d;  // [m]
  geometry::Aabb box;     // [m]
};

PreparedPolygon prepare(std::span<const Vec2> v);

// `a` (translated by a_shift) and `b` (translated by b_shift) are at least `gap` apart along some edge normal.
bool separated(const PreparedPolygon& a, const Vec2& a_shift, const PreparedPolygon& b, const Vec2& b_shift,
               double gap);

// Uniform grid over the region; each placed polygon is listed in every cell its box touches.
class PlacementGrid {
 public:
  PlacementGrid(const Vec2& lo, const Vec2& hi, double cell) : lo_(lo), cell_(cell) {
    nx_ = std::max(1, static_cast<int>(std::ceil((hi.x() - lo.x()) / cell)));
    ny_ = std::max(1, static_cast<int>(std::ceil((hi.y() - lo.y()) / cell)));
    cells_.resize(static_cast<std::size_t>(nx_) * static_cast<std::size_t>(ny_));
  }
  // Cell index range [x0, x1] x [y0, y1] covered by the box (clamped); false if the box misses the grid.
  bool range(const geometry::Aabb& b, int& x0, int& y0, int& x1, int& y1) const {
    x0 = clamp_cell((b.lo.x() - lo_.x()) / cell_, nx_);
    x1 = clamp_cell((b.hi.x() - lo_.x()) / cell_, nx_);
    y0 = clamp_cell((b.lo.y() - lo_.y()) / cell_, ny_);
    y1 = clamp_cell((b.hi.y() - lo_.y()) / cell_, ny_);
    return b.hi.x() >= lo_.x() && b.hi.y() >= lo_.y() && b.lo.x() <= lo_.x() + nx_ * cell_ &&
           b.lo.y() <= lo_.y() + ny_ * cell_;
  }
  void insert(const geometry::Aabb& b, int item) {
    int x0, y0, x1, y1;
    if (!range(b, x0, y0, x1, y1)) return;
    for (int y = y0; y <= y1; ++y)
      for (int x = x0; x <= x1; ++x) cells_[index(x, y)].push_back(item);
  }
  const std::vector<int>& cell(int x, int y) const { return cells_[index(x, y)]; }

 private:
  static int clamp_cell(double c, int n) {
    if (!(c > 0.0)) return 0;
    if (c >= n - 1) return n - 1;
    return static_cast<int>(c);
  }
  std::size_t index(int x, int y) const {
    return static_cast<std::size_t>(y) * static_cast<std::size_t>(nx_) + static_cast<std::size_t>(x);
  }
  Vec2 lo_;
  double cell_;
  int nx_ = 1, ny_ = 1;
  std::vector<std::vector<int>> cells_;
};

// The polygons placed so far (the obstacles in the region, then the floes) on the placement grid, and whether a new
// one is clear of them all.
class PlacedSet {
 public:
  PlacedSet(const Vec2& lo, const Vec2& hi, double cell) : region_{lo, hi}, grid_(lo, hi, cell) {}

  // The obstacles (world frame) that reach into the region; room for `floes` more.
  void add_obstacles(std::span<const std::vector<Vec2>> obstacles, std::size_t floes) {
    placed_.reserve(obstacles.size() + floes);
    for (const std::vector<Vec2>& o : obstacles) {
      if (o.size() < 3) continue;
      PreparedPolygon p = prepare(o);
      if (!p.box.overlaps(region_)) continue;
      grid_.insert(p.box, static_cast<int>(placed_.size()));
      placed_.push_back(std::move(p));
      shift_.emplace_back(0.0, 0.0);
    }
    stamp_.assign(placed_.size() + floes, 0);
  }

  // Whether `body` with its frame at p, grown by `gap` [m], overlaps nothing placed.
  bool clear(const PreparedPolygon& body, const Vec2& p, double gap) {
    const geometry::Aabb box{body.box.lo + p - Vec2(gap, gap), body.box.hi + p + Vec2(gap, gap)};
    int x0, y0, x1, y1;
    grid_.range(box, x0, y0, x1, y1);
    if (++current_stamp_ == 0) {  // wrapped: clear the marks
      std::fill(stamp_.begin(), stamp_.end(), 0);
      current_stamp_ = 1;
    }
    for (int y = y0; y <= y1; ++y) {
      for (int x = x0; x <= x1; ++x) {
        for (int item : grid_.cell(x, y)) {
          if (stamp_[static_cast<std::size_t>(item)] == current_stamp_) continue;
          stamp_[static_cast<std::size_t>(item)] = current_stamp_;
          const PreparedPolygon& other = placed_[static_cast<std::size_t>(item)];
          const Vec2& other_shift = shift_[static_cast<std::size_t>(item)];
          const geometry::Aabb other_box{other.box.lo + other_shift, other.box.hi + other_shift};
          if (!box.overlaps(other_box)) continue;
          if (!separated(body, p, other, other_shift, gap)) return false;
        }
      }
    }
    return true;
  }

  void add(const PreparedPolygon& body, const Vec2& p) {
    grid_.insert(geometry::Aabb{body.box.lo + p, body.box.hi + p}, static_cast<int>(placed_.size()));
    placed_.push_back(body);
    shift_.push_back(p);
  }

 private:
  geometry::Aabb region_;
  PlacementGrid grid_;
  std::vector<PreparedPolygon> placed_;
  std::vector<Vec2> shift_;  // world position of each placed polygon's frame [m]
  std::vector<std::uint32_t> stamp_;
  std::uint32_t current_stamp_ = 0;
};

}  // namespace polyfloe::scene::detail
