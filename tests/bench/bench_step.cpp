// Cost of a whole World::step per floe (kick, drift, world-frame shapes, broad phase, narrow phase + contact law +
// contact cache, drift forcing), one thread unless a case's second argument says otherwise.
//
//   <case>/<N>/<T>     T worker threads (World::set_threads; OpenMP). With T > 1 the per-floe-step time is wall
//                      time (the benchmark thread's CPU time would miss the other threads' work); with T = 1 it is
//                      the thread's CPU time.
//
//   BM_DensePack/<N>   a jammed pack at area fraction ~0.87 inside four fixed walls: every floe already presses on
//                      about four neighbours (or a wall) with ~2 mm overlaps when timing starts.
//   BM_DensePackSorted/<N>  the same pack with the bodies stored in lattice (row-major) order, so that bodies
//                      close in space are close in memory, as a scene's generated field is added to the World
//                      (space order; scene/build_world.cpp): what locality is worth, on 1 and 2 threads.
//   BM_FreeDrift/<N>   an open field at area fraction ~0.62 with random velocities (few contacts).
//   BM_MemoryPerFloe/<N>  heap bytes held per floe by a warm World of the DensePack (its shapes included): glibc's
//                      mallinfo2() before the pack is built and after the World is warm and the pack's body
//                      descriptions are gone (counter bytes_per_floe); the time reported is meaningless.
//   BM_DensePackContactOnly/<N>  the DensePack with every drift term off: the contact dynamics alone, what the
//                      LAMMPS disk pack of scripts/bench_lammps.sh does (it has no drag); up to 1.5M floes.
//   BM_DensePackContactOnlySorted/<N>  the same added in lattice order.
//   BM_ContactOnlyOrderSameRun/<N>  both, the random-order and the lattice-order World, stepped by turns in one
//                      process on one thread: their ratio turn by turn, which a shared machine's swings of speed (up
//                      to 40 % between runs minutes apart here) reach alike; BM_ContactOnlySizesSameRun (no
//                      argument) the same for random order at 1.5k, 15k, 150k and 1.5M floes. Their time is manual
//                      time: the thread CPU time of the counted turns (the counters are described at each case).
//
// Bodies are added in random order (no relation to position: bodies added in any order, e.g. a generated field
// largest first, as scenes did before 2026-11-25) except in the Sorted cases and the lattice World of
// BM_ContactOnlyOrderSameRun. The World stores them in space order (WorldSettings::store_in_space_order, as a
// scene's World does): random order should then cost what lattice order does (before 2026-11-27 the World kept the
// order bodies were added in: 1.3-1.6x at 150k-1.5M floes).
//
// All but the ContactOnly cases have every default drift term on (form drag, drag moment, skin and air drag;
// current 0.2 m/s, wind 10 m/s, not aligned); h = 1 m, dt = shortest_contact_duration(1 m/s) / 40, the time step a
// scene would use.
//
// How the pack is built (no DEM compaction needed, so 150,000 floes set up in seconds): generators on a square
// lattice of spacing s = 9 m, jittered by up to +-0.03 s; each floe is its generator's Voronoi cell (inside the
// domain box) intersected with a 10-gon of circumradius rho = 0.56 s at random angles around the generator, then
// scaled about the generator by (1 + eps), eps = 2e-4. Two neighbours whose bisector cuts both 10-gons share a
// piece of it, so after the scaling they overlap along it by eps x their distance (~2 mm); a cell on the domain
// edge overlaps its wall the same way. With that jitter nearly every lattice link is such a face and no diagonal
// one is, so rows and columns are unbroken chains between two walls: the pack stays jammed (~4 contacts per floe
// over thousands of steps) instead of relaxing into gaps. ~12 vertices per floe, area fraction ~0.87.
// The free field uses rho = 0.46 s, jitter +-0.1 s and shrinks the floes (eps = -1e-3): area fraction ~0.62, nobody
// touches at the start, a few close neighbours (mm gaps) collide within the first steps, random speeds <= 0.5 m/s.
//
// Counters (per floe-step; "floe-step" = one floe advanced by one step):
//   us_per_floe_step  CPU time of step() / (steps x floes) [us]
//   contacts_per_floe 2 x (contact pairs) / floes, averaged over the timed steps: the mean number of contacts a
//                     floe takes part in (floe-wall contacts included)
//   candidates_per_floe  broad-phase candidate pairs / floes (after the timed steps)
//   dt_ms             the time step [ms]
//   *_ns              World::profile() stage times (wall clock) per floe-step [ns]: integrate (kicks + drift),
//                     shapes (slot sort, world vertices + boxes, velocity prediction, linear drift model between
//                     full drift evaluations), broad, narrow_law (narrow phase + contact law + cache), forcing
//                     (full drift evaluations; every step here: update_every = 1)
//   narrow_only_ns    planar_overlap alone over the final state's candidate pairs, per floe [ns] (timed apart from
//                     the steps, each pair fresh: no kept topology, so an upper bound of the part of narrow_law that
//                     is geometry); ns_per_candidate: the same per pair
//   kept_fraction     of the timed steps' contacts, those whose overlap was built from the topology kept from the
//                     step before (contact::OverlapTopology) instead of clipping
#include <benchmark/benchmark.h>

#include <malloc.h>
#include <time.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <map>
#include <memory>
#include <optional>
#include <numbers>
#include <random>
#include <string>
#include <vector>

#include "contact/broad_phase.h"
#include "dynamics/world.h"
#include "forcing/analytic_fields.h"
#include "dense_pack.h"
#include "statistics.h"
#include "test_support.h"
#include "thread_clock.h"

using namespace polyfloe;
using geometry::Vec2;

namespace {

using tsupport::make_pack;
using tsupport::Pack;
using tsupport::PackSpec;
using tsupport::percentile;
using tsupport::spread;
using tsupport::thread_cpu_seconds;

enum class Kind { dense, dense_sorted, free, dense_contact, dense_contact_sorted };

const Pack& pack_for(int n, Kind kind) {
  // Generated once per (N, kind): repetitions rebuild the World from the same bodies but not the geometry.
  static std::map<std::pair<int, Kind>, Pack> cache;
  if (kind == Kind::dense_contact) kind = Kind::dense;  // the same packs
  if (kind == Kind::dense_contact_sorted) kind = Kind::dense_sorted;
  auto it = cache.find({n, kind});
  if (it != cache.end()) return it->second;
  PackSpec ps;
  if (kind == Kind::dense_sorted) ps.shuffle = false;
  if (kind == Kind::free) {
    ps.rho = 0.46;
    ps.jitter = 0.1;
    ps.eps = -1e-3;
    ps.speed = 0.5;
    ps.walls = false;
  }
  return cache.emplace(std::pair{n, kind}, make_pack(n, ps, kind == Kind::free ? 11u : 7u)).first->second;
}

// A World of `pack` as a scene builds one (bodies stored in space order), forces evaluated and two steps taken (the
// contact cache filled, scratch vectors sized), and its time step: shortest_contact_duration(1 m/s) / 40.
struct WarmWorld {
  dynamics::WorldSettings settings;
  std::unique_ptr<dynamics::World> world;
  double dt = 0.0;
};

WarmWorld warm_world(const Pack& pack, Kind kind, int threads,
                     contact::ForceModel model = contact::ForceModel::centroid) {
  WarmWorld w;
  dynamics::WorldSettings& ws = w.settings;
  ws.store_in_space_order = true;  // as scene::build_world's worlds
  ws.contact.force_model = model;
  ws.drift.ocean = forcing::make_field(forcing::FieldSpec::uniform({0.2, 0.05}));
  ws.drift.wind = forcing::make_field(forcing::FieldSpec::uniform({8.0, 6.0}));
  if (kind == Kind::dense_contact || kind == Kind::dense_contact_sorted)
    ws.drift.form_drag = ws.drift.moment_drag = ws.drift.skin_drag = ws.drift.air_drag = ws.drift.coriolis = false;
  w.world = std::make_unique<dynamics::World>(ws);
  w.world->set_threads(threads);
  for (const auto& d : pack.bodies) w.world->add_body(d);
  w.dt = w.world->shortest_contact_duration(1.0) / 40.0;
  w.world->compute_forces(0.0);
  for (int k = 0; k < 2; ++k) w.world->step(w.dt);
  return w;
}

void run(benchmark::State& state, Kind kind, contact::ForceModel model = contact::ForceModel::centroid) {
  const int n = static_cast<int>(state.range(0));
  const int threads = state.range(1) > 0 ? static_cast<int>(state.range(1)) : 1;
  const bool dense = kind != Kind::free;
  const Pack& pack = pack_for(n, kind);
  WarmWorld warm = warm_world(pack, kind, threads, model);
  dynamics::World& world = *warm.world;
  const dynamics::WorldSettings& ws = warm.settings;
  const double dt = warm.dt;
  if (dense && 2.0 * static_cast<double>(world.contacts().size()) / pack.floes < 2.0) {
    state.SkipWithError("the dense pack has fewer than 2 contacts per floe at the start");
    return;
  }

  const dynamics::StepProfile p0 = world.profile();
  double contact_pairs = 0.0;
  const double cpu0 = thread_cpu_seconds();
  const auto wall0 = std::chrono::steady_clock::now();
  for (auto _ : state) {
    world.step(dt);
    contact_pairs += static_cast<double>(world.contact_count());
  }
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall0).count();
  const double cpu = threads > 1 ? wall : thread_cpu_seconds() - cpu0;
  const dynamics::StepProfile p1 = world.profile();
  if (!(world.max_speed() < 10.0)) {
    state.SkipWithError("the pack became unstable during timing");
    return;
  }

  // Broad-phase candidates at the final state (outside timing).
  std::vector<geometry::Aabb> boxes;
  std::vector<std::uint8_t> dyn;
  for (std::size_t i = 0; i < world.size(); ++i) {
    const auto v = world.world_vertices(static_cast<int>(i));
    geometry::Aabb b{v[0], v[0]};
    for (const Vec2& q : v) {
      b.lo = b.lo.cwiseMin(q);
      b.hi = b.hi.cwiseMax(q);
    }
    boxes.push_back(b);
    dyn.push_back(world.motion(static_cast<int>(i)) == dynamics::Motion::dynamic ? 1 : 0);
  }
  std::vector<contact::CandidatePair> pairs;
  contact::GridBroadPhase(ws.broad_phase_cell).find_pairs(boxes, dyn, pairs);
  // The narrow phase alone over those candidates, in the World's storage order (outside the step's timing): what
  // part of narrow_law is geometry.
  const int passes = std::max(1, 3000000 / std::max<int>(1, static_cast<int>(pairs.size())));
  std::int64_t hits = 0;
  const double np0 = thread_cpu_seconds();
  for (int r = 0; r < passes; ++r) {
    for (const auto& cp : pairs) {
      contact::PlanarContact g;
      hits += contact::planar_overlap(world.world_vertices(cp.a), world.world_vertices(cp.b), g);
      benchmark::DoNotOptimize(g);
    }
  }
  const double narrow_only = (thread_cpu_seconds() - np0) / passes;
  benchmark::DoNotOptimize(hits);

  const double floe_steps = static_cast<double>(state.iterations()) * pack.floes;
  state.SetItemsProcessed(static_cast<std::int64_t>(floe_steps));
  state.counters["floes"] = pack.floes;
  state.counters["list_builds"] = static_cast<double>(world.neighbour_list_builds());
  state.counters["body_reorders"] = static_cast<double>(world.body_reorders());
  // The share of bodies whose world-frame vertices follow the previous body's in memory (1: stored in one order).
  double follows = 0.0;
  for (std::size_t i = 1; i < world.size(); ++i) {
    const auto prev = world.world_vertices(static_cast<int>(i - 1));
    follows += world.world_vertices(static_cast<int>(i)).data() == prev.data() + prev.size();
  }
  state.counters["vertices_in_order"] = world.size() > 1 ? follows / static_cast<double>(world.size() - 1) : 1.0;
  state.counters["threads"] = threads;
  state.counters["dt_ms"] = 1e3 * dt;
  state.counters["area_fraction"] = pack.area_fraction;
  state.counters["vertices"] = pack.mean_vertices;
  state.counters["us_per_floe_step"] = 1e6 * cpu / floe_steps;
  state.counters["contacts_per_floe"] = 2.0 * contact_pairs / floe_steps;
  state.counters["candidates_per_floe"] = static_cast<double>(pairs.size()) / pack.floes;
  state.counters["integrate_ns"] = 1e9 * (p1.integrate - p0.integrate) / floe_steps;
  state.counters["shapes_ns"] = 1e9 * (p1.shapes - p0.shapes) / floe_steps;
  state.counters["broad_ns"] = 1e9 * (p1.broad - p0.broad) / floe_steps;
  state.counters["narrow_law_ns"] = 1e9 * (p1.narrow_and_law - p0.narrow_and_law) / floe_steps;
  state.counters["forcing_ns"] = 1e9 * (p1.forcing - p0.forcing) / floe_steps;
  state.counters["narrow_only_ns"] = 1e9 * narrow_only / pack.floes;
  state.counters["kept_fraction"] = p1.contacts > p0.contacts ? static_cast<double>(p1.reused - p0.reused) /
                                                                    static_cast<double>(p1.contacts - p0.contacts)
                                                              : 0.0;
  state.counters["ns_per_candidate"] = pairs.empty() ? 0.0 : 1e9 * narrow_only / static_cast<double>(pairs.size());
}

void BM_DensePack(benchmark::State& state) { run(state, Kind::dense); }
// The same pack under the foundation force model, at its own (smaller) automatic step.
void BM_DensePackFoundation(benchmark::State& state) { run(state, Kind::dense, contact::ForceModel::foundation); }
void BM_DensePackSorted(benchmark::State& state) { run(state, Kind::dense_sorted); }
void BM_FreeDrift(benchmark::State& state) { run(state, Kind::free); }
void BM_DensePackContactOnly(benchmark::State& state) { run(state, Kind::dense_contact); }
void BM_DensePackContactOnlySorted(benchmark::State& state) { run(state, Kind::dense_contact_sorted); }

void BM_MemoryPerFloe(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0));
  double bytes = 0.0;
  int floes = 0;
  for (auto _ : state) {
    auto heap = [] {
      const struct mallinfo2 m = mallinfo2();
      return static_cast<double>(m.uordblks + m.hblkhd);
    };
    const double before = heap();
    std::optional<dynamics::World> world;
    {
      Pack pack = make_pack(n, PackSpec{}, 7u);
      floes = pack.floes;
      dynamics::WorldSettings ws;
      ws.drift.ocean = forcing::make_field(forcing::FieldSpec::uniform({0.2, 0.05}));
      ws.drift.wind = forcing::make_field(forcing::FieldSpec::uniform({8.0, 6.0}));
      world.emplace(ws);
      for (const auto& d : pack.bodies) world->add_body(d);
      const double dt = world->shortest_contact_duration(1.0) / 40.0;
      world->compute_forces(0.0);
      for (int k = 0; k < 3; ++k) world->step(dt);
    }  // the pack's descriptions are freed; the shapes live on in the World
    bytes = heap() - before;
    benchmark::DoNotOptimize(world->positions().data());
  }
  state.counters["floes"] = floes;
  state.counters["bytes_per_floe"] = bytes / floes;
}

// Turns of steps for worlds measured in one run (the *SameRun cases): each turn `steps` steps of one World, timed
// in this thread's CPU time. Turns of the worlds follow each other closely, so that they all meet the machine's
// load alike however it moves during the run.
struct Turns {
  WarmWorld w;
  int floes = 0;
  int steps = 1;
  std::vector<double> us;    // each turn's us per floe-step
  dynamics::StepProfile p0;  // the World's stage times when the counted turns began
  // One turn; its thread CPU time [s].
  double take() {
    const double t0 = thread_cpu_seconds();
    for (int k = 0; k < steps; ++k) w.world->step(w.dt);
    const double seconds = thread_cpu_seconds() - t0;
    us.push_back(1e6 * seconds / (static_cast<double>(steps) * floes));
    return seconds;
  }
  void warm_turn() {  // a turn not counted: every World has taken one since the others were built
    take();
    us.clear();
    p0 = w.world->profile();
  }
  // The counted turns' stage times [ns per floe-step] as counters named <prefix>_<stage>_ns.
  void stage_counters(benchmark::State& state, const std::string& prefix) const {
    const dynamics::StepProfile p1 = w.world->profile();
    const double per = 1e9 / (static_cast<double>(us.size()) * steps * floes);
    state.counters[prefix + "_shapes_ns"] = per * (p1.shapes - p0.shapes);
    state.counters[prefix + "_broad_ns"] = per * (p1.broad - p0.broad);
    state.counters[prefix + "_narrow_law_ns"] = per * (p1.narrow_and_law - p0.narrow_and_law);
    state.counters[prefix + "_integrate_ns"] = per * (p1.integrate - p0.integrate);
  }
  bool stable() const { return w.world->max_speed() < 10.0; }
};

Turns turns_of(int n, Kind kind, double floe_steps_per_turn) {
  const Pack& pack = pack_for(n, kind);
  Turns t{warm_world(pack, kind, 1), pack.floes, 1, {}, {}};
  t.steps = std::max(1, static_cast<int>(std::lround(floe_steps_per_turn / pack.floes)));
  return t;
}

// BM_ContactOnlyOrderSameRun/<N>: the contact-only pack in random order and in lattice order, two Worlds stepped by
// turns in one process (each iteration a turn of each, the one that goes first alternating; a turn 300k floe-steps
// rounded to whole steps, at least one: 2 steps at 150k, 1 at 1.5M), so that slow swings of a shared machine's
// speed fall on both alike. Counters: random_us and lattice_us, the medians of their turns [us per floe-step];
// ratio, the median of each iteration's random / lattice (two turns next to each other in time); ratio_of_medians;
// ratio_min, ratio_max; each World's stage times (<order>_<stage>_ns, wall clock, as the DensePack cases').
void BM_ContactOnlyOrderSameRun(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0));
  Turns random = turns_of(n, Kind::dense_contact, 3e5), lattice = turns_of(n, Kind::dense_contact_sorted, 3e5);
  random.warm_turn();
  lattice.warm_turn();
  std::vector<double> ratios;
  bool random_first = true;
  for (auto _ : state) {
    Turns& first = random_first ? random : lattice;
    Turns& second = random_first ? lattice : random;
    const double seconds = first.take();  // (two statements: the order of a sum's operands is unspecified)
    state.SetIterationTime(seconds + second.take());
    random_first = !random_first;
    ratios.push_back(random.us.back() / lattice.us.back());
  }
  if (!random.stable() || !lattice.stable()) {
    state.SkipWithError("a pack became unstable during timing");
    return;
  }
  state.counters["floes"] = random.floes;
  state.counters["steps_per_turn"] = random.steps;
  state.counters["random_us"] = percentile(random.us, 0.5);
  state.counters["lattice_us"] = percentile(lattice.us, 0.5);
  state.counters["ratio"] = percentile(ratios, 0.5);
  state.counters["ratio_of_medians"] = percentile(random.us, 0.5) / percentile(lattice.us, 0.5);
  state.counters["ratio_min"] = *std::min_element(ratios.begin(), ratios.end());
  state.counters["ratio_max"] = *std::max_element(ratios.begin(), ratios.end());
  random.stage_counters(state, "random");
  lattice.stage_counters(state, "lattice");
}

// BM_ContactOnlySizesSameRun: the contact-only pack in random order at 1.5k, 15k, 150k and 1.5M floes, four Worlds
// stepped by turns in one process (each iteration a turn of each, 600k floe-steps rounded to whole steps, at least
// one: 405, 40, 4 and 1 steps; the one that goes first rotating). Counters: us_<N>, the median of each size's turns
// [us per floe-step]; spread_percent, (max - min) / (max + min) of those medians [%], what "flat within +-20 %" is
// measured by.
void BM_ContactOnlySizesSameRun(benchmark::State& state) {
  const std::vector<int> sizes{1500, 15000, 150000, 1500000};
  std::vector<Turns> worlds;
  for (const int n : sizes) worlds.push_back(turns_of(n, Kind::dense_contact, 6e5));
  for (Turns& t : worlds) t.warm_turn();
  std::size_t first = 0;
  for (auto _ : state) {
    double seconds = 0.0;
    for (std::size_t k = 0; k < worlds.size(); ++k) seconds += worlds[(first + k) % worlds.size()].take();
    first = (first + 1) % worlds.size();
    state.SetIterationTime(seconds);
  }
  std::vector<double> medians;
  for (std::size_t k = 0; k < worlds.size(); ++k) {
    if (!worlds[k].stable()) {
      state.SkipWithError("a pack became unstable during timing");
      return;
    }
    medians.push_back(percentile(worlds[k].us, 0.5));
    state.counters["us_" + std::to_string(sizes[k])] = medians.back();
  }
  state.counters["spread_percent"] = 100.0 * spread(medians);
}

}  // namespace

// Fixed step counts (the set-up is not repeated to calibrate): about 1.5 million floe-steps per case. The second
// argument is the thread count.
BENCHMARK(BM_DensePack)->Args({1500, 1})->Iterations(1000)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_DensePack)->Args({15000, 1})->Iterations(100)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_DensePack)->Args({150000, 1})->Iterations(10)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_DensePack)->Args({15000, 2})->Iterations(100)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_DensePack)->Args({150000, 2})->Iterations(10)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_DensePackFoundation)->Args({15000, 1})->Iterations(100)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_DensePackSorted)->Args({15000, 1})->Iterations(100)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_DensePackSorted)->Args({150000, 1})->Iterations(10)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_DensePackSorted)->Args({15000, 2})->Iterations(100)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_DensePackSorted)->Args({150000, 2})->Iterations(10)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_FreeDrift)->Args({1500, 1})->Iterations(1000)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_FreeDrift)->Args({15000, 1})->Iterations(100)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_FreeDrift)->Args({150000, 1})->Iterations(10)->Unit(benchmark::kMillisecond);

BENCHMARK(BM_MemoryPerFloe)->Arg(15000)->Iterations(1)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_MemoryPerFloe)->Arg(150000)->Iterations(1)->Unit(benchmark::kMillisecond);

BENCHMARK(BM_DensePackContactOnly)->Args({1500, 1})->Iterations(1000)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_DensePackContactOnly)->Args({15000, 1})->Iterations(100)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_DensePackContactOnly)->Args({150000, 1})->Iterations(10)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_DensePackContactOnly)->Args({1500000, 1})->Iterations(3)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_DensePackContactOnly)->Args({150000, 2})->Iterations(10)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_DensePackContactOnlySorted)->Args({1500, 1})->Iterations(1000)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_DensePackContactOnlySorted)->Args({15000, 1})->Iterations(100)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_DensePackContactOnlySorted)->Args({150000, 1})->Iterations(10)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_DensePackContactOnlySorted)->Args({1500000, 1})->Iterations(3)->Unit(benchmark::kMillisecond);

// Worlds measured by turns in one run (a turn not counted first): 150k: 40 iterations of 2 + 2 steps; 1.5M: 16 of
// 1 + 1; the sizes: 12 of 405 + 40 + 4 + 1 steps. About 20-40 s each, and the packs built.
BENCHMARK(BM_ContactOnlyOrderSameRun)->Arg(150000)->Iterations(40)->UseManualTime()->Unit(benchmark::kMillisecond);
BENCHMARK(BM_ContactOnlyOrderSameRun)->Arg(1500000)->Iterations(16)->UseManualTime()->Unit(benchmark::kMillisecond);
BENCHMARK(BM_ContactOnlySizesSameRun)->Iterations(12)->UseManualTime()->Unit(benchmark::kMillisecond);

BENCHMARK_MAIN();
