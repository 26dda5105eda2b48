// The World's drift model (dynamics/drift_model.h) on its own: the damped inverse solves the final kick's
// 3 x 3 system, the linear model gives back the load where it was fitted and b - D v elsewhere, linear steps
// follow the step count and never start a run, and a kept inverse holds for its step only.
#include <gtest/gtest.h>

#include <cstring>
#include <random>

#include <Eigen/Dense>

#include "dynamics/drift_model.h"

using namespace polyfloe;
using dynamics::DriftModel;
using geometry::Vec2;

namespace {

// A drift load with a random symmetric positive definite drag part (a sum of quadratic-drag samples), a Coriolis
// part and a force and torque.
forcing::DriftLoad random_load(std::mt19937& rng) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  forcing::DriftLoad d;
  for (int k = 0; k < 6; ++k) d.add(50.0 * (1.5 + u(rng)), Vec2{3.0 * u(rng), 3.0 * u(rng)}, Vec2{u(rng), u(rng)}, 1.0);
  d.mf = 20.0 * u(rng);
  d.force = {100.0 * u(rng), 100.0 * u(rng)};
  d.torque = 300.0 * u(rng);
  return d;
}

// A = M + dt D_drag + dt/2 C as the documentation of DriftModel::DampedInverse writes it.
Eigen::Matrix3d kick_matrix(const forcing::DriftLoad& d, double dt, double mass, double inertia) {
  forcing::DriftLoad drag = d;
  drag.mf = 0.0;
  Eigen::Matrix3d c = Eigen::Matrix3d::Zero();
  c(0, 1) = -d.mf;
  c(1, 0) = d.mf;
  return Eigen::Vector3d(mass, mass, inertia).asDiagonal().toDenseMatrix() + dt * drag.damping() + 0.5 * dt * c;
}

double relative(const Eigen::Vector3d& a, const Eigen::Vector3d& b) { return (a - b).norm() / b.norm(); }

}  // namespace

TEST(DriftModel, TheDampedInverseSolvesTheFinalKicksSystem) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int k = 0; k < 200; ++k) {
    const forcing::DriftLoad d = random_load(rng);
    const double dt = 0.01 + 5.0 * (1.0 + u(rng)), mass = 1e3 * (1.5 + u(rng)), inertia = 5e3 * (1.5 + u(rng));
    const Vec2 p{1e3 * u(rng), 1e3 * u(rng)};
    const double pw = 1e3 * u(rng);
    const DriftModel::Velocity v = DriftModel::apply(DriftModel::damped_inverse(d, dt, mass, inertia), p, pw);
    const Eigen::Vector3d av = kick_matrix(d, dt, mass, inertia) * Eigen::Vector3d(v.u.x(), v.u.y(), v.w);
    ASSERT_LT(relative(av, {p.x(), p.y(), pw}), 1e-12) << "case " << k;
  }
}

TEST(DriftModel, TheLinearModelGivesBackTheLoadWhereItWasFittedAndBMinusDvElsewhere) {
  std::mt19937 rng(11);
  DriftModel m;
  m.resize(3, false);
  for (std::size_t i = 0; i < 3; ++i) m.load(i) = random_load(rng);
  const forcing::DriftLoad fitted = m.load(1);
  m.resize_linear_model(3);
  const Vec2 vs{0.3, -0.2};
  const double ws = 0.01;
  m.fit_linear_model(1, vs, ws);
  m.set_linear_load(1, vs, ws);
  EXPECT_LT(relative({m.load(1).force.x(), m.load(1).force.y(), m.load(1).torque},
                     {fitted.force.x(), fitted.force.y(), fitted.torque}),
            1e-14);
  // Elsewhere: F_d(v) = F_d(v*) - D (v - v*), the damping matrix (drag and Coriolis) unchanged.
  const Vec2 v{-0.5, 0.4};
  const double w = -0.02;
  m.set_linear_load(1, v, w);
  const Eigen::Vector3d expected = Eigen::Vector3d(fitted.force.x(), fitted.force.y(), fitted.torque) -
                                   fitted.damping() * Eigen::Vector3d(v.x() - vs.x(), v.y() - vs.y(), w - ws);
  EXPECT_LT(relative({m.load(1).force.x(), m.load(1).force.y(), m.load(1).torque}, expected), 1e-12);
  EXPECT_EQ(m.load(1).dxx, fitted.dxx);
  EXPECT_EQ(m.load(1).mf, fitted.mf);
}

TEST(DriftModel, LinearStepsFollowTheStepCountAndNeverStartARun) {
  forcing::DriftSettings s;
  s.treatment = forcing::DriftTreatment::semi_implicit;
  s.update_every = 4;
  DriftModel m;
  EXPECT_FALSE(m.linear_step(s, 5, 0.1, 2)) << "no loads yet: the first evaluation is a full one";
  m.resize(2, true);
  m.resize_linear_model(2);
  EXPECT_FALSE(m.linear_step(s, 4, 0.1, 2)) << "every 4th step is a full evaluation";
  EXPECT_TRUE(m.linear_step(s, 5, 0.1, 2));
  EXPECT_TRUE(m.linear_step(s, 7, 0.1, 2));
  EXPECT_FALSE(m.linear_step(s, 8, 0.1, 2));
  EXPECT_FALSE(m.linear_step(s, 5, 0.0, 2)) << "compute_forces from outside (dt = 0) evaluates anew";
  EXPECT_FALSE(m.linear_step(s, 5, 0.1, 3)) << "a body was added since";
  s.update_every = 1;
  EXPECT_FALSE(m.linear_step(s, 5, 0.1, 2));
  s.update_every = 4;
  s.treatment = forcing::DriftTreatment::explicit_step;
  EXPECT_FALSE(m.linear_step(s, 5, 0.1, 2)) << "the linear model is the semi-implicit treatment's";
}

TEST(DriftModel, AKeptInverseHoldsForItsStepOnly) {
  std::mt19937 rng(3);
  DriftModel m;
  m.resize(1, false);
  m.load(0) = random_load(rng);
  const double mass = 2e3, inertia = 9e3;
  ASSERT_TRUE(m.begin_inverses(1, 0.5)) << "none kept yet";
  m.keep_inverse(0, 0.5, mass, inertia);
  m.set_inverses_dt(0.5);
  EXPECT_FALSE(m.begin_inverses(1, 0.5));
  EXPECT_TRUE(m.begin_inverses(1, 0.25));
  // Held for dt = 0.5: the kept one, whatever the load is now; for another dt computed from the load now.
  const forcing::DriftLoad before = m.load(0);
  m.load(0).dxx *= 3.0;
  const DriftModel::DampedInverse kept = m.inverse_of(0, 0.5, mass, inertia);
  const DriftModel::DampedInverse old = DriftModel::damped_inverse(before, 0.5, mass, inertia);
  EXPECT_EQ(std::memcmp(&kept, &old, sizeof kept), 0);
  const DriftModel::DampedInverse other = m.inverse_of(0, 0.25, mass, inertia);
  const DriftModel::DampedInverse now = DriftModel::damped_inverse(m.load(0), 0.25, mass, inertia);
  EXPECT_EQ(std::memcmp(&other, &now, sizeof other), 0);
  // New loads from outside: nothing is kept.
  m.resize(1, false);
  EXPECT_TRUE(m.begin_inverses(1, 0.5));
}
