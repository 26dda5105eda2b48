// The paper's cube-plate check swept over the strike angle (Fig. 3 of the paper; docs/validation.md "Cube-plate"):
// v'/v0 and w' r / v0 after the first impact (the contact list empty again) for alpha = 0..45 degrees, for each
// narrow phase and contact-point model, against Eq. 6-7; and the error against the contact stiffness and the step.
// A benchmark driver: prints a table and writes JSON for postprocess/plot_cube_plate.py.
//
//   build/tests/bench_cube_plate [-o FILE.json]   (default FILE: cube_plate.json; about 10 s)
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <numbers>
#include <string>
#include <vector>

#include "cube_plate.h"

namespace {

using namespace polyfloe;
using dynamics::ContactPointModel;
using dynamics::SpatialNarrowPhase;

std::string num(double x) {
  char b[40];
  std::snprintf(b, sizeof b, "%.9g", x);
  return b;
}

struct Config {
  const char* name;
  SpatialNarrowPhase narrow;
  ContactPointModel point;
};

}  // namespace

int main(int argc, char** argv) {
  std::string out_file = "cube_plate.json";
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "-o" && i + 1 < argc) {
      out_file = argv[++i];
    } else {
      std::fprintf(stderr, "usage: %s [-o FILE.json]\n", argv[0]);
      return 2;
    }
  }
  constexpr double deg = std::numbers::pi / 180.0;
  std::vector<double> angles{0.0, 0.25, 0.5, 1.0, 2.0, 3.0, 4.0};
  for (int a = 5; a <= 45; a += 5) angles.push_back(a);
  const Config configs[] = {
      {"sat, witness", SpatialNarrowPhase::sat, ContactPointModel::witness},
      {"sat, manifold", SpatialNarrowPhase::sat, ContactPointModel::manifold},
      {"libccd gjk_epa, its point", SpatialNarrowPhase::gjk_epa, ContactPointModel::witness},
      {"libccd gjk_epa_tiebreak, its point", SpatialNarrowPhase::gjk_epa_tiebreak, ContactPointModel::witness},
      {"libccd mpr, its point", SpatialNarrowPhase::mpr, ContactPointModel::witness},
      {"libccd gjk_epa_tiebreak, manifold", SpatialNarrowPhase::gjk_epa_tiebreak, ContactPointModel::manifold},
  };
  std::string json = "{\n  \"restitution\": 0.5,\n  \"angles_deg\": [";
  for (std::size_t i = 0; i < angles.size(); ++i) json += (i ? ", " : "") + num(angles[i]);
  json += "],\n  \"analytic\": {\"v_ratio\": [";
  for (std::size_t i = 0; i < angles.size(); ++i)
    json += (i ? ", " : "") + num(test::cube_plate_analytic(angles[i] * deg, 0.5).v_ratio);
  json += "], \"w_ratio\": [";
  for (std::size_t i = 0; i < angles.size(); ++i)
    json += (i ? ", " : "") + num(test::cube_plate_analytic(angles[i] * deg, 0.5).w_ratio);
  json += "]},\n  \"runs\": [\n";
  std::printf("%-36s %6s %9s %9s %9s %9s %10s %6s\n", "method", "alpha", "v'/v0", "Eq.7", "wr/v0", "Eq.6", "spurious",
              "points");
  bool first = true;
  for (const Config& c : configs) {
    std::string v, w, sp, pts, steps;
    double worst = 0.0;
    for (std::size_t i = 0; i < angles.size(); ++i) {
      test::CubePlateSetup s;
      s.alpha = angles[i] * deg;
      s.narrow_phase = c.narrow;
      s.contact_point = c.point;
      const auto r = test::run_cube_plate(s);
      const auto ref = test::cube_plate_analytic(s.alpha, 0.5);
      if (angles[i] >= 5.0)
        worst = std::max({worst, std::abs(r.v_ratio - ref.v_ratio), std::abs(r.w_ratio - ref.w_ratio)});
      std::printf("%-36s %6.2f %9.5f %9.5f %9.5f %9.5f %10.2e %6d\n", c.name, angles[i], r.v_ratio, ref.v_ratio,
                  r.w_ratio, ref.w_ratio, r.spurious_w, r.manifold_points);
      const char* sep = i ? ", " : "";
      v += sep + num(r.v_ratio);
      w += sep + num(r.w_ratio);
      sp += sep + num(r.spurious_w);
      pts += sep + std::to_string(r.manifold_points);
      steps += sep + std::to_string(r.steps);
    }
    std::printf("%-36s worst |error| over alpha = 5..45: %.4f (of v0)\n\n", c.name, worst);
    json += std::string(first ? "" : ",\n") + "    {\"method\": \"" + c.name + "\", \"v_ratio\": [" + v +
            "], \"w_ratio\": [" + w + "], \"spurious_w\": [" + sp + "], \"manifold_points\": [" + pts +
            "], \"contact_steps\": [" + steps + "], \"worst_error_5_45\": " + num(worst) + "}";
    first = false;
  }
  json += "\n  ],\n  \"stiffness\": [\n";
  // The error against the contact stiffness: the rigid-impact formulas assume an instantaneous impact; a finite
  // contact duration lets the cube turn while it is pushed.
  std::printf("%-10s %6s %12s %12s %12s\n", "E [Pa]", "alpha", "t_c [s]", "|dv|/v0", "|dw| r/v0");
  first = true;
  for (double e : {1e8, 1e9, 1e10, 1e11}) {
    for (double a : {15.0, 30.0}) {
      test::CubePlateSetup s;
      s.alpha = a * deg;
      s.youngs_modulus = e;
      const auto r = test::run_cube_plate(s);
      const auto ref = test::cube_plate_analytic(s.alpha, 0.5);
      const double t_c = test::make_cube_plate(s).shortest_contact_duration(1.0);
      std::printf("%-10.0e %6.1f %12.3e %12.2e %12.2e\n", e, a, t_c, std::abs(r.v_ratio - ref.v_ratio),
                  std::abs(r.w_ratio - ref.w_ratio));
      json += std::string(first ? "" : ",\n") + "    {\"youngs_modulus\": " + num(e) + ", \"alpha_deg\": " + num(a) +
              ", \"v_error\": " + num(std::abs(r.v_ratio - ref.v_ratio)) +
              ", \"w_error\": " + num(std::abs(r.w_ratio - ref.w_ratio)) + "}";
      first = false;
    }
  }
  json += "\n  ]\n}\n";
  if (const std::filesystem::path parent = std::filesystem::path(out_file).parent_path(); !parent.empty()) {
    std::error_code ec;
    std::filesystem::create_directories(parent, ec);  // -o results/cube_plate.json on a fresh checkout
  }
  std::FILE* f = std::fopen(out_file.c_str(), "w");
  if (!f || std::fputs(json.c_str(), f) < 0 || std::fclose(f) != 0) {
    std::fprintf(stderr, "cannot write %s\n", out_file.c_str());
    return 1;
  }
  std::printf("wrote %s\n", out_file.c_str());
  return 0;
}
