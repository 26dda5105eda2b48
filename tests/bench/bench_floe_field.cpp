// Floe-field generation at the paper's settings (power-law sizes 5-100 m, alpha = 2, 5-10 corners): the whole
// generate_floe_field() for a 1 km square at 50 % and 60 % (~1.2k / 1.4k floes) and for an 8 km square at 60 %
// (~97k floes; the [fields] target: 10^5 floes at 60 % in under 10 s on one core). Counters: floes, seconds per
// field, realised concentration, fitted size exponent and mean circularity. BM_ExplicitFloes: a scene that lists N
// floes one by one, read and built (the initial-overlap check through the broad phase: time per floe flat in N).
//   ./build/tests/bench_floe_field --benchmark_repetitions=3 --benchmark_report_aggregates_only=true
#include <benchmark/benchmark.h>

#include <random>
#include <vector>

#include <cmath>
#include <string>

#include "dynamics/world.h"
#include "geometry/voronoi.h"
#include "scene/scene.h"
#include "scene/scene_reader.h"
#include "scene/field_statistics.h"
#include "scene/floe_field.h"
#include "thread_clock.h"

using namespace polyfloe;

namespace {

void BM_GenerateFloeField(benchmark::State& state) {
  scene::FloeFieldSpec spec;
  const double side = static_cast<double>(state.range(0));
  spec.region_min = {0.0, 0.0};
  spec.region_max = {side, side};
  spec.concentration = static_cast<double>(state.range(1)) / 100.0;
  spec.seed = 1;
  scene::FloeField field;
  const double cpu0 = tsupport::thread_cpu_seconds();
  for (auto _ : state) {
    field = scene::generate_floe_field(spec, 920.0, 0);
    benchmark::DoNotOptimize(field.floes.data());
  }
  const double seconds = (tsupport::thread_cpu_seconds() - cpu0) / static_cast<double>(state.iterations());
  const scene::FieldStatistics st =
      scene::field_statistics(field.floes, field.region_area, spec.size_min, spec.size_max);
  state.counters["floes"] = static_cast<double>(st.floes);
  state.counters["seconds"] = seconds;
  state.counters["us_per_floe"] = 1e6 * seconds / static_cast<double>(st.floes);
  state.counters["concentration"] = st.concentration;
  state.counters["exponent"] = st.size_distribution.exponent;
  state.counters["circularity"] = st.mean_circularity;
}

// Voronoi cells of N random sites in a 1 km x 1 km box (Boost.Polygon with mirrored sites), per site.
void BM_VoronoiCells(benchmark::State& state) {
  const auto n = static_cast<std::size_t>(state.range(0));
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> u(1.0, 999.0);
  std::vector<geometry::Vec2> sites(n);
  for (auto& p : sites) p = {u(rng), u(rng)};
  const geometry::Aabb box{{0.0, 0.0}, {1000.0, 1000.0}};
  const double cpu0 = tsupport::thread_cpu_seconds();
  for (auto _ : state) benchmark::DoNotOptimize(geometry::voronoi_cells(sites, box).data());
  state.counters["us_per_site"] = 1e6 * (tsupport::thread_cpu_seconds() - cpu0) /
                                  (static_cast<double>(n) * static_cast<double>(state.iterations()));
}

// A scene of N explicit 8 m squares on a 10 m lattice (each checked against the others for initial overlap),
// parsed and built; seconds and microseconds per floe.
void BM_ExplicitFloes(benchmark::State& state) {
  const auto n = static_cast<int>(state.range(0));
  const int side = static_cast<int>(std::ceil(std::sqrt(n)));
  std::string text = "run: {duration: 1}\nfloes:\n";
  for (int i = 0; i < n; ++i)
    text += "  - {rectangle: {width: 8, height: 8}, position: [" + std::to_string(10 * (i % side)) + ", " +
            std::to_string(10 * (i / side)) + "]}\n";
  const double cpu0 = tsupport::thread_cpu_seconds();
  for (auto _ : state) {
    const scene::Scene sc = scene::parse_scene(text, "explicit.yaml");
    const dynamics::World w = scene::build_world(sc);
    benchmark::DoNotOptimize(w.size());
  }
  const double seconds = (tsupport::thread_cpu_seconds() - cpu0) / static_cast<double>(state.iterations());
  state.counters["seconds"] = seconds;
  state.counters["us_per_floe"] = 1e6 * seconds / n;
}

}  // namespace

BENCHMARK(BM_VoronoiCells)->Arg(1000)->Arg(100000)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_ExplicitFloes)->Arg(10000)->Arg(40000)->Arg(200000)->Unit(benchmark::kMillisecond)->Iterations(1);
BENCHMARK(BM_GenerateFloeField)->Args({1000, 50})->Args({1000, 60})->Args({8000, 60})->Unit(benchmark::kMillisecond);

BENCHMARK_MAIN();
