// Cost of a whole SpatialWorld::step per body, on 1 and 2 threads: the pile of tests/support/spatial_pile.h (a
// plate and 289 boxes thrown onto it under gravity, friction, manifold contacts), timed from t = 0.15 s, when every
// box is on the plate (about 300 contacts), for 1,000 steps.
//
//   build/tests/bench_spatial_step
//
// Counters: us_per_body_step (wall clock / (steps x bodies) [us]), contacts_per_body (contacts / bodies, averaged
// over the timed steps) and the SpatialWorld::profile() stages per body-step [ns]: integrate (kicks, the move and
// the world-frame vertices), broad, narrow_law (narrow phase, manifold, law, springs, the sum), forcing (gravity).
#include <benchmark/benchmark.h>

#include <chrono>

#include "dynamics/spatial_world.h"
#include "scene/scene.h"
#include "scene/scene_reader.h"
#include "spatial_pile.h"

namespace {

using namespace polyfloe;

void BM_SpatialPile(benchmark::State& state) {
  const int threads = static_cast<int>(state.range(0));
  const scene::Scene sc = scene::parse_scene(tsupport::spatial_pile_yaml(), "spatial_pile.yaml");
  dynamics::SpatialWorld world = scene::build_spatial_world(sc);
  world.set_threads(threads);
  const double dt = scene::time_step(sc, world);
  world.compute_forces(dt);
  while (world.time() < 0.15) world.step(dt);  // every box on the plate
  const dynamics::StepProfile p0 = world.profile();
  double contacts = 0.0, wall = 0.0;
  std::uint64_t steps = 0;
  for (auto _ : state) {
    const auto t0 = std::chrono::steady_clock::now();
    world.step(dt);
    wall += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    contacts += static_cast<double>(world.contacts().size());
    ++steps;
  }
  const dynamics::StepProfile& p1 = world.profile();
  const double body_steps = static_cast<double>(steps) * static_cast<double>(world.size());
  state.counters["bodies"] = static_cast<double>(world.size());
  state.counters["threads"] = threads;
  state.counters["us_per_body_step"] = 1e6 * wall / body_steps;
  state.counters["contacts_per_body"] = contacts / body_steps;
  state.counters["integrate_ns"] = 1e9 * (p1.integrate - p0.integrate) / body_steps;
  state.counters["broad_ns"] = 1e9 * (p1.broad - p0.broad) / body_steps;
  state.counters["narrow_law_ns"] = 1e9 * (p1.narrow_and_law - p0.narrow_and_law) / body_steps;
  state.counters["forcing_ns"] = 1e9 * (p1.forcing - p0.forcing) / body_steps;
}

}  // namespace

BENCHMARK(BM_SpatialPile)->Arg(1)->Arg(2)->Iterations(1000)->UseRealTime()->Unit(benchmark::kMillisecond);

BENCHMARK_MAIN();
