// Floe-field generation at the paper's settings (power-law sizes 5-100 m, alpha = 2, 5-10 corners): the whole
// generate_floe_field() for a 1 km square at 50 % and 60 % (~1.2k / 1.4k floes) and for an 8 km square at 60 %
// (~97k floes; the [fields] target: 10^5 floes at 60 % in under 10 s on one core). Counters: floes, seconds per
// field, realised concentration, fitted size exponent and mean circularity.
//   ./build/tests/bench_floe_field --benchmark_repetitions=3 --benchmark_report_aggregates_only=true
#include <benchmark/benchmark.h>

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
  const scene::FieldStatistics st = scene::field_statistics(field.floes, field.region_area, spec.size_min, spec.size_max);
  state.counters["floes"] = static_cast<double>(st.floes);
  state.counters["seconds"] = seconds;
  state.counters["us_per_floe"] = 1e6 * seconds / static_cast<double>(st.floes);
  state.counters["concentration"] = st.concentration;
  state.counters["exponent"] = st.size_distribution.exponent;
  state.counters["circularity"] = st.mean_circularity;
}

}  // namespace

BENCHMARK(BM_GenerateFloeField)->Args({1000, 50})->Args({1000, 60})->Args({8000, 60})->Unit(benchmark::kMillisecond);

BENCHMARK_MAIN();
