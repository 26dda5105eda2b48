// The planar force models against the measures a contact potential must meet, for corner-rich ice (the figures
// of docs/validation.md, "Force models: energy, convergence, flat faces"; each printed line is quoted there):
//
//   a. A frictionless, perfectly elastic (e = 1) gas of 50 random convex floes of 3-8 corners, elongated up to 4:1,
//      6-15 m across, moving at up to 3 m/s in a box of four fixed walls, at 40 steps per contact (each model's
//      automatic step at 3 m/s: for the foundation model 9 times smaller), run to 200 collisions (contact starts,
//      walls included) with the contact-resolution guard of `polyfloe run` applied every step. Reference: the
//      initial kinetic energy, at every contact-free step. The study tier (ContactEnergyStudy, label study: about
//      2 CPU-minutes for the foundation model alone) runs the same gas to 1,000 collisions, the figures docs quote;
//      the error grows with the collisions (and the speeds of squeezed floes with it), so the 200-collision run
//      asserts the same bounds with the margins stated at each. The
//      gas shares its energy out: small floes squeezed between two others reach 50-65 m/s (`polyfloe run`'s speed
//      guard, 20 x the reference speed, would stop both runs there: a scene like this needs a higher
//      run.reference_speed).
//   b. Single frictionless e = 1 impacts of 10 m squares closing at 1 m/s, corner against corner (head on, and
//      2 m off the line of centres) and corner against face (the corner's bisector along the normal, and yawed
//      15 degrees), from 40 to 640 steps per contact of the Hertz models' step (for the foundation model, whose
//      own step is 5 times smaller here, the harder test). Reference: the kinetic energy before the impact; the
//      convergence order is the least-squares slope of log |error| against log (steps per contact).
//   c. A 20 m x 2 m floe pressed flat on a fixed wall by a steady load (5 mm static overlap, as test_coulomb),
//      started 1e-4 rad off flat, e = 0.5, mu = 0.3: its tilt after 100 s.
//
// The bounds are regression bounds on the models as they are, not the targets of an energy-conserving law: the gas
// is chaotic (a last-bit change moves its figures), so its bounds are loose and catch a blow-up; the single
// impacts are not, and their bounds are about twice what is measured.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <string>
#include <utility>
#include <vector>

#include "dynamics/world.h"
#include "floe_gas.h"
#include "run/simulation.h"
#include "test_support.h"

using namespace polyfloe;
using geometry::Vec2;

namespace {

dynamics::WorldSettings frictionless_elastic(contact::ForceModel model) {
  dynamics::WorldSettings ws;
  ws.contact.force_model = model;
  ws.contact.friction = 0.0;
  ws.contact.restitution = 1.0;
  ws.drift = forcing::DriftSettings::none();
  return ws;
}

std::string name_of(contact::ForceModel m) { return contact::force_model_name(m); }

using Pair = std::pair<dynamics::BodyId, dynamics::BodyId>;

// The touching pairs, sorted (a vector reused step after step: the gas runs millions of steps).
void touching(const dynamics::World& w, std::vector<Pair>& out) {
  out.clear();
  for (const auto& c : w.contacts()) out.push_back({w.id(c.a), w.id(c.b)});
  std::sort(out.begin(), out.end());
}

struct GasOutcome {
  int collisions = 0;
  std::uint64_t steps = 0, contact_steps = 0, free_steps = 0;
  double max_error = 0.0;   // max |KE - KE0| / KE0 over the contact-free steps
  double last_error = 0.0;  // (KE - KE0) / KE0 at the last contact-free step
  std::string stopped;      // the run guard's message, if a run would have stopped (exit 3) there
};

GasOutcome corner_rich_gas(contact::ForceModel model, int collisions) {
  constexpr int kFloes = 50;
  constexpr double kSpacing = 16.0, kSpeed = 3.0;
  const tsupport::FloeShapes shapes{
      .corners_min = 3, .corners_max = 8, .size_min = 6.0, .size_max = 15.0, .aspect_min = 0.25, .aspect_max = 1.0};
  const tsupport::Field field = tsupport::make_field(29, kFloes, kSpacing, kSpeed, 0.1, shapes);
  dynamics::World w(frictionless_elastic(model));
  for (const auto& b : field.bodies) w.add_body(b);
  // The box: four fixed walls 10 m thick just outside the placement grid (8 x 7 sites).
  const double half_x = 4.0 * kSpacing + 2.0, half_y = 3.5 * kSpacing + 2.0;
  auto horizontal =
      std::make_shared<const geometry::ConvexPolygon>(geometry::ConvexPolygon::rectangle(2.0 * half_x + 20.0, 10.0));
  auto vertical =
      std::make_shared<const geometry::ConvexPolygon>(geometry::ConvexPolygon::rectangle(10.0, 2.0 * half_y + 20.0));
  w.add_body({.id = 1, .shape = horizontal, .position = {0.0, -half_y - 5.0}, .motion = dynamics::Motion::fixed});
  w.add_body({.id = 2, .shape = horizontal, .position = {0.0, half_y + 5.0}, .motion = dynamics::Motion::fixed});
  w.add_body({.id = 3, .shape = vertical, .position = {-half_x - 5.0, 0.0}, .motion = dynamics::Motion::fixed});
  w.add_body({.id = 4, .shape = vertical, .position = {half_x + 5.0, 0.0}, .motion = dynamics::Motion::fixed});
  // Each model's automatic step: for the foundation model 9 times smaller than the others' here (it resolves a
  // flat face pressed on a face, whose contact lasts the same at any speed: at the others' step a 20 m/s flat
  // impact on a wall lasted 9.5 steps and the guard stopped the run).
  const double dt = w.shortest_contact_duration(kSpeed) / 40.0;
  const double e0 = w.kinetic_energy();
  GasOutcome o;
  std::vector<Pair> before, now;
  while (o.collisions < collisions && o.steps < 40000000) {
    const dynamics::StepReport& report = w.step(dt);
    ++o.steps;
    try {  // a contact resolved by too few steps stops `polyfloe run` (its speed guard is left out: see above)
      run::check_contact_resolution(w, report, dt);
    } catch (const run::InstabilityError& e) {
      o.stopped = e.what();
      break;
    }
    touching(w, now);
    // New pairs: those of `now` not in `before` (both sorted).
    for (std::size_t i = 0, j = 0; i < now.size(); ++i) {
      while (j < before.size() && before[j] < now[i]) ++j;
      o.collisions += (j < before.size() && before[j] == now[i]) ? 0 : 1;
    }
    o.contact_steps += now.size();
    if (now.empty()) {
      ++o.free_steps;
      o.last_error = (w.kinetic_energy() - e0) / e0;
      o.max_error = std::max(o.max_error, std::abs(o.last_error));
    }
    std::swap(before, now);
  }
  std::printf(
      "corner-rich gas, %s: %d collisions in %llu steps (dt %.3e s, %.1f s), %llu contact-steps; at the "
      "%llu contact-free steps max |KE - E0|/E0 = %.3e, last %+.3e; fastest floe %.2f m/s (3 at the start)"
      "%s%s\n",
      name_of(model).c_str(), o.collisions, static_cast<unsigned long long>(o.steps), dt,
      static_cast<double>(o.steps) * dt, static_cast<unsigned long long>(o.contact_steps),
      static_cast<unsigned long long>(o.free_steps), o.max_error, o.last_error, w.max_speed(),
      o.stopped.empty() ? "" : "; the run guard stopped it: ", o.stopped.c_str());
  return o;
}

// One impact of two 10 m x 10 m floes (h = 1 m) closing at 1 m/s along x: A at yaw_a, B at yaw_b, B's line of
// motion `offset` m off A's, at `steps` steps per Hertz contact (or per contact of the model's own automatic step).
// Returns (KE after - KE before) / KE before.
double impact_energy_error(contact::ForceModel model, double yaw_a, double yaw_b, double offset, double steps,
                           bool own_step = false) {
  dynamics::World w(frictionless_elastic(model));
  auto sq = std::make_shared<const geometry::ConvexPolygon>(geometry::ConvexPolygon::rectangle(10, 10));
  const double reach_a = 5.0 * (std::abs(std::cos(yaw_a)) + std::abs(std::sin(yaw_a)));
  const double reach_b = 5.0 * (std::abs(std::cos(yaw_b)) + std::abs(std::sin(yaw_b)));
  const double gap = 0.05;
  w.add_body({.id = 1, .shape = sq, .position = {-reach_a - 0.5 * gap, 0.0}, .yaw = yaw_a, .velocity = {0.5, 0.0}});
  w.add_body({.id = 2, .shape = sq, .position = {reach_b + 0.5 * gap, offset}, .yaw = yaw_b, .velocity = {-0.5, 0.0}});
  // (as the gas; or the model's own automatic step)
  const double dt = (own_step ? w.shortest_contact_duration(1.0) : w.shortest_hertz_contact_duration(1.0)) / steps;
  const double e0 = w.kinetic_energy();
  bool touched = false;
  for (int i = 0; i < 50000000; ++i) {
    w.step(dt);
    if (!w.contacts().empty()) touched = true;
    if (touched && w.contacts().empty()) break;
  }
  EXPECT_TRUE(touched);
  return (w.kinetic_energy() - e0) / e0;
}

// The gas to `collisions` collisions, within each model's bound: the bounds catch a blow-up and are the same at 200
// and at 1,000 collisions (the error grows with the collisions).
void expect_gas_within_bound(contact::ForceModel model, int collisions) {
  const GasOutcome o = corner_rich_gas(model, collisions);
  EXPECT_GE(o.collisions, collisions);
  EXPECT_GT(o.free_steps, 1000u);
  EXPECT_TRUE(o.stopped.empty()) << o.stopped;
  const double bound[] = {10.0, 5e-2, 1e-4};
  EXPECT_LT(o.max_error, bound[static_cast<int>(model)]);
}

}  // namespace

class ContactEnergy : public ::testing::TestWithParam<contact::ForceModel> {};

// Measured at 200 collisions: centroid 2.9e-2, gradient 4.8e-4, foundation 2.3e-10 (fastest floes 14, 9 and 12 m/s),
// under the bounds by 340x, 100x and 4e5x. The study below goes on to 1,000 collisions, where squeezed floes reach
// 50-65 m/s and the errors grow to 3.0, 8.3e-3 and 1.4e-6: the same bounds, nearer.
TEST_P(ContactEnergy, CornerRichElasticGasReachesTwoHundredCollisionsWithinEachModelsEnergyBound) {
  expect_gas_within_bound(GetParam(), 200);
}

class ContactEnergyStudy : public ::testing::TestWithParam<contact::ForceModel> {};

// Measured: centroid 3.0 (the energy more than doubles: the force is not a gradient), gradient 8.3e-3, foundation
// 1.4e-6 (its target: 1e-4; 8.6e-6 at the others' step, where a run can meet a flat impact too fast).
TEST_P(ContactEnergyStudy, CornerRichElasticGasReachesAThousandCollisionsWithinEachModelsEnergyBound) {
  expect_gas_within_bound(GetParam(), 1000);
}

TEST_P(ContactEnergy, SingleCornerImpactsStayWithinEachModelsEnergyBoundAtFortyStepsPerContact) {
  struct Case {
    const char* name;
    double yaw_a, yaw_b, offset;
  };
  const double q = 0.25 * std::numbers::pi;
  const Case cases[] = {{"corner-corner, head on", q, q, 0.0},
                        {"corner-corner, 2 m off", q, q, 2.0},
                        {"corner-face, bisector on the normal", q, 0.0, 0.0},
                        {"corner-face, yawed 15 deg", q + std::numbers::pi / 12.0, 0.0, 0.0}};
  for (const Case& c : cases) {
    std::vector<double> n_steps, errors;
    std::string row;
    for (double n : {40.0, 80.0, 160.0, 320.0, 640.0}) {
      const double e = impact_energy_error(GetParam(), c.yaw_a, c.yaw_b, c.offset, n);
      n_steps.push_back(std::log(n));
      errors.push_back(std::log(std::max(std::abs(e), 1e-16)));
      char cell[32];
      std::snprintf(cell, sizeof cell, " %+.2e", e);
      row += cell;
    }
    // Least-squares slope of log |error| against log n: the convergence order is its negative.
    const double mx = (n_steps[0] + n_steps[4]) / 2.0;
    double my = 0.0;
    for (double y : errors) my += y / 5.0;
    double sxy = 0.0, sxx = 0.0;
    for (std::size_t k = 0; k < 5; ++k) {
      sxy += (n_steps[k] - mx) * (errors[k] - my);
      sxx += (n_steps[k] - mx) * (n_steps[k] - mx);
    }
    const double order = -sxy / sxx;
    std::printf("%s, %s: energy error at 40, 80, 160, 320, 640 steps per contact:%s; order %.2f\n",
                name_of(GetParam()).c_str(), c.name, row.c_str(), order);
    // At the Hertz models' default step (measured at most: centroid 5.8e-3, a model error that does not shrink with
    // the step; gradient 2.3e-5; foundation 6.3e-7 for the corners, and 1.5e-3 for the pair 2 m off, whose faces
    // are parallel and meet flat: a linear spring that lasts 11 of these steps).
    const double at_40 = std::exp(errors[0]);
    const bool flat = c.offset != 0.0;
    const double bound[] = {1.2e-2, 5e-5, flat ? 3e-3 : 1e-4};
    EXPECT_LT(at_40, bound[static_cast<int>(GetParam())]) << c.name;
    if (GetParam() == contact::ForceModel::foundation) {
      EXPECT_GT(order, 1.7) << c.name;  // measured 2.0-3.0
      if (flat) {
        // At the foundation model's own automatic step, which resolves a flat face pressed on a face.
        const double own = impact_energy_error(GetParam(), c.yaw_a, c.yaw_b, c.offset, 40.0, true);
        std::printf("foundation, %s, at its own automatic step (40 steps per flat contact): %+.2e\n", c.name, own);
        EXPECT_LT(std::abs(own), 2e-4) << c.name;  // measured -1.0e-4 (the faces slide off each other's ends)
      }
    }
  }
}

// A floe pressed flat on a wall: does its face stay on the wall? A model without tilt stiffness lets it roll onto
// a corner.
TEST_P(ContactEnergy, FloePressedFlatOnAWallStaysWithinAMilliradianOfFlatForAHundredSeconds) {
  constexpr double kLength = 20.0, kWidth = 2.0, kDepth = 5e-3;
  dynamics::WorldSettings ws;
  ws.contact.force_model = GetParam();
  ws.contact.friction = 0.3;
  ws.contact.restitution = 0.5;
  ws.drift = forcing::DriftSettings::none();
  dynamics::World w(ws);
  const double e_star = ws.contact.youngs_modulus / (2.0 * (1.0 - ws.contact.poisson_ratio * ws.contact.poisson_ratio));
  const double k_n = 4.0 / 3.0 * e_star * std::sqrt(std::sqrt(kLength * kWidth / std::numbers::pi));
  const double f_n = k_n * std::pow(kDepth, 1.5);
  auto wall = std::make_shared<const geometry::ConvexPolygon>(geometry::ConvexPolygon::rectangle(200.0, 10.0));
  auto floe = std::make_shared<const geometry::ConvexPolygon>(geometry::ConvexPolygon::rectangle(kLength, kWidth));
  w.add_body({.id = 1, .shape = wall, .position = {0.0, -5.0}, .motion = dynamics::Motion::fixed});
  // Started at the overlap where the model carries the load: 5 mm for the Hertz-type models; for the foundation,
  // whose flat face is stiffer (2 kappa L per metre of overlap), f_n / (2 kappa L).
  const double depth0 = GetParam() == contact::ForceModel::foundation
                            ? f_n / (2.0 * contact::ContactLaw(ws.contact).foundation_modulus() * kLength)
                            : kDepth;
  const int f = w.add_body({.id = 2, .shape = floe, .position = {0.0, 0.5 * kWidth - depth0}, .yaw = 1e-4});
  const double dt = w.shortest_contact_duration(1.0) / 40.0;
  double max_tilt = 0.0;
  while (w.time() < 100.0) {
    w.set_external_load(f, {0.0, -f_n}, 0.0);
    w.step(dt);
    max_tilt = std::max(max_tilt, std::abs(w.yaws()[static_cast<std::size_t>(f)]));
  }
  const double tilt = std::abs(w.yaws()[static_cast<std::size_t>(f)]);
  std::printf("pressed flat on a wall, %s: tilt after 100 s %.3e rad (max %.3e; started at 1e-4)\n",
              name_of(GetParam()).c_str(), tilt, max_tilt);
  // Both keep the face on the wall here (measured: centroid 3.3e-6 rad, at most 1.0e-4; gradient 8.7e-5, at
  // most 5.1e-4): friction holds the gradient model's neutral tilt.
  EXPECT_LT(max_tilt, 1e-3);
}

INSTANTIATE_TEST_SUITE_P(ForceModels, ContactEnergy,
                         ::testing::Values(contact::ForceModel::centroid, contact::ForceModel::gradient,
                                           contact::ForceModel::foundation),
                         [](const auto& info) { return name_of(info.param); });
INSTANTIATE_TEST_SUITE_P(ForceModels, ContactEnergyStudy,
                         ::testing::Values(contact::ForceModel::centroid, contact::ForceModel::gradient,
                                           contact::ForceModel::foundation),
                         [](const auto& info) { return name_of(info.param); });
