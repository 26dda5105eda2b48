// Sampling an OpenFOAM current: accuracy against cost of the ocean drag on floes in the strait flow
// (of_cases/strait), for each way of sampling the field - a field-file grid of 40, 20, 10, 5 or 2.5 m, or probing
// the OpenFOAM mesh directly (coupling/'s ProbedField) - and each bottom-quadrature rule.
//
// BM_FieldSampling/source/rule: the ocean load (form drag on the side faces, the drag moment with the water's
// rotation, skin drag on the bottom) on ~300 floes (10-60 m, 5-10 corners) lying wholly in the water of the strait,
// each moving at the current at its centre plus a random 0.05 m/s and +-2e-3 rad/s. Counters: ns_per_floe (thread
// CPU: points placed, field sampled, kernels), points_per_floe, force_error and torque_error: RMS over floes of
// |load - reference| / RMS of the reference, the reference being the mesh probed directly with the degree-5 rule
// on every fan triangle cut into 4^3 pieces; grid_mb: the field file's grid in memory.
//   of_cases/strait/Allrun --quick       # once: the OpenFOAM case (any mesh)
//   build-bench/tests/bench_field_sampling --case of_cases/strait --benchmark_repetitions=3
//       --benchmark_report_aggregates_only=true --benchmark_out=docs/data/field_sampling.json
//   /usr/bin/python3 postprocess/plot_field_sampling.py docs/data/field_sampling.json docs/figures/field_sampling.png
#include <benchmark/benchmark.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <numbers>
#include <random>
#include <string>
#include <vector>

#include "forcing/drift.h"
#include "forcing/gridded_field.h"
#include "openfoam_case.h"
#include "probed_field.h"
#include "quadrature_samples.h"
#include "resample.h"
#include "scene/floe_field.h"
#include "thread_clock.h"

using namespace polyfloe;
using forcing::Quadrature;
using geometry::Vec2;

namespace {

std::string g_case = "of_cases/strait";
constexpr double kGrid[] = {40.0, 20.0, 10.0, 5.0, 2.5};  // source 0..4; source 5 = direct
constexpr Quadrature kRules[] = {Quadrature::centroid, Quadrature::degree1, Quadrature::degree2, Quadrature::degree4};
constexpr double kRho = 1025.0, kDraft = 0.9, kFormC = 0.20, kMomentC = 0.14, kSkinC = 0.0055;

struct Floe {
  std::vector<Vec2> world;  // vertices, counter-clockwise [m]
  Vec2 centre;
  double area, side_area, radius;
  forcing::FloeMotion motion;
};

struct Setup {
  std::shared_ptr<const std::vector<coupling::MeshSnapshot>> snaps;
  std::unique_ptr<coupling::ProbedField> direct;
  std::vector<Floe> floes;
  std::vector<forcing::DriftLoad> reference;
};

// The ocean load on one floe with the bottom samples `s` (levers from the centre) in `field`.
forcing::DriftLoad ocean_load(const Floe& f, const tsupport::Samples& s, const forcing::VelocityField& field,
                              std::vector<forcing::Vec3>& pts, std::vector<Vec2>& u, std::vector<double>& fx,
                              std::vector<double>& fy) {
  forcing::DriftLoad l;
  const std::size_t nv = f.world.size(), nq = s.rx.size();
  pts.resize(std::max(nv, nq));
  u.resize(pts.size());
  fx.resize(nq);
  fy.resize(nq);
  forcing::side_sample_points(f.world, kDraft, {pts.data(), nv});
  field.sample(0.0, {pts.data(), nv}, {u.data(), nv});
  const std::span<const Vec2> water{u.data(), nv};
  forcing::add_form_drag(l, kFormC, kRho, kDraft, f.motion, f.world, water);
  const double omega_w = forcing::water_rotation_rate(f.world, water, f.area);
  forcing::add_moment_drag(l, kMomentC, kRho, f.side_area, f.radius, f.motion.omega - omega_w);
  for (std::size_t q = 0; q < nq; ++q) pts[q] = {f.centre.x() + s.rx[q], f.centre.y() + s.ry[q], -kDraft};
  field.sample(0.0, {pts.data(), nq}, {u.data(), nq});
  for (std::size_t q = 0; q < nq; ++q) {
    fx[q] = u[q].x();
    fy[q] = u[q].y();
  }
  forcing::add_surface_drag(l, kSkinC, kRho, f.motion, {s.rx, s.ry, s.w}, fx, fy);
  return l;
}

const Setup& setup() {
  static const Setup s = [] {
    Setup r;
    r.snaps = std::make_shared<const std::vector<coupling::MeshSnapshot>>(
        coupling::read_openfoam_case(g_case, {coupling::TimeSelection::Kind::latest, {}}));
    r.direct = std::make_unique<coupling::ProbedField>(r.snaps, forcing::GriddedFieldOptions{});
    scene::FloeFieldSpec spec;
    spec.region_min = {-100.0, 0.0};
    spec.region_max = {2000.0, 1000.0};
    spec.concentration = 0.3;
    spec.size_min = 10.0;
    spec.size_max = 60.0;
    spec.seed = 3;
    std::mt19937_64 rng(17);
    std::normal_distribution<double> n01;
    for (const dynamics::BodyDesc& d : scene::generate_floe_field(spec, 920.0, 0).floes) {
      Floe f;
      f.centre = d.position;
      const double c = std::cos(d.yaw), sn = std::sin(d.yaw);
      bool wet = true;
      for (const Vec2& p : d.shape->vertices()) {
        const Vec2 w = d.position + geometry::rotate(p, c, sn);
        f.world.push_back(w);
        // wholly in the water, 5 m clear of every wall
        wet = wet && r.direct->contains({w.x() + 5.0 * p.normalized().x(), w.y() + 5.0 * p.normalized().y(), -0.5});
      }
      if (!wet) continue;
      f.area = d.shape->area();
      double perimeter = 0.0;
      for (std::size_t i = 0; i < f.world.size(); ++i)
        perimeter += (f.world[(i + 1) % f.world.size()] - f.world[i]).norm();
      f.side_area = perimeter * kDraft;
      f.radius = std::sqrt(f.area / std::numbers::pi);
      const Vec2 water = r.direct->at({f.centre.x(), f.centre.y(), -kDraft}, 0.0);
      f.motion = {f.centre, water + 0.05 * Vec2(n01(rng), n01(rng)), 2e-3 * n01(rng)};
      r.floes.push_back(std::move(f));
    }
    std::vector<forcing::Vec3> pts;
    std::vector<Vec2> u;
    std::vector<double> fx, fy;
    for (const Floe& f : r.floes)
      r.reference.push_back(ocean_load(f, tsupport::refined(f.world, f.centre, 3), *r.direct, pts, u, fx, fy));
    std::fprintf(stderr, "field sampling: %zu floes wholly in the water of %s\n", r.floes.size(), g_case.c_str());
    return r;
  }();
  return s;
}

void BM_FieldSampling(benchmark::State& state) {
  const Setup& s = setup();
  const int source = static_cast<int>(state.range(0));
  const Quadrature rule = kRules[state.range(1)];
  std::shared_ptr<const forcing::VelocityField> field;
  double grid_mb = 0.0;
  if (source < 5) {
    coupling::GridSpec spec;
    spec.cell = kGrid[source];
    auto grid = std::make_shared<const forcing::GridData>(coupling::resample(*s.snaps, spec, true, "strait").grid);
    grid_mb = 1e-6 * static_cast<double>(grid->u.size() * 2 * sizeof(double) + grid->wet.size());
    field = std::make_shared<forcing::GriddedField>(grid, forcing::GriddedFieldOptions{});
  } else {
    field = std::shared_ptr<const forcing::VelocityField>(s.direct.get(), [](const forcing::VelocityField*) {});
  }
  std::vector<tsupport::Samples> samples(s.floes.size());
  double points = 0.0;
  for (std::size_t i = 0; i < s.floes.size(); ++i) {
    tsupport::add_rule(s.floes[i].world, s.floes[i].centre, rule, samples[i]);
    points += static_cast<double>(samples[i].rx.size() + s.floes[i].world.size());
  }
  std::vector<forcing::Vec3> pts;
  std::vector<Vec2> u;
  std::vector<double> fx, fy;
  double ef2 = 0.0, f2 = 0.0, et2 = 0.0, t2 = 0.0;
  for (std::size_t i = 0; i < s.floes.size(); ++i) {
    const forcing::DriftLoad l = ocean_load(s.floes[i], samples[i], *field, pts, u, fx, fy);
    ef2 += (l.force - s.reference[i].force).squaredNorm();
    f2 += s.reference[i].force.squaredNorm();
    et2 += std::pow(l.torque - s.reference[i].torque, 2);
    t2 += std::pow(s.reference[i].torque, 2);
  }
  double sink = 0.0;
  const double cpu0 = tsupport::thread_cpu_seconds();
  for (auto _ : state)
    for (std::size_t i = 0; i < s.floes.size(); ++i)
      sink += ocean_load(s.floes[i], samples[i], *field, pts, u, fx, fy).torque;
  const double floes = static_cast<double>(s.floes.size());
  state.counters["ns_per_floe"] =
      1e9 * (tsupport::thread_cpu_seconds() - cpu0) / (floes * static_cast<double>(state.iterations()));
  state.counters["points_per_floe"] = points / floes;
  state.counters["force_error"] = std::sqrt(ef2 / f2);
  state.counters["torque_error"] = std::sqrt(et2 / t2);
  state.counters["grid_mb"] = grid_mb;
  state.counters["sink"] = sink;  // keeps the loop live (DoNotOptimize on a double read afterwards is unsafe here)
  char label[64];
  if (source < 5)
    std::snprintf(label, sizeof label, "grid %g m %s", kGrid[source], std::string(to_string(rule)).c_str());
  else
    std::snprintf(label, sizeof label, "direct %s", std::string(to_string(rule)).c_str());
  state.SetLabel(label);
}

}  // namespace

BENCHMARK(BM_FieldSampling)->ArgsProduct({{0, 1, 2, 3, 4, 5}, {0, 1, 2, 3}})->Unit(benchmark::kMicrosecond);

int main(int argc, char** argv) {
  // --case DIR (ours), the rest to Google Benchmark.
  std::vector<char*> rest{argv[0]};
  for (int i = 1; i < argc; ++i) {
    if (std::strcmp(argv[i], "--case") == 0 && i + 1 < argc)
      g_case = argv[++i];
    else
      rest.push_back(argv[i]);
  }
  int n = static_cast<int>(rest.size());
  benchmark::Initialize(&n, rest.data());
  try {
    (void)setup();
  } catch (const std::exception& e) {
    std::fprintf(stderr, "bench_field_sampling: %s\n(run the case first: of_cases/strait/Allrun --quick)\n", e.what());
    return 2;
  }
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
