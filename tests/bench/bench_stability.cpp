// The time step against the contacts it must resolve: the stability map and the time-step accuracy that the
// speed-accuracy chart uses (docs/performance.md, "Stability map" and "Speed against accuracy"). A benchmark
// driver, not Google Benchmark: it prints tables and writes JSON.
//
//   build/tests/bench_stability [-o FILE.json] [--quick] [--only impacts|packs|cost]...
//   (default FILE: stability_map.json; --only runs the named parts, repeatable; --quick: a smaller grid)
//
// 1. Binary impacts. Floe A is a random convex polygon (5-10 corners, aspect up to 2) of 20 m (area-equivalent
//    diameter), floe B the same kind with 1/r of A's area (mass ratio r), both 1 m thick, random orientations.
//    B moves at v = 1 m/s along -x towards A with a random lateral offset (their y extents overlap); the run starts
//    at the first touch (found by bisection on the narrow phase, so no step is spent approaching) and lasts 12 t_c,
//    where t_c is the Hertz contact duration of the pair (its m*, R*) at v, the duration the automatic time step
//    divides. Grid: Young's modulus E in {1e7, 1e8, 1e9, 1e10} Pa x r in {1, 10, 100}, 24 random pairs per cell;
//    two contact settings: elastic (e = 1, mu = 0) and the scenes' (e = 0.5, mu = 0.3).
//    Each pair runs with dt = t_c / n for n from 1 to 160 steps per contact and a reference at n = 2560.
//    - error: the velocities after the run against the reference, in the energy norm:
//      sqrt(sum m |v - v_ref|^2 + I (w - w_ref)^2) / sqrt(sum m |v0|^2);
//    - stable at n: every pair ends finite and with at most 5 % of its initial kinetic energy more than the
//      reference run ends with (an unresolved contact overshoots and throws the floes apart; the centroid force
//      model alone may gain a little in corner contacts, which the reference shares); the measured critical step
//      is t_c / n_c, n_c the smallest n stable together with every larger n.
//    - predicted: velocity Verlet is stable for dt < 2/omega; at the stiffest point of an undamped Hertz impact
//      omega^2 = (3/2) k_n delta_max^(1/2) / m*, which gives dt = t_c / 2.015 whatever k_n, m* and v (so the map
//      shows the ratio measured / predicted).
// 2. Jammed packs (tests/support/dense_pack.h: ~2,500 floes of ~10 m, 4 contacts each, inside walls),
//    pre-compressed by eps in {2e-4, 2e-3, 1e-2} (overlaps ~2 mm, 2 cm, 9 cm), E = 1e9 Pa, e = 0.5, mu = 0.3,
//    no drift: dt = t_c(1 m/s) / n (the automatic step at reference speed 1 m/s) for n from 1 to 40, 4,000 steps.
//    Unstable: non-finite, or the kinetic energy above max(100 x its value after the first 200 steps, 1 J per floe
//    at 0.01 m/s). Predicted from the run guard's estimate (the step report's shortest contact: the pack's stiffest
//    contact, its approach rate and stored energy as an impact speed) at the start: dt = t_guard / 2.015.
// 3. Cost per floe-step by bottom-quadrature rule (the other axis of the speed-accuracy chart): the 1,500-floe
//    jammed pack with every drift term on (bench_step's DensePack: current 0.2 m/s, wind 10 m/s), 500 steps at
//    dt = t_c(1 m/s) / 40, CPU time of this thread, median of 3. The chart multiplies it by the steps per contact:
//    CPU per floe to simulate one contact duration.
#include <time.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <numbers>
#include <optional>
#include <random>
#include <string>
#include <vector>

#include "contact/narrow_phase_planar.h"
#include "contact_methods.h"
#include "dense_pack.h"
#include "driver_args.h"
#include "json_out.h"
#include "dynamics/world.h"
#include "forcing/analytic_fields.h"
#include "test_support.h"
#include "thread_clock.h"

using namespace polyfloe;
using geometry::Vec2;

namespace {

constexpr double kPredictedSteps = 2.015;  // t_c / (2 / omega_max), see the header
constexpr double kGainLimit = 0.05;        // unstable impact: 5 % of the initial energy gained over the reference

struct Floe {
  std::shared_ptr<const geometry::ConvexPolygon> shape;
  double yaw = 0.0;
};

Floe random_floe(std::mt19937_64& rng, double diameter) {
  std::uniform_real_distribution<double> u(0.0, 1.0);
  const int corners = 5 + static_cast<int>(u(rng) * 6.0);
  const double aspect = 1.0 + u(rng);
  std::vector<Vec2> v = tsupport::random_convex(rng, std::min(corners, 10), aspect, 1.0);
  const auto unit = geometry::ConvexPolygon::from_vertices(v);
  const double scale = 0.5 * diameter / unit.equivalent_radius();
  for (Vec2& p : v) p *= scale;
  return {std::make_shared<const geometry::ConvexPolygon>(geometry::ConvexPolygon::from_vertices(v)),
          2.0 * std::numbers::pi * u(rng)};
}

std::vector<Vec2> placed(const Floe& f, const Vec2& at) {
  std::vector<Vec2> out;
  const double c = std::cos(f.yaw), s = std::sin(f.yaw);
  for (const Vec2& p : f.shape->vertices()) out.push_back(at + geometry::rotate(p, c, s));
  return out;
}

struct ImpactCase {
  Floe a, b;
  Vec2 b_start;  // B's centroid at the first touch (A at the origin)
};

ImpactCase make_impact(std::mt19937_64& rng, double ratio) {
  std::uniform_real_distribution<double> u(0.0, 1.0);
  ImpactCase c;
  c.a = random_floe(rng, 20.0);
  c.b = random_floe(rng, 20.0 / std::sqrt(ratio));
  auto extent = [](const std::vector<Vec2>& v, int axis, bool hi) {
    double e = hi ? -1e300 : 1e300;
    for (const Vec2& p : v) e = hi ? std::max(e, p[axis]) : std::min(e, p[axis]);
    return e;
  };
  const std::vector<Vec2> a = placed(c.a, {0.0, 0.0}), b0 = placed(c.b, {0.0, 0.0});
  // Lateral offset: B's y extent inside A's, so moving along -x it must hit A.
  const double lo = extent(a, 1, false) - extent(b0, 1, false), hi = extent(a, 1, true) - extent(b0, 1, true);
  const double lo_ok = std::min(lo, hi), hi_ok = std::max(lo, hi);
  const double y = lo_ok + (0.1 + 0.8 * u(rng)) * (hi_ok - lo_ok);
  // The first touch along -x: a scan in steps of 1/400 of the sweep finds an overlapping position (the y extents
  // overlap, so one exists), then bisection between it and the last clear one.
  const double x_clear = extent(a, 0, true) - extent(b0, 0, false) + 1.0;
  const double x_past = extent(a, 0, false) - extent(b0, 0, true) - 1.0;
  contact::PlanarContact g;
  double far = x_clear, near = x_clear;
  for (int k = 1; k <= 400; ++k) {
    const double x = x_clear + (x_past - x_clear) * k / 400.0;
    if (contact::planar_overlap(a, placed(c.b, {x, y}), g)) {
      near = x;
      break;
    }
    far = x;
  }
  if (near == x_clear) return make_impact(rng, ratio);  // grazing miss at this resolution: draw another pair
  for (int k = 0; k < 200 && far - near > 1e-12; ++k) {
    const double mid = 0.5 * (far + near);
    const std::vector<Vec2> b = placed(c.b, {mid, y});
    (contact::planar_overlap(a, b, g) ? near : far) = mid;
  }
  c.b_start = {far, y};
  return c;
}

struct Outcome {
  Vec2 va, vb;
  double wa = 0.0, wb = 0.0;
  double energy_before = 0.0, energy_after = 0.0;
  bool finite = true;
  bool touched = false;  // a contact happened during the run
};

struct ContactSetting {
  const char* name;
  double restitution, friction;
};

dynamics::World impact_world(const ImpactCase& c, double youngs, const ContactSetting& cs, double speed) {
  dynamics::WorldSettings ws;
  ws.drift = forcing::DriftSettings::none();
  ws.contact.youngs_modulus = youngs;
  ws.contact.restitution = cs.restitution;
  ws.contact.friction = cs.friction;
  dynamics::World w(ws);
  w.add_body({.id = 1, .shape = c.a.shape, .position = {0.0, 0.0}, .yaw = c.a.yaw});
  w.add_body({.id = 2, .shape = c.b.shape, .position = c.b_start, .yaw = c.b.yaw, .velocity = {-speed, 0.0}});
  return w;
}

double pair_contact_duration(const dynamics::World& w, double speed) {
  const contact::PairCoefficients k = w.contact_law().coefficients(
      w.shape(0).equivalent_radius(), w.shape(1).equivalent_radius(), w.mass(0), w.mass(1));
  return contact::hertz_contact_duration(k.k_n, k.m_star, speed);
}

Outcome run_impact(const ImpactCase& c, double youngs, const ContactSetting& cs, double steps_per_contact,
                   double speed) {
  dynamics::World w = impact_world(c, youngs, cs, speed);
  const double tc = pair_contact_duration(w, speed);
  const double dt = tc / steps_per_contact;
  const int steps = static_cast<int>(std::ceil(12.0 * steps_per_contact));
  Outcome o;
  o.energy_before = w.kinetic_energy();
  w.compute_forces(dt);
  for (int k = 0; k < steps; ++k) {
    w.step(dt);
    o.touched = o.touched || !w.contacts().empty();
    if (!std::isfinite(w.kinetic_energy()) || w.max_speed() > 1e3 * speed) {
      o.finite = false;
      break;
    }
  }
  o.va = w.velocities()[0];
  o.vb = w.velocities()[1];
  o.wa = w.angular_velocities()[0];
  o.wb = w.angular_velocities()[1];
  o.energy_after = w.kinetic_energy();
  o.finite = o.finite && std::isfinite(o.energy_after);
  return o;
}

double energy_norm_error(const dynamics::World& w, const Outcome& o, const Outcome& ref) {
  const double e = w.mass(0) * (o.va - ref.va).squaredNorm() + w.inertia(0) * (o.wa - ref.wa) * (o.wa - ref.wa) +
                   w.mass(1) * (o.vb - ref.vb).squaredNorm() + w.inertia(1) * (o.wb - ref.wb) * (o.wb - ref.wb);
  return std::sqrt(e / (2.0 * o.energy_before));  // sum m |v0|^2 = 2 KE0
}

using tsupport::percentile;

}  // namespace

int main(int argc, char** argv) {
  std::string out_file = "stability_map.json";
  bool quick = false;
  std::vector<std::string> only;
  CLI::App app("The stability map: binary impacts, jammed packs and the cost against the steps per contact",
               "bench_stability");
  app.add_option("-o", out_file, "the JSON file written")->capture_default_str();
  app.add_flag("--quick", quick, "one modulus, two mass ratios, 6 pairs per cell");
  app.add_option("--only", only, "run only these parts (repeatable; default all)")
      ->check(CLI::IsMember({"impacts", "packs", "cost"}));
  if (const std::optional<int> stop = tsupport::parse_args(app, argc, argv)) return *stop;
  auto wanted = [&](const char* part) {
    return only.empty() || std::find(only.begin(), only.end(), part) != only.end();
  };
  const auto t_start = std::chrono::steady_clock::now();
  const std::vector<double> youngs = quick ? std::vector<double>{1e9} : std::vector<double>{1e7, 1e8, 1e9, 1e10};
  const std::vector<double> ratios = quick ? std::vector<double>{1, 100} : std::vector<double>{1, 10, 100};
  const int samples = quick ? 6 : 24;
  const std::vector<double> ns{1, 1.25, 1.5, 1.75, 2, 2.5, 3, 4, 5, 7, 10, 14, 20, 28, 40, 80, 160};
  const double n_ref = 2560.0, speed = 1.0;
  const ContactSetting settings[] = {{"elastic", 1.0, 0.0}, {"scenes", 0.5, 0.3}};

  // (a measurement without a value, NaN or infinite, is written as -1)
  using tsupport::or_none;
  tsupport::Json json = {{"predicted_steps_per_contact", 2.015}};
  if (wanted("impacts")) {
    json["steps_per_contact"] = or_none(ns);
    json["impacts"] = tsupport::Json::array();
    std::printf("Binary impacts, %d random pairs per cell, v = %.1f m/s; n = steps per contact (dt = t_c / n)\n",
                samples, speed);
    std::printf("%-8s %8s %6s  %14s  %12s  %12s  %12s  %12s\n", "setting", "E [Pa]", "ratio", "critical n_c",
                "err n=5 p50", "err n=5 p90", "err n=40 p50", "err n=40 p90");
    for (const ContactSetting& cs : settings) {
      for (double E : youngs) {
        for (double r : ratios) {
          std::mt19937_64 rng(20261123u + static_cast<std::uint64_t>(r) * 7919u);
          // Pairs whose reference run has a contact (all of them, as built; checked, so that no pair counts as stable
          // for never touching).
          std::vector<ImpactCase> cases;
          std::vector<Outcome> refs;
          while (static_cast<int>(cases.size()) < samples) {
            const ImpactCase c = make_impact(rng, r);
            const Outcome ref = run_impact(c, E, cs, n_ref, speed);
            if (!ref.touched) {
              std::fprintf(stderr, "a pair did not touch in its reference run; drawing another\n");
              continue;
            }
            cases.push_back(c);
            refs.push_back(ref);
          }
          std::vector<dynamics::World> worlds;  // each pair's masses and inertias, for the error norm
          for (const ImpactCase& c : cases) worlds.push_back(impact_world(c, E, cs, speed));
          std::vector<double> p50, p90, worst_gain;
          std::vector<bool> stable;
          for (double n : ns) {
            std::vector<double> errs;
            bool ok = true;
            double gain = 0.0;
            for (std::size_t s = 0; s < cases.size(); ++s) {
              const Outcome o = run_impact(cases[s], E, cs, n, speed);
              if (!o.finite) {
                ok = false;
                errs.push_back(INFINITY);
                gain = INFINITY;
                continue;
              }
              errs.push_back(energy_norm_error(worlds[s], o, refs[s]));
              // Energy gained over what the converged run ends with (the centroid force model itself does not conserve
              // energy exactly in corner contacts: docs/validation.md), as a fraction of the energy at the start.
              const double g = (o.energy_after - refs[s].energy_after) / o.energy_before;
              gain = std::max(gain, g);
              if (g > kGainLimit) ok = false;
            }
            p50.push_back(percentile(errs, 0.5));
            p90.push_back(percentile(errs, 0.9));
            worst_gain.push_back(gain);
            stable.push_back(ok);
          }
          // Smallest n stable together with every larger n.
          double n_c = NAN;
          for (std::size_t k = ns.size(); k-- > 0;) {
            if (!stable[k]) break;
            n_c = ns[k];
          }
          auto at = [&](const std::vector<double>& v, double n) {
            for (std::size_t k = 0; k < ns.size(); ++k)
              if (ns[k] == n) return v[k];
            return std::nan("");
          };
          std::printf("%-8s %8.0e %6.0f  %14.2f  %12.2e  %12.2e  %12.2e  %12.2e\n", cs.name, E, r, n_c, at(p50, 5),
                      at(p90, 5), at(p50, 40), at(p90, 40));
          std::vector<double> stable_d(stable.begin(), stable.end());
          json["impacts"].push_back({{"setting", cs.name},
                                     {"youngs_modulus", E},
                                     {"mass_ratio", r},
                                     {"samples", samples},
                                     {"critical_steps_per_contact", or_none(n_c)},
                                     {"error_p50", or_none(p50)},
                                     {"error_p90", or_none(p90)},
                                     {"energy_gain_max", or_none(worst_gain)},
                                     {"stable", or_none(stable_d)}});
        }
      }
    }
  }

  if (wanted("packs")) {
    json["packs"] = tsupport::Json::array();

    // 2. Jammed packs.
    const std::vector<double> pack_ns{1, 1.25, 1.5, 2, 2.5, 3, 4, 5, 7, 10, 20, 40};
    const std::vector<double> eps_list =
        quick ? std::vector<double>{2e-4, 1e-2} : std::vector<double>{2e-4, 2e-3, 1e-2};
    const int pack_steps = quick ? 1500 : 4000;
    std::printf("\nJammed packs (~2,500 floes, E = 1e9 Pa, e = 0.5, mu = 0.3), dt = t_c(1 m/s) / n, %d steps\n",
                pack_steps);
    std::printf("%-8s %10s %12s %14s %16s\n", "eps", "overlap", "critical n_c", "guard n (start)", "guard / binary");
    for (double eps : eps_list) {
      tsupport::PackSpec ps;
      ps.eps = eps;
      const tsupport::Pack pack = tsupport::make_pack(2500, ps, 5u);
      std::vector<bool> stable;
      std::vector<double> growth;
      double guard_n = NAN, overlap = 0.0;
      for (double n : pack_ns) {
        dynamics::WorldSettings ws;
        ws.drift = forcing::DriftSettings::none();
        dynamics::World w(ws);
        for (const auto& d : pack.bodies) w.add_body(d);
        const double tc = w.shortest_contact_duration(1.0);
        const double dt = tc / n;
        w.compute_forces(dt);
        if (std::isnan(guard_n)) {
          const auto res = w.report().shortest;
          guard_n = tc / res.duration;  // the pack's stiffest contact needs guard_n x the binary steps per contact
          double depth = 0.0;
          for (const auto& c : w.contacts()) depth += c.geometry.depth;
          overlap = w.contacts().empty() ? 0.0 : depth / static_cast<double>(w.contacts().size());
        }
        double e200 = 0.0;
        bool ok = true;
        for (int k = 0; k < pack_steps; ++k) {
          w.step(dt);
          if (k == 199) e200 = w.kinetic_energy();
          if (!std::isfinite(w.kinetic_energy()) || w.max_speed() > 100.0) {
            ok = false;
            break;
          }
        }
        const double floor = 0.5 * (w.mass(0)) * 1e-4 * pack.floes;  // every floe at 0.01 m/s
        const double e_end = w.kinetic_energy();
        ok = ok && e_end <= std::max(100.0 * e200, floor);
        stable.push_back(ok);
        growth.push_back(ok ? e_end / std::max(e200, 1e-300) : INFINITY);
      }
      double n_c = NAN;
      for (std::size_t k = pack_ns.size(); k-- > 0;) {
        if (!stable[k]) break;
        n_c = pack_ns[k];
      }
      std::printf("%-8.0e %8.1f mm %12.2f %14.2f %16.2f\n", eps, 1e3 * overlap, n_c, guard_n * kPredictedSteps,
                  guard_n);
      std::vector<double> stable_d(stable.begin(), stable.end());
      json["packs"].push_back({{"eps", eps},
                               {"floes", pack.floes},
                               {"mean_overlap", overlap},
                               {"critical_steps_per_contact", or_none(n_c)},
                               {"guard_steps_per_contact", guard_n * kPredictedSteps},
                               {"steps_per_contact", or_none(pack_ns)},
                               {"energy_growth", or_none(growth)},
                               {"stable", or_none(stable_d)}});
    }
  }

  if (wanted("cost")) {
    json["step_cost"] = tsupport::Json::array();

    // 3. Step cost per quadrature rule.
    std::printf("\nStep cost, 1,500-floe jammed pack with every drift term, one thread (median of 3 x 500 steps)\n");
    const tsupport::Pack small = tsupport::make_pack(1500, tsupport::PackSpec{}, 7u);
    const std::pair<const char*, forcing::Quadrature> rules[] = {{"centroid", forcing::Quadrature::centroid},
                                                                 {"degree1", forcing::Quadrature::degree1},
                                                                 {"degree2", forcing::Quadrature::degree2},
                                                                 {"degree4", forcing::Quadrature::degree4},
                                                                 {"degree5", forcing::Quadrature::degree5}};
    for (const auto& [name, rule] : rules) {
      std::vector<double> us;
      for (int rep = 0; rep < 3; ++rep) {
        dynamics::WorldSettings ws;
        ws.drift.ocean = forcing::make_field(forcing::FieldSpec::uniform({0.2, 0.05}));
        ws.drift.wind = forcing::make_field(forcing::FieldSpec::uniform({8.0, 6.0}));
        ws.drift.quadrature = rule;
        dynamics::World w(ws);
        for (const auto& d : small.bodies) w.add_body(d);
        const double dt = w.shortest_contact_duration(1.0) / 40.0;
        w.compute_forces(0.0);
        for (int k = 0; k < 5; ++k) w.step(dt);
        const double t0 = tsupport::thread_cpu_seconds();
        const int steps = quick ? 100 : 500;
        for (int k = 0; k < steps; ++k) w.step(dt);
        us.push_back(1e6 * (tsupport::thread_cpu_seconds() - t0) / (static_cast<double>(steps) * small.floes));
      }
      const double med = percentile(us, 0.5);
      std::printf("  %-9s %.3f us per floe-step\n", name, med);
      json["step_cost"].push_back({{"quadrature", name}, {"us_per_floe_step", med}});
    }
  }
  if (!tsupport::write_json(out_file, json)) return 1;
  const double secs = std::chrono::duration<double>(std::chrono::steady_clock::now() - t_start).count();
  std::printf("\nwrote %s (%.0f s)\n", out_file.c_str(), secs);
  return 0;
}
