// The planar contact stage (dynamics/contact_stage.h) on its own, over hand-made slots, no World:
//   two squares pressed together by d and sliding past each other get the Hertz force k_n d^1.5 along the normal
//   from the lower id to the higher, the tangential spring -k_s d^0.5 v dt, and the torques of that friction at the
//   overlap's centroid (closed forms, 1e-12 relative; the torques also within the rounding of the centroid); the spring carries to the next evaluation through the
//   contact history (its force doubles); a pair joined by an intact bond face is skipped; a jostled lattice of
//   floes gives the same bits on 2 threads as on 1; the records list the touching pairs by body index.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <numbers>
#include <random>
#include <vector>

#include "bonds/bond_set.h"
#include "contact/contact_law.h"
#include "dynamics/contact_stage.h"
#include "geometry/polygon.h"

using namespace polyfloe;
using dynamics::PlanarContactStage;
using geometry::Vec2;

namespace {

constexpr double kSide = 10.0, kDensity = 900.0, kThickness = 1.0;  // [m], [kg/m^3], [m]

// Square floes of kSide, one slot per body in the order added (the stage needs no other order). The views'
// arrays live here.
struct Floes {
  std::vector<dynamics::SlotKey> slots;
  std::vector<int> body_slot;
  std::vector<dynamics::SlotStatic> statics;
  std::vector<dynamics::SlotState> states;
  std::vector<geometry::Aabb> boxes;
  std::vector<std::uint8_t> dynamic;
  std::vector<Vec2> world_xy, position;
  std::vector<double> yaw, reach, inv_mass, inv_inertia;

  void add(const Vec2& p, double angle, const Vec2& v, double omega) {
    const geometry::ConvexPolygon sq = geometry::ConvexPolygon::rectangle(kSide, kSide);
    const int i = static_cast<int>(slots.size());
    const double m = kDensity * sq.area() * kThickness;
    slots.push_back({0, static_cast<dynamics::BodyId>(100 + i), i});
    body_slot.push_back(i);
    statics.push_back({m, sq.equivalent_radius(), sq.equivalent_radius(), static_cast<dynamics::BodyId>(100 + i), i,
                       static_cast<int>(world_xy.size()), static_cast<int>(sq.size())});
    states.push_back({p, v, omega});
    geometry::Aabb box{p, p};
    const Vec2 rot(std::cos(angle), std::sin(angle));
    for (const Vec2& c : sq.vertices()) {
      const Vec2 w = p + Vec2(rot.x() * c.x() - rot.y() * c.y(), rot.y() * c.x() + rot.x() * c.y());
      world_xy.push_back(w);
      box.lo = box.lo.cwiseMin(w);
      box.hi = box.hi.cwiseMax(w);
    }
    boxes.push_back(box);
    dynamic.push_back(1);
    position.push_back(p);
    yaw.push_back(angle);
    reach.push_back(0.5 * std::numbers::sqrt2 * kSide);
    inv_mass.push_back(1.0 / m);
    inv_inertia.push_back(1.0 / (m * kSide * kSide / 6.0));
  }
  dynamics::SlotView view() const {
    return {slots, body_slot, statics, boxes, dynamic, world_xy, position, yaw, reach};
  }
  dynamics::PlanarContactInput input(double dt, int threads, const bonds::BondSet* bonds = nullptr) const {
    return {.statics = statics,
            .states = states,
            .world_xy = world_xy,
            .inv_mass = inv_mass,
            .inv_inertia = inv_inertia,
            .bonds = bonds,
            .dt = dt,
            .threads = threads};
  }
};

// One stage with its neighbour lists and contact history.
struct Stage {
  contact::ContactLaw law{contact::ContactLawSettings{}};
  dynamics::NeighbourLists lists{0.0};
  contact::ContactCache cache;
  PlanarContactStage stage;
  Stage() { lists.set_skin(1.0); }
  const dynamics::ContactSum::Totals& run(const Floes& f, double dt, int threads,
                                          const bonds::BondSet* bonds = nullptr) {
    stage.find_pairs(f.view(), law, dynamics::PlanarNarrowPhase::exact, threads, lists);
    const dynamics::PlanarContactInput in = f.input(dt, threads, bonds);
    stage.evaluate(in, law, lists, cache);
    return stage.sum(in, lists, cache);
  }
};

constexpr double kDepth = 0.01, kSlip = 0.02, kDt = 0.01;  // [m], [m/s], [s]

// Floe 0 at rest, floe 1 pressed into it by kDepth along x and sliding along +y at kSlip.
Floes pressed_pair() {
  Floes f;
  f.add({0.0, 0.0}, 0.0, {0.0, 0.0}, 0.0);
  f.add({kSide - kDepth, 0.0}, 0.0, {0.0, kSlip}, 0.0);
  return f;
}

TEST(ContactStage, PressedSlidingSquaresGetTheHertzForceAndTheSpringsFrictionAtTheOverlapsCentroid) {
  const Floes f = pressed_pair();
  Stage s;
  // Elastic (e = 1): the damping, at the rate predicted for the end of the step, would resist the floes' parting.
  s.law = contact::ContactLaw(contact::ContactLawSettings{.restitution = 1.0});
  const contact::PairCoefficients k =
      s.law.coefficients(f.statics[0].radius, f.statics[1].radius, f.statics[0].mass, f.statics[1].mass);
  const double fn = k.k_n * kDepth * std::sqrt(kDepth);        // no damping
  const double ft = -k.k_s * std::sqrt(kDepth) * kSlip * kDt;  // the spring after one step of slip
  ASSERT_LT(std::abs(ft), k.mu * fn);                          // below the Coulomb cap
  const double arm = 0.5 * (kSide - kDepth);                   // the overlap's centroid from either centre [m]
  for (int evaluation = 1; evaluation <= 2; ++evaluation) {
    SCOPED_TRACE(evaluation);
    const dynamics::ContactSum::Totals& t = s.run(f, kDt, 1);
    ASSERT_EQ(t.hits, 1u);
    EXPECT_EQ(s.stage.candidates(), 1u);
    const double ft_now = evaluation * ft;  // the spring kept in the history grows by the same slip
    EXPECT_NEAR(s.stage.slot_force(1).x(), fn, 1e-12 * fn);
    EXPECT_NEAR(s.stage.slot_force(1).y(), ft_now, 1e-12 * std::abs(ft));
    EXPECT_EQ(s.stage.slot_force(0), -s.stage.slot_force(1));
    // Friction at the contact point turns both floes the same way: -arm F_t each (the centroid's y is 0 to
    // rounding: the overlap centroid's formula divides by its area, a lever of order 1e-16 kSide^2 / kDepth).
    const double tol = 1e-12 * arm * std::abs(ft) + 1e-13 * kSide * fn;
    EXPECT_NEAR(s.stage.slot_torque(1), -arm * ft_now, tol);
    EXPECT_NEAR(s.stage.slot_torque(0), -arm * ft_now, tol);
    EXPECT_NEAR(t.deepest.depth, kDepth, 1e-12);
  }
  std::vector<dynamics::ContactRecord> records;
  s.stage.list_contacts(f.statics, records);
  ASSERT_EQ(records.size(), 1u);
  EXPECT_EQ(records[0].a, 0);
  EXPECT_EQ(records[0].b, 1);
  EXPECT_NEAR(records[0].geometry.normal.x(), 1.0, 1e-15);
  EXPECT_NEAR(records[0].geometry.area, kDepth * kSide, 1e-12);
  EXPECT_NEAR(records[0].normal_force, fn, 1e-12 * fn);
}

TEST(ContactStage, APairJoinedByAnIntactBondFaceIsSkipped) {
  const Floes f = pressed_pair();
  bonds::BondSet bonds(bonds::BondMaterial{.points_per_face = 3});
  bonds.add_face({.a = 0,
                  .b = 1,
                  .id_a = 100,
                  .id_b = 101,
                  .p0 = {0.5 * kSide, -0.5 * kSide},
                  .p1 = {0.5 * kSide, 0.5 * kSide},
                  .thickness = kThickness,
                  .centre_a = f.position[0],
                  .centre_b = f.position[1]});
  Stage s;
  EXPECT_EQ(s.run(f, kDt, 1, &bonds).hits, 0u);
  EXPECT_EQ(s.stage.slot_force(1), Vec2(0.0, 0.0));
  EXPECT_EQ(s.run(f, kDt, 1).hits, 1u);  // the same pair without the bond touches
}

// The bits of every slot's force and torque.
std::vector<double> sums(const PlanarContactStage& stage, int n) {
  std::vector<double> out;
  for (int k = 0; k < n; ++k) {
    out.push_back(stage.slot_force(k).x());
    out.push_back(stage.slot_force(k).y());
    out.push_back(stage.slot_torque(k));
  }
  return out;
}

TEST(ContactStage, AJostledLatticeGivesTheSameBitsOnTwoThreadsAsOnOne) {
  Floes f;
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> jitter(-0.05, 0.05);
  const int side = 12;
  for (int i = 0; i < side; ++i)
    for (int j = 0; j < side; ++j)
      f.add({9.95 * i + jitter(rng), 9.95 * j + jitter(rng)}, jitter(rng), {jitter(rng), jitter(rng)}, jitter(rng));
  const int n = side * side;
  Stage one, two;
  for (int evaluation = 0; evaluation < 3; ++evaluation) {  // the later ones read the histories the first stored
    const dynamics::ContactSum::Totals t1 = one.run(f, kDt, 1);
    const dynamics::ContactSum::Totals t2 = two.run(f, kDt, 2);
    EXPECT_GT(t1.hits, static_cast<std::size_t>(n));  // most floes press on their neighbours
    EXPECT_EQ(t1.hits, t2.hits);
    const std::vector<double> a = sums(one.stage, n), b = sums(two.stage, n);
    EXPECT_EQ(std::memcmp(a.data(), b.data(), a.size() * sizeof(double)), 0) << "evaluation " << evaluation;
  }
}

}  // namespace
