// The paper's cube-plate check swept over the strike angle (Fig. 3 of the paper; docs/validation.md "Cube-plate"):
// v'/v0 and w' r / v0 after the first impact (the contact list empty again) for alpha = 0..45 degrees, for each
// narrow phase and contact-point model, against Eq. 6-7; and the error against the contact stiffness and the step.
// A benchmark driver: prints a table and writes JSON for postprocess/plot_cube_plate.py.
//
//   build/tests/bench_cube_plate [-o FILE.json]   (default FILE: cube_plate.json; about 10 s)
#include <cmath>
#include <cstdio>
#include <numbers>
#include <optional>
#include <string>
#include <vector>

#include "cube_plate.h"
#include "driver_args.h"
#include "json_out.h"

namespace {

using namespace polyfloe;
using dynamics::ContactPointModel;
using dynamics::SpatialNarrowPhase;
using tsupport::Json;

struct Config {
  const char* name;
  SpatialNarrowPhase narrow;
  ContactPointModel point;
};

}  // namespace

int main(int argc, char** argv) {
  std::string out_file = "cube_plate.json";
  CLI::App app("The cube-plate impact against equations (6) and (7), every spatial contact method", "bench_cube_plate");
  app.add_option("-o", out_file, "the JSON file written")->capture_default_str();
  if (const std::optional<int> stop = tsupport::parse_args(app, argc, argv)) return *stop;
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
  Json json = {{"restitution", 0.5}, {"angles_deg", angles}};
  Json& analytic = json["analytic"];
  for (double a : angles) {
    analytic["v_ratio"].push_back(test::cube_plate_analytic(a * deg, 0.5).v_ratio);
    analytic["w_ratio"].push_back(test::cube_plate_analytic(a * deg, 0.5).w_ratio);
  }
  json["runs"] = Json::array();
  std::printf("%-36s %6s %9s %9s %9s %9s %10s %6s\n", "method", "alpha", "v'/v0", "Eq.7", "wr/v0", "Eq.6", "spurious",
              "points");
  for (const Config& c : configs) {
    Json run = {{"method", c.name}};
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
      run["v_ratio"].push_back(r.v_ratio);
      run["w_ratio"].push_back(r.w_ratio);
      run["spurious_w"].push_back(r.spurious_w);
      run["manifold_points"].push_back(r.manifold_points);
      run["contact_steps"].push_back(r.steps);
    }
    std::printf("%-36s worst |error| over alpha = 5..45: %.4f (of v0)\n\n", c.name, worst);
    run["worst_error_5_45"] = worst;
    json["runs"].push_back(run);
  }
  // The error against the contact stiffness: the rigid-impact formulas assume an instantaneous impact; a finite
  // contact duration lets the cube turn while it is pushed.
  std::printf("%-10s %6s %12s %12s %12s\n", "E [Pa]", "alpha", "t_c [s]", "|dv|/v0", "|dw| r/v0");
  json["stiffness"] = Json::array();
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
      json["stiffness"].push_back({{"youngs_modulus", e},
                                   {"alpha_deg", a},
                                   {"v_error", std::abs(r.v_ratio - ref.v_ratio)},
                                   {"w_error", std::abs(r.w_ratio - ref.w_ratio)}});
    }
  }
  if (!tsupport::write_json(out_file, json)) return 1;
  std::printf("wrote %s\n", out_file.c_str());
  return 0;
}
