// Bonds between elements (bonds/bond_set.h) against closed forms: the static stretch of a bonded chain (a bar of
// modulus E), tensile failure at the bond strength and its linear scaling, compression that never breaks a bond,
// failure of a face once fewer than 2 points hold, contact suppressed while bonded and restored after, momentum
// conservation, the critical time step bound, corner pairs, and a square-element cantilever against
// Euler-Bernoulli. Frozen sheets built by the scene (scene/ice_sheet.h) are in test_frozen_sheet.cpp.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <limits>
#include <numeric>

#include "bond_support.h"
#include "bonds/bond_set.h"
#include "dynamics/world.h"
#include "test_support.h"

using namespace polyfloe;
using geometry::Vec2;
using namespace tsupport::bond;

namespace {

std::shared_ptr<const geometry::ConvexPolygon> square(double side) {
  const double h = side / 2;
  return tsupport::shape_of({{-h, -h}, {h, -h}, {h, h}, {-h, h}});
}

// A row of `n` squares of side `s` along x (element 0 at the origin), bonded face to face. Element 0 is fixed when
// `anchor_first`.
dynamics::World chain(int n, double s, const bonds::BondMaterial& m, bool anchor_first = true) {
  dynamics::WorldSettings ws;
  ws.drift = forcing::DriftSettings::none();
  ws.contact.youngs_modulus = kE;
  ws.contact.poisson_ratio = kNu;
  dynamics::World w(ws);
  for (int i = 0; i < n; ++i) {
    w.add_body({.id = static_cast<dynamics::BodyId>(i),
                .shape = square(s),
                .position = {i * s, 0.0},
                .thickness = kH,
                .density = kRho,
                .motion = (i == 0 && anchor_first) ? dynamics::Motion::fixed : dynamics::Motion::dynamic});
  }
  bonds::BondSet b(m);
  for (int i = 0; i + 1 < n; ++i) {
    const double x = (i + 0.5) * s;
    b.add_face({.a = i,
                .b = i + 1,
                .id_a = static_cast<std::uint64_t>(i),
                .id_b = static_cast<std::uint64_t>(i + 1),
                .p0 = {x, -s / 2},
                .p1 = {x, s / 2},
                .thickness = kH,
                .centre_a = {i * s, 0.0},
                .centre_b = {(i + 1) * s, 0.0}});
  }
  w.set_bonds(std::move(b));
  return w;
}

TEST(Bonds, ChainStretchesLikeABarOfModulusE) {
  // n elements of side s, the first fixed, a force F on the last: the chain of n - 1 bonded faces stretches by
  // F (n - 1) s / (E s h) (each face: two half-elements of length s/2 in series). Settled with damping.
  const int n = 6;
  const double s = 10.0, F = 2.0e5;
  dynamics::World w = chain(n, s, material());
  w.set_external_load(n - 1, {F, 0.0}, 0.0);
  const double dt = safe_dt(w);
  for (int k = 0; k < 40000; ++k) w.step(dt);
  const double stretch = w.positions()[n - 1].x() - (n - 1) * s;
  const double expected = F * (n - 1) * s / (kE * s * kH);
  EXPECT_NEAR(stretch / expected, 1.0, 1e-6) << "stretch " << stretch << " m";
  EXPECT_LT(std::abs(w.velocities()[n - 1].x()), 1e-9);
  EXPECT_EQ(w.bonds()->intact_faces(), static_cast<std::size_t>(n - 1));
  // The stress in each face is F / (s h), uniform along the chain.
  for (std::size_t p = 0; p < w.bonds()->points(); ++p) EXPECT_NEAR(w.bonds()->point_sigma(p), F / (s * kH), 1e-3);
}

// Pulls element 1 of a bonded pair away from the fixed element 0 with a force growing at `rate` [N/s] and returns
// the force at which the face failed [N].
double tensile_failure_force(double strength, double rate) {
  const double s = 10.0;
  dynamics::World w = chain(2, s, material(strength));
  const double dt = safe_dt(w);
  while (w.bonds()->intact_faces() == 1) {
    w.set_external_load(1, {rate * (w.time() + dt), 0.0}, 0.0);
    w.step(dt);
    if (w.time() > 1e3) return NAN;
  }
  return rate * w.time();
}

TEST(Bonds, TensileFailureAtTheStrengthScalesLinearly) {
  // A face of area s h under a slowly growing pull fails when sigma = F / (s h) passes the tensile strength.
  const double s = 10.0, area = s * kH;
  std::vector<double> strengths{0.1e6, 0.5e6, 1.0e6, 1.5e6}, forces;
  for (double st : strengths) {
    const double f = tensile_failure_force(st, st * area / 10.0);  // reach the strength in about 10 s
    forces.push_back(f);
    EXPECT_NEAR(f / (st * area), 1.0, 0.01) << "strength " << st;
  }
  // Linear fit through the four points: R^2.
  const double mx = std::accumulate(strengths.begin(), strengths.end(), 0.0) / 4;
  const double my = std::accumulate(forces.begin(), forces.end(), 0.0) / 4;
  double sxy = 0, sxx = 0, syy = 0;
  for (int i = 0; i < 4; ++i) {
    sxy += (strengths[i] - mx) * (forces[i] - my);
    sxx += (strengths[i] - mx) * (strengths[i] - mx);
    syy += (forces[i] - my) * (forces[i] - my);
  }
  const double r2 = sxy * sxy / (sxx * syy);
  EXPECT_GT(r2, 0.9999);
  std::printf("tensile failure force / (strength x area): %.4f %.4f %.4f %.4f; R^2 = %.6f\n",
              forces[0] / (0.1e6 * area), forces[1] / (0.5e6 * area), forces[2] / (1.0e6 * area),
              forces[3] / (1.5e6 * area), r2);
}

TEST(Bonds, CompressionAloneNeverBreaks) {
  const double s = 10.0;
  dynamics::World w = chain(3, s, material(0.1e6));
  w.set_external_load(2, {-5.0e7, 0.0}, 0.0);  // 5 MPa of compression, 50 x the tensile strength
  const double dt = safe_dt(w);
  for (int k = 0; k < 5000; ++k) w.step(dt);
  EXPECT_EQ(w.bonds()->intact_faces(), 2u);
  EXPECT_EQ(w.bonds()->intact_points(), 8u);
  EXPECT_TRUE(w.contacts().empty()) << "bonded elements must not also touch through the contact law";
}

TEST(Bonds, FaceFailsWhenFewerThanTwoPointsHoldThenContactActs) {
  // Turn element 1 about the face's lower end: the upper points open first and fail one by one; the face goes
  // when only one point is left, after which the two touch through the ordinary contact law.
  const double s = 10.0;
  bonds::BondMaterial m = material(0.2e6);
  m.points_per_face = 4;
  dynamics::World w = chain(2, s, m);
  w.set_external_load(1, {0.0, 0.0}, 2.0e5);  // counter-clockwise torque on element 1
  const double dt = safe_dt(w);
  std::size_t seen_partial = 0;
  while (w.bonds()->intact_faces() == 1 && w.time() < 50.0) {
    w.step(dt);
    const std::size_t left = w.bonds()->intact_points();
    if (left > 0 && left < 4) seen_partial = std::max(seen_partial, 4 - left);
    w.set_external_load(1, {0.0, 0.0}, 2.0e5 * (1.0 + w.time()));
  }
  ASSERT_EQ(w.bonds()->intact_faces(), 0u);
  EXPECT_GE(seen_partial, 1u) << "some points failed before the face";
  EXPECT_EQ(w.bonds()->intact_points(), 0u);
  EXPECT_TRUE(std::isfinite(w.bonds()->face_broken_time(0)));
  EXPECT_FALSE(w.bonds()->bonded(0, 1));
  // Pushed back into element 0, element 1 now meets it through the contact law.
  w.set_external_load(1, {-1.0e6, 0.0}, 0.0);
  w.set_velocity(1, {-0.5, 0.0}, 0.0);
  for (int k = 0; k < 20000 && w.contacts().empty(); ++k) w.step(dt);
  EXPECT_FALSE(w.contacts().empty());
}

TEST(Bonds, MomentumAndAngularMomentumConserved) {
  // A free 3 x 3 block of bonded squares, spinning and shaken: the bond forces are internal.
  dynamics::WorldSettings ws;
  ws.drift = forcing::DriftSettings::none();
  dynamics::World w(ws);
  const double s = 5.0;
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> U(-1.0, 1.0);
  for (int j = 0; j < 3; ++j)
    for (int i = 0; i < 3; ++i)
      w.add_body({.id = static_cast<dynamics::BodyId>(3 * j + i),
                  .shape = square(s),
                  .position = {i * s, j * s},
                  .velocity = {0.3 + 0.01 * U(rng), 0.01 * U(rng)},
                  .angular_velocity = 0.01 * U(rng)});
  bonds::BondSet b(material(1e9));
  auto face = [&](int a, int c, Vec2 p0, Vec2 p1) {
    b.add_face({.a = a,
                .b = c,
                .id_a = static_cast<std::uint64_t>(a),
                .id_b = static_cast<std::uint64_t>(c),
                .p0 = p0,
                .p1 = p1,
                .thickness = 1.0,
                .centre_a = w.positions()[a],
                .centre_b = w.positions()[c]});
  };
  for (int j = 0; j < 3; ++j)
    for (int i = 0; i < 3; ++i) {
      const int k = 3 * j + i;
      if (i < 2) face(k, k + 1, {(i + 0.5) * s, (j - 0.5) * s}, {(i + 0.5) * s, (j + 0.5) * s});
      if (j < 2) face(k, k + 3, {(i - 0.5) * s, (j + 0.5) * s}, {(i + 0.5) * s, (j + 0.5) * s});
    }
  w.set_bonds(std::move(b));
  w.compute_forces(0.0);
  const Vec2 p0 = w.linear_momentum();
  const double l0 = w.angular_momentum();
  const double dt = safe_dt(w);
  for (int k = 0; k < 3000; ++k) w.step(dt);
  EXPECT_LT((w.linear_momentum() - p0).norm(), 1e-12 * p0.norm());
  EXPECT_NEAR(w.angular_momentum(), l0, 1e-10 * std::abs(l0) + 1e-9);
  EXPECT_EQ(w.bonds()->intact_faces(), 12u);
}

TEST(Bonds, CriticalTimeStepIsALowerBound) {
  // Undamped chain, kicked: at the bound (2 / omega_max from Gershgorin) the motion stays bounded; the true limit
  // is above it.
  bonds::BondMaterial m = material(1e12);
  m.damping_ratio = 0.0;
  m.shear_strength = 1e12;
  dynamics::World w = chain(5, 10.0, m, false);
  w.set_velocity(4, {0.01, 0.0}, 0.001);
  const double bound = 2.0 * safe_dt(w);
  w.compute_forces(0.0);
  const double e0 = w.kinetic_energy();
  double e_max = 0.0;
  for (int k = 0; k < 20000; ++k) {
    w.step(0.99 * bound);
    e_max = std::max(e_max, w.kinetic_energy());
  }
  EXPECT_LT(e_max, 1.5 * e0) << "energy grew: the bound is not a stable step";
}

TEST(Bonds, CriticalTimeStepAccountsForDamping) {
  // Heavily damped bonds (zeta = 0.7) under a load: stable at the bound and settles to the static stretch, while
  // the undamped bound (2.9 times longer here) blows up.
  for (double zeta : {0.1, 0.7, 1.0}) {
    SCOPED_TRACE(zeta);
    bonds::BondMaterial m = material(1e12);
    m.shear_strength = 1e12;
    m.damping_ratio = zeta;
    dynamics::World w = chain(12, 10.0, m);
    w.set_external_load(11, {2.0e5, 0.0}, 0.0);
    const double bound = 2.0 * safe_dt(w);
    for (int k = 0; k < 20000; ++k) w.step(0.99 * bound);
    EXPECT_NEAR((w.positions()[11].x() - 110.0) / (2.0e5 * 11 / kE), 1.0, 1e-3);
  }
  bonds::BondMaterial m = material(1e12);
  m.shear_strength = 1e12;
  m.damping_ratio = 0.7;
  dynamics::World w = chain(12, 10.0, m);
  w.set_external_load(11, {2.0e5, 0.0}, 0.0);
  const double z = 1.4, undamped = 2.0 * safe_dt(w) / (std::sqrt(1.0 + z * z) - z);
  for (int k = 0; k < 2000 && std::abs(w.positions()[11].x()) < 1e6; ++k) w.step(undamped);
  EXPECT_FALSE(std::abs(w.positions()[11].x()) < 1e3) << "the undamped bound should not be stable at zeta = 0.7";
}

TEST(Bonds, BadInputIsRefused) {
  EXPECT_THROW(bonds::BondSet(bonds::BondMaterial{.youngs_modulus = 0.0}), std::invalid_argument);
  EXPECT_THROW(bonds::BondSet(bonds::BondMaterial{.points_per_face = 1}), std::invalid_argument);
  EXPECT_THROW(bonds::BondSet(bonds::BondMaterial{.friction_angle = 2.0}), std::invalid_argument);
  bonds::BondSet b(material());
  EXPECT_THROW(b.add_face({.a = 0, .b = 0, .p0 = {0, 0}, .p1 = {0, 1}, .centre_a = {-1, 0}, .centre_b = {1, 0}}),
               std::invalid_argument);
  EXPECT_THROW(b.add_face({.a = 0, .b = 1, .p0 = {0, 0}, .p1 = {0, 0}, .centre_a = {-1, 0}, .centre_b = {1, 0}}),
               std::invalid_argument);
  EXPECT_THROW(b.add_face({.a = 0, .b = 1, .p0 = {0, 0}, .p1 = {0, 1}, .centre_a = {-1, 0}, .centre_b = {-2, 0}}),
               std::invalid_argument);
  EXPECT_EQ(b.faces(), 0u);
}

}  // namespace

namespace {

TEST(Bonds, CornerPairsAreLockedWhileTheirCornerHolds) {
  // Three squares in an L: 0-1 and 1-2 bonded, 0 and 2 touching only at the corner (5, 5). The corner pair is
  // locked while both faces at that corner hold, and released once either fails.
  bonds::BondSet b(material());
  b.add_face({.a = 0, .b = 1, .p0 = {5, -5}, .p1 = {5, 5}, .centre_a = {0, 0}, .centre_b = {10, 0}});
  b.add_face({.a = 1, .b = 2, .p0 = {5, 5}, .p1 = {15, 5}, .centre_a = {10, 0}, .centre_b = {10, 10}});
  const int faces[] = {0, 1};
  b.add_corner_pair(0, 2, faces);
  EXPECT_TRUE(b.bonded(0, 2));
  EXPECT_TRUE(b.bonded(2, 0));
  EXPECT_FALSE(b.bonded(0, 3));
  // Break face 1 by pulling element 2 up.
  const std::vector<Vec2> pos{{0, 0}, {10, 0}, {10, 10.1}};  // 10 MPa of tension on face 1
  const std::vector<double> yaw(3, 0.0), omega(3, 0.0), mass{1e5, 1e5, 1e5};
  const std::vector<Vec2> vel(3, Vec2(0, 0));
  std::vector<Vec2> force(3, Vec2(0, 0));
  std::vector<double> torque(3, 0.0);
  EXPECT_EQ(b.apply({pos, yaw, vel, omega, mass}, force, torque, 1.0), 1);
  EXPECT_TRUE(b.face_intact(0));
  EXPECT_FALSE(b.face_intact(1));
  EXPECT_FALSE(b.bonded(0, 2)) << "the corner is no longer whole: 0 and 2 may now meet by contact";
  const int bad[] = {5};
  EXPECT_THROW(b.add_corner_pair(0, 2, bad), std::invalid_argument);
}

}  // namespace

namespace {

// A strip of nx x ny bonded squares of side s, its left column bonded to a fixed column of squares.
struct Strip {
  dynamics::World world;
  int nx, ny;
  double s;
  int index(int i, int j) const { return j * (nx + 1) + i; }  // i = 0: the fixed column
};

Strip bonded_strip(int nx, int ny, double s, double zeta) {
  dynamics::WorldSettings ws;
  ws.drift = forcing::DriftSettings::none();
  Strip st{dynamics::World(ws), nx, ny, s};
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i <= nx; ++i)
      st.world.add_body({.id = static_cast<dynamics::BodyId>(st.index(i, j)),
                         .shape = square(s),
                         .position = {i * s, j * s},
                         .thickness = kH,
                         .density = kRho,
                         .motion = i == 0 ? dynamics::Motion::fixed : dynamics::Motion::dynamic});
  bonds::BondMaterial m = material(1e12);
  m.shear_strength = 1e12;
  m.damping_ratio = zeta;
  bonds::BondSet b(m);
  const auto& pos = st.world.positions();
  auto face = [&](int a, int c, Vec2 p0, Vec2 p1) {
    b.add_face({.a = a,
                .b = c,
                .id_a = static_cast<std::uint64_t>(a),
                .id_b = static_cast<std::uint64_t>(c),
                .p0 = p0,
                .p1 = p1,
                .thickness = kH,
                .centre_a = pos[static_cast<std::size_t>(a)],
                .centre_b = pos[static_cast<std::size_t>(c)]});
  };
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i <= nx; ++i) {
      if (i < nx)
        face(st.index(i, j), st.index(i + 1, j), {(i + 0.5) * s, (j - 0.5) * s}, {(i + 0.5) * s, (j + 0.5) * s});
      if (j + 1 < ny && i > 0)
        face(st.index(i, j), st.index(i, j + 1), {(i - 0.5) * s, (j + 0.5) * s}, {(i + 0.5) * s, (j + 0.5) * s});
    }
  st.world.set_bonds(std::move(b));
  return st;
}

// Mean displacement of the free end's column under a load ramped to (fx, fy) in total over `ramp` seconds, then
// held; averaged over the last quarter of the hold.
Vec2 tip_displacement(Strip& st, Vec2 load, double ramp, double hold) {
  std::vector<int> column;
  for (int j = 0; j < st.ny; ++j) column.push_back(st.index(st.nx, j));
  return mean_displacement_under_load(st.world, column, load, ramp, hold);
}

TEST(Bonds, CantileverDeflectionMatchesEulerBernoulli) {
  // A 20 x 2 strip of 5 m squares (100 m x 10 m x 1 m), clamped by bonds to a fixed column: its modulus measured by
  // an axial pull, then the tip deflection under a transverse tip load against P L^3 / (3 E_eff I), I = h w^3 / 12.
  // L runs from the fixed column's centroid to the load (the last column's centroids): the first bond's spring
  // spans half of the fixed element too (k_n = E / centroid distance), so that is where the clamp is. What is left:
  // the 8 bond points across the width give sum(A_p y^2) 1.6 % below w^3 h / 12, and shear adds ~0.8 %.
  const int nx = 20, ny = 2;
  const double s = 5.0, w_strip = ny * s, L = nx * s, I = kH * w_strip * w_strip * w_strip / 12.0;
  Strip pull = bonded_strip(nx, ny, s, 0.7);
  const double P_axial = 1.0e6;  // [N]
  const Vec2 u = tip_displacement(pull, {P_axial, 0.0}, 5.0, 5.0);
  const double e_eff = P_axial * L / (w_strip * kH * u.x());
  Strip bend = bonded_strip(nx, ny, s, 0.7);
  const double P = 3.0e3;  // [N]: about 1 cm of deflection
  const Vec2 d = tip_displacement(bend, {0.0, P}, 40.0, 20.0);
  const double euler_bernoulli = P * L * L * L / (3.0 * e_eff * I);
  std::printf("axial E_eff / E = %.4f; tip deflection %.5f m, Euler-Bernoulli %.5f m (ratio %.3f)\n", e_eff / kE, d.y(),
              euler_bernoulli, d.y() / euler_bernoulli);
  EXPECT_NEAR(e_eff / kE, 1.0, 0.01) << "aligned squares stretch like a bar of modulus E";
  EXPECT_NEAR(d.y() / euler_bernoulli, 1.0, 0.10);
}

}  // namespace

namespace {

TEST(Bonds, FacesBetweenFixedElementsGiveFiniteForces) {
  // Both elements fixed (infinite mass): the dashpot would be inf x 0; the face is skipped, forces stay finite.
  bonds::BondSet b(material());
  b.add_face({.a = 0, .b = 1, .p0 = {5, -5}, .p1 = {5, 5}, .centre_a = {0, 0}, .centre_b = {10, 0}});
  const double inf = std::numeric_limits<double>::infinity();
  const std::vector<Vec2> pos{{0, 0}, {10, 0}}, vel(2, Vec2(0, 0));
  const std::vector<double> yaw(2, 0.0), omega(2, 0.0), mass{inf, inf};
  std::vector<Vec2> force(2, Vec2(0, 0));
  std::vector<double> torque(2, 0.0);
  b.apply({pos, yaw, vel, omega, mass}, force, torque, 0.0);
  EXPECT_TRUE(force[0].allFinite() && force[1].allFinite() && std::isfinite(torque[0]) && std::isfinite(torque[1]));
  EXPECT_TRUE(std::isinf(b.critical_time_step(mass, yaw)));
}

}  // namespace
