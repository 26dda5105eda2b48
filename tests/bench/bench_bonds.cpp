// Frozen sheets under compression: the whole step per element for a sheet of triangular elements ([bonds] target:
// 10^4 elements), bonded and squeezed between two plates closing at 1 m/s (the uniaxial scene's settings, scaled).
// Warmed up until the plates press the sheet, so contacts at the plates and bond failures are in the timed steps.
// Counters: elements, faces, us per element-step (whole step) and the bond stage's share.
//   ./build-bench/tests/bench_bonds --benchmark_repetitions=3 --benchmark_report_aggregates_only=true
#include <benchmark/benchmark.h>

#include <string>

#include "scene/scene_reader.h"
#include "thread_clock.h"

using namespace polyfloe;

namespace {

void BM_CompressedSheetStep(benchmark::State& state) {
  const double side = static_cast<double>(state.range(0));  // [m]
  const std::string s = std::to_string(side);
  const std::string text =
      "run: {duration: 10}\n"
      "forcing: {air: {drag: {enabled: false}}}\n"
      "ice_sheet: {region: [0, 0, " +
      s + ", " + s +
      "], cell_size: 11.284, elements: triangles,"
      " bonds: {tensile_strength: 1.0e6, shear_strength: 1.0e6, friction_angle: 0.6}}\n"
      "floes:\n"
      "  - {rectangle: {width: 20, height: " +
      std::to_string(side + 40) + "}, position: [-10, " + std::to_string(side / 2) +
      "], velocity: [0.5, 0], motion: kinematic}\n"
      "  - {rectangle: {width: 20, height: " +
      std::to_string(side + 40) + "}, position: [" + std::to_string(side + 10) + ", " + std::to_string(side / 2) +
      "], velocity: [-0.5, 0], motion: kinematic}\n";
  const scene::Scene sc = scene::parse_scene(text, "bench.yaml", {});
  dynamics::World w = scene::build_world(sc);
  const double dt = scene::time_step(sc, w);
  // Warm up: 0.2 % strain, so the plates press and bonds carry load.
  const int warm = static_cast<int>(0.002 * side / dt);
  for (int k = 0; k < warm; ++k) w.step(dt);
  const double bonds0 = w.profile().bonds;
  const double cpu0 = tsupport::thread_cpu_seconds();
  for (auto _ : state) w.step(dt);
  const double seconds = tsupport::thread_cpu_seconds() - cpu0;
  const double steps = static_cast<double>(state.iterations());
  const double elements = static_cast<double>(w.size() - 2);
  state.counters["elements"] = elements;
  state.counters["faces"] = static_cast<double>(w.bonds()->faces());
  state.counters["broken"] = static_cast<double>(w.bonds()->faces() - w.bonds()->intact_faces());
  state.counters["dt_us"] = 1e6 * dt;
  state.counters["us_per_element_step"] = 1e6 * seconds / (steps * elements);
  state.counters["bond_stage_us_per_element_step"] = 1e6 * (w.profile().bonds - bonds0) / (steps * elements);
}

}  // namespace

// 250 m: the uniaxial scene (~3,400 elements); 430 m: ~10^4 elements.
BENCHMARK(BM_CompressedSheetStep)->Arg(250)->Arg(430)->Unit(benchmark::kMillisecond)->Iterations(300);
BENCHMARK_MAIN();
