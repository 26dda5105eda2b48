// Drift forcing: accuracy against cost of the bottom-drag quadrature (the chart of docs/figures/drift_quadrature.png)
// and the cost of the whole drift stage per floe.
//
// BM_SkinDragQuadrature/field/rule: the skin drag (Eq. 13) on every floe of the paper's field (power-law sizes
// 5-100 m, 5-10 corners, 50 % of a 1 km square, ~1.2k floes) in a sheared current (u = 0.2 m/s + 2e-3 1/s y,
// across the square) or a Rankine vortex (core 300 m, 0.5 m/s, centred); each floe moves at the water velocity at
// its centre plus a random 0.05 m/s and +-2e-3 rad/s. Counters: ns per floe (levers turned, field sampled, kernel),
// torque and force error: RMS over floes of (value - reference) / RMS of the reference, the reference being the
// degree-5 rule on every fan triangle cut into 4^4 pieces (its own error, against 4^3 pieces, is printed).
// BM_DriftStage/rule: World::step on 1.2k floes spread out (no contacts), every drift term on, uniform current
// and wind (the channel scene's forcing): the drift stage's time per floe from the World's profile.
//   ./build/tests/bench_drift --benchmark_repetitions=5 --benchmark_report_aggregates_only=true
//   /usr/bin/python3 postprocess/plot_drift_quadrature.py RESULTS.json docs/figures/drift_quadrature.png
#include <benchmark/benchmark.h>

#include <cmath>
#include <cstdio>
#include <map>
#include <random>
#include <vector>

#include "dynamics/world.h"
#include "forcing/analytic_fields.h"
#include "forcing/drift.h"
#include "forcing/quadrature.h"
#include "scene/floe_field.h"
#include "quadrature_samples.h"
#include "thread_clock.h"

using namespace polyfloe;
using forcing::Quadrature;
using geometry::Vec2;

namespace {

constexpr Quadrature kRules[] = {Quadrature::centroid, Quadrature::degree1, Quadrature::degree2, Quadrature::degree4,
                                 Quadrature::degree5};
constexpr double kK = 0.5 * 0.0055 * 1025.0;  // 1/2 c_w rho_w
constexpr double kDraft = 0.9;

struct Floe {
  std::vector<Vec2> local;  // body frame, centroid at the origin
  Vec2 centre;
  double yaw;
  forcing::FloeMotion motion;
};

const std::vector<dynamics::BodyDesc>& field_floes() {
  static const std::vector<dynamics::BodyDesc> floes = [] {
    scene::FloeFieldSpec spec;
    spec.region_min = {0.0, 0.0};
    spec.region_max = {1000.0, 1000.0};
    spec.concentration = 0.5;
    spec.seed = 3;
    return scene::generate_floe_field(spec, 920.0, 0).floes;
  }();
  return floes;
}

std::shared_ptr<const forcing::VelocityField> make(int field) {
  forcing::FieldSpec s;
  if (field == 0) {
    s.kind = forcing::FieldKind::linear;
    s.velocity = {0.2, 0.0};
    s.origin = {500.0, 500.0};
    s.gradient << 0.0, 2e-3, 0.0, 0.0;
  } else {
    s.kind = forcing::FieldKind::rankine;
    s.origin = {500.0, 500.0};
    s.core_radius = 300.0;
    s.max_speed = 0.5;
  }
  return forcing::make_field(s);
}

std::vector<Floe> floes_in(int field) {
  const auto f = make(field);
  std::mt19937_64 rng(17);
  std::normal_distribution<double> n01;
  std::vector<Floe> out;
  for (const auto& d : field_floes()) {
    Floe fl{d.shape->vertices(), d.position, d.yaw, {}};
    const Vec2 water = f->at({d.position.x(), d.position.y(), -kDraft}, 0.0);
    fl.motion = {d.position, water + 0.05 * Vec2(n01(rng), n01(rng)), 2e-3 * n01(rng)};
    out.push_back(std::move(fl));
  }
  return out;
}

using tsupport::add_rule;
using tsupport::Samples;

std::vector<Vec2> world_polygon(const Floe& f) {
  std::vector<Vec2> v;
  const double c = std::cos(f.yaw), s = std::sin(f.yaw);
  for (const Vec2& p : f.local) v.push_back(f.centre + geometry::rotate(p, c, s));
  return v;
}

Samples refined(const Floe& f, int levels) { return tsupport::refined(world_polygon(f), f.centre, levels); }

forcing::DriftLoad skin(const Floe& f, const Samples& s, const forcing::VelocityField& field) {
  std::vector<forcing::Vec3> pts(s.rx.size());
  std::vector<Vec2> u(s.rx.size());
  std::vector<double> fx(s.rx.size()), fy(s.rx.size());
  for (std::size_t q = 0; q < pts.size(); ++q) pts[q] = {f.centre.x() + s.rx[q], f.centre.y() + s.ry[q], -kDraft};
  field.sample(0.0, pts, u);
  for (std::size_t q = 0; q < u.size(); ++q) {
    fx[q] = u[q].x();
    fy[q] = u[q].y();
  }
  forcing::DriftLoad l;
  forcing::add_surface_drag(l, 0.0055, 1025.0, f.motion, {s.rx, s.ry, s.w}, fx, fy);
  return l;
}

struct Reference {
  std::vector<Floe> floes;
  std::vector<forcing::DriftLoad> exact;
};
const Reference& reference(int field) {
  static std::map<int, Reference> cache;
  if (auto it = cache.find(field); it != cache.end()) return it->second;
  Reference r;
  r.floes = floes_in(field);
  const auto f = make(field);
  double d2 = 0.0, t2 = 0.0;
  for (const Floe& fl : r.floes) {
    r.exact.push_back(skin(fl, refined(fl, 4), *f));
    const forcing::DriftLoad coarse = skin(fl, refined(fl, 3), *f);
    d2 += std::pow(coarse.torque - r.exact.back().torque, 2);
    t2 += std::pow(r.exact.back().torque, 2);
  }
  std::fprintf(stderr, "reference (%s): RMS torque difference between 4^3 and 4^4 pieces %.1e\n",
               field == 0 ? "shear" : "vortex", std::sqrt(d2 / t2));
  return cache.emplace(field, std::move(r)).first->second;
}

void BM_SkinDragQuadrature(benchmark::State& state) {
  const int field = static_cast<int>(state.range(0));
  const Quadrature rule = kRules[state.range(1)];
  const Reference& ref = reference(field);
  const auto f = make(field);
  // Body-frame rule points per floe (precomputed, as the World does).
  std::vector<Samples> local(ref.floes.size());
  for (std::size_t i = 0; i < ref.floes.size(); ++i) add_rule(ref.floes[i].local, {0.0, 0.0}, rule, local[i]);
  // Accuracy.
  double et2 = 0.0, t2 = 0.0, ef2 = 0.0, f2 = 0.0;
  std::size_t points = 0;
  for (std::size_t i = 0; i < ref.floes.size(); ++i) {
    const Floe& fl = ref.floes[i];
    Samples s = local[i];
    const double c = std::cos(fl.yaw), sn = std::sin(fl.yaw);
    for (std::size_t q = 0; q < s.rx.size(); ++q) {
      const double x = s.rx[q], y = s.ry[q];
      s.rx[q] = c * x - sn * y;
      s.ry[q] = sn * x + c * y;
    }
    points += s.rx.size();
    const forcing::DriftLoad l = skin(fl, s, *f);
    et2 += std::pow(l.torque - ref.exact[i].torque, 2);
    t2 += std::pow(ref.exact[i].torque, 2);
    ef2 += (l.force - ref.exact[i].force).squaredNorm();
    f2 += ref.exact[i].force.squaredNorm();
  }
  // Cost: the World's per-floe work for one surface - turn the levers, sample the field, run the kernel.
  std::size_t max_q = 0;
  for (const Samples& s : local) max_q = std::max(max_q, s.rx.size());
  std::vector<double> rx(max_q), ry(max_q), fx(max_q), fy(max_q);
  std::vector<forcing::Vec3> pts(max_q);
  std::vector<Vec2> u(max_q);
  double sink = 0.0;
  const double cpu0 = tsupport::thread_cpu_seconds();
  for (auto _ : state) {
    for (std::size_t i = 0; i < ref.floes.size(); ++i) {
      const Floe& fl = ref.floes[i];
      const Samples& s = local[i];
      const std::size_t n = s.rx.size();
      const double c = std::cos(fl.yaw), sn = std::sin(fl.yaw);
      for (std::size_t q = 0; q < n; ++q) {
        rx[q] = c * s.rx[q] - sn * s.ry[q];
        ry[q] = sn * s.rx[q] + c * s.ry[q];
        pts[q] = {fl.centre.x() + rx[q], fl.centre.y() + ry[q], -kDraft};
      }
      f->sample(0.0, {pts.data(), n}, {u.data(), n});
      for (std::size_t q = 0; q < n; ++q) {
        fx[q] = u[q].x();
        fy[q] = u[q].y();
      }
      forcing::DriftLoad l;
      forcing::add_surface_drag(l, 0.0055, 1025.0, fl.motion, {{rx.data(), n}, {ry.data(), n}, {s.w.data(), n}},
                                {fx.data(), n}, {fy.data(), n});
      sink += l.torque;
    }
  }
  benchmark::DoNotOptimize(sink);
  const double floes = static_cast<double>(ref.floes.size());
  state.counters["ns_per_floe"] = 1e9 * (tsupport::thread_cpu_seconds() - cpu0) / (floes * state.iterations());
  state.counters["points_per_floe"] = static_cast<double>(points) / floes;
  state.counters["torque_error"] = std::sqrt(et2 / t2);
  state.counters["force_error"] = std::sqrt(ef2 / f2);
  state.SetLabel(std::string(field == 0 ? "shear " : "vortex ") + std::string(to_string(rule)));
}

void BM_DriftStage(benchmark::State& state) {
  const Quadrature rule = kRules[state.range(0)];
  dynamics::WorldSettings ws;
  ws.drift.quadrature = rule;
  ws.drift.ocean = forcing::make_field(forcing::FieldSpec::uniform({4.0, 0.0}));
  ws.drift.wind = forcing::make_field(forcing::FieldSpec::uniform({20.0, 0.0}));
  dynamics::World w(ws);
  for (dynamics::BodyDesc d : field_floes()) {
    d.position *= 3.0;  // spread out: no contacts
    w.add_body(d);
  }
  w.compute_forces(0.0);
  w.step(0.01);
  const dynamics::StepProfile p0 = w.profile();
  for (auto _ : state) w.step(0.01);
  const dynamics::StepProfile& p = w.profile();
  const double floe_steps = static_cast<double>(w.size()) * static_cast<double>(p.steps - p0.steps);
  state.counters["drift_ns_per_floe"] = 1e9 * (p.forcing - p0.forcing) / floe_steps;
  state.counters["step_ns_per_floe"] = 1e9 *
                                       ((p.forcing + p.integrate + p.shapes + p.broad + p.narrow_and_law) -
                                        (p0.forcing + p0.integrate + p0.shapes + p0.broad + p0.narrow_and_law)) /
                                       floe_steps;
  state.SetLabel(std::string(to_string(rule)));
}

}  // namespace

BENCHMARK(BM_SkinDragQuadrature)->ArgsProduct({{0, 1}, {0, 1, 2, 3, 4}})->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_DriftStage)->DenseRange(0, 4)->Unit(benchmark::kMicrosecond);

BENCHMARK_MAIN();
