// The grid broad phase on the paper's floe fields: power-law sizes 5-100 m (alpha = 2), 5-10 corners, 50 %
// concentration, in square regions of 1, 3.16 and 10 km (about 1.2k, 12k and 120k floes). The cost per floe must
// stay flat (O(N)) although a 100 m floe spans many cells of a grid sized for the mean floe.
//   ./build/tests/bench_broad_phase --benchmark_repetitions=5 --benchmark_report_aggregates_only=true
#include <benchmark/benchmark.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <vector>

#include "contact/broad_phase.h"
#include "scene/floe_field.h"

using namespace polyfloe;
using geometry::Vec2;

namespace {

struct Boxes {
  std::vector<geometry::Aabb> boxes;
  std::vector<std::uint8_t> dynamic;
};

// sorted: bodies renumbered in row-major order of 50 m tiles of their centres (what a World that sorts its bodies
// spatially would hand the broad phase); otherwise largest first, as the generator stores them.
const Boxes& field_boxes(int side_m, bool sorted) {
  static std::map<std::pair<int, bool>, Boxes> cache;
  auto it = cache.find({side_m, sorted});
  if (it != cache.end()) return it->second;
  scene::FloeFieldSpec spec;
  spec.region_min = {0.0, 0.0};
  spec.region_max = {static_cast<double>(side_m), static_cast<double>(side_m)};
  spec.concentration = 0.5;
  spec.seed = 7;
  const scene::FloeField f = scene::generate_floe_field(spec, 920.0, 0);
  Boxes b;
  for (const dynamics::BodyDesc& d : f.floes) {
    geometry::Aabb box{d.position, d.position};
    const double c = std::cos(d.yaw), s = std::sin(d.yaw);
    for (const Vec2& v : d.shape->vertices()) {
      const Vec2 w = d.position + geometry::rotate(v, c, s);
      box.lo = box.lo.cwiseMin(w);
      box.hi = box.hi.cwiseMax(w);
    }
    b.boxes.push_back(box);
    b.dynamic.push_back(1);
  }
  if (sorted) {
    auto tile = [](const geometry::Aabb& x) {
      const Vec2 c = 0.5 * (x.lo + x.hi);
      return std::pair<long, long>{static_cast<long>(c.y() / 50.0), static_cast<long>(c.x() / 50.0)};
    };
    std::stable_sort(b.boxes.begin(), b.boxes.end(),
                     [&](const geometry::Aabb& p, const geometry::Aabb& q) { return tile(p) < tile(q); });
  }
  return cache.emplace(std::pair<int, bool>{side_m, sorted}, std::move(b)).first->second;
}

void BM_GridBroadPhase(benchmark::State& state) {
  const Boxes& b = field_boxes(static_cast<int>(state.range(0)), state.range(1) != 0);
  contact::GridBroadPhase grid;
  std::vector<contact::CandidatePair> pairs;
  grid.find_pairs(b.boxes, b.dynamic, pairs);  // warm: buffers sized
  for (auto _ : state) {
    grid.find_pairs(b.boxes, b.dynamic, pairs);
    benchmark::DoNotOptimize(pairs.data());
  }
  const double n = static_cast<double>(b.boxes.size());
  state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(b.boxes.size()));
  state.counters["floes"] = n;
  state.counters["ns_per_floe"] =
      benchmark::Counter(n, benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
  state.counters["candidates_per_floe"] = static_cast<double>(pairs.size()) / n;
  state.counters["cell_m"] = grid.cell_size();
}

}  // namespace

BENCHMARK(BM_GridBroadPhase)
    ->ArgsProduct({{1000, 3162, 10000}, {0, 1}})
    ->ArgNames({"side_m", "sorted"})
    ->Unit(benchmark::kMicrosecond);

BENCHMARK_MAIN();
