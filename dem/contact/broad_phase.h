// Broad phase: a uniform grid rebuilt every step with a counting sort (no per-step allocation once warm).
// Each body is entered in every cell its bounding box touches, so a 100 m floe among 5 m floes costs cells in
// proportion to its area and the total stays O(N) at a fixed concentration. A pair is reported once, by the cell
// that holds the lower corner of the two boxes' intersection. Pairs of two non-dynamic bodies are skipped.
#pragma once

#include <cstdint>
#include <span>
#include <utility>
#include <vector>

#include "geometry/vec2.h"

namespace polyfloe::contact {

struct CandidatePair {
  int a = 0, b = 0;  // body indices, a < b
  int entry = -1;    // the World's neighbour-list entry this pair came from (-1: none), where it keeps what the
                     // narrow phase may reuse the next step
};

class GridBroadPhase {
 public:
  static constexpr int kTile = 16;  // cells per tile side: the order in which cells are numbered and scanned

  // cell_size [m]; 0 picks 2 x the mean box extent of the dynamic bodies each build.
  explicit GridBroadPhase(double cell_size = 0.0) : requested_cell_(cell_size) {}
  void find_pairs(std::span<const geometry::Aabb> boxes, std::span<const std::uint8_t> is_dynamic,
                  std::vector<CandidatePair>& pairs);
  // The same in two parts, so that the scan can be split between threads: build() enters the boxes in the grid
  // (the spans must stay valid until the scans are done), scan_tiles() appends the pairs that tiles [t0, t1) report.
  // Scanning consecutive tile ranges and concatenating the results gives find_pairs' list, in its order.
  void build(std::span<const geometry::Aabb> boxes, std::span<const std::uint8_t> is_dynamic);
  std::size_t tile_count() const { return tiles_; }
  void scan_tiles(std::size_t t0, std::size_t t1, std::vector<CandidatePair>& pairs) const;
  double cell_size() const { return cell_; }
  std::size_t cell_count() const { return cell_start_.empty() ? 0 : cell_start_.size() - 1; }

 private:
  double requested_cell_ = 0.0;
  double cell_ = 1.0;
  std::vector<int> cell_start_;  // prefix sums, size = cells (padded to whole tiles) + 1
  std::vector<int> entries_;     // body indices grouped by cell
  std::vector<int> cursor_;
  std::vector<std::int32_t> ranges_;  // per body: ix0, iy0, ix1, iy1
  // The grid of the last build: boxes, flags, tiles (tw x th cells each, ntx per row of tiles).
  std::span<const geometry::Aabb> boxes_;
  std::span<const std::uint8_t> dynamic_;
  std::size_t tiles_ = 0;
  int tw_ = 1, th_ = 1, ntx_ = 1;
};

}  // namespace polyfloe::contact
