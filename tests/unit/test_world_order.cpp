// The World's contact stage works on bodies sorted by position ("slots", dynamics/world.h), re-sorted every step.
// The order is private: these tests check that nothing a user sees depends on it.
//   - The same jammed pack added in two different body orders (lattice order and shuffled) gives, per body id,
//     bitwise the same poses, velocities, forces and torques and the same contacts (by id pair) at every step
//     checked, the same diagnostic sums and the same state (its rows in id order), also when one of them stores its
//     bodies in space order (WorldSettings::store_in_space_order: its indices change as it re-stores them); one's
//     state restored into a world built in the other order continues bitwise.
//   - A frozen sheet of 8 x 8 squares pulled apart (bonds that break) gives bitwise the same poses, velocities, intact
//     faces and contacts, added in lattice order and kept there, or added shuffled and stored in space order.
//   - Bodies that jump across the whole field in one step (every body crosses most others: the full-sort path)
//     keep world-frame vertices that follow them (1e-12 m) and get exactly the contacts a brute-force narrow phase
//     over every pair finds.
//   - The broad phase's neighbour lists: the same jostling pack with a skin so thin that the lists are rebuilt
//     nearly every step, the automatic skin, and one wider than the floes (built once) gives bitwise the same
//     positions and velocities and exactly the contacts a brute-force narrow phase finds, at every step checked.
//   - The thread count: the same jostling pack on 1, 2, 3 and 7 threads gives bitwise the same forces, torques,
//     states, contact counts, stored springs, shortest active contact and deepest overlap at every step.
//   - A body whose state becomes non-finite sorts last, has no contact, and leaves the others' shapes and contacts
//     intact (the broad phase used to hang on a NaN box).
//   - A step's first kick tests how far the bodies moved against the lists' skin, and the contact stage takes that
//     verdict; a step cut short between the two (a drift field that throws) leaves it unread. A state restored then,
//     with floes moved onto others, is tested anew: its contacts are exactly the brute-force ones.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <memory>
#include <random>
#include <set>
#include <utility>
#include <vector>

#include "bond_support.h"
#include "contact/narrow_phase_planar.h"
#include "dense_pack.h"
#include "dynamics/world.h"
#include "forcing/analytic_fields.h"
#include "world_checks.h"

using namespace polyfloe;
using geometry::Vec2;

namespace {

using IdPairs = std::set<std::pair<dynamics::BodyId, dynamics::BodyId>>;

IdPairs contact_ids(const dynamics::World& w) {
  IdPairs out;
  for (const dynamics::ContactRecord& c : w.contacts()) {
    EXPECT_LT(w.id(c.a), w.id(c.b));
    out.emplace(w.id(c.a), w.id(c.b));
  }
  return out;
}

// Every pair of bodies, at least one dynamic, that the exact narrow phase finds in contact (leaving out body `skip`).
IdPairs brute_force_contacts(const dynamics::World& w, int skip = -1) {
  IdPairs out;
  const int n = static_cast<int>(w.size());
  for (int i = 0; i < n; ++i)
    for (int j = i + 1; j < n; ++j) {
      if (i == skip || j == skip) continue;
      if (w.motion(i) != dynamics::Motion::dynamic && w.motion(j) != dynamics::Motion::dynamic) continue;
      contact::PlanarContact g;
      if (contact::planar_overlap(w.world_vertices(i), w.world_vertices(j), g, false))
        out.emplace(std::min(w.id(i), w.id(j)), std::max(w.id(i), w.id(j)));
    }
  return out;
}

void expect_vertices_follow_bodies(const dynamics::World& w) {
  for (int i = 0; i < static_cast<int>(w.size()); ++i)
    if (w.positions()[i].allFinite()) tsupport::expect_vertices_follow_body(w, i);
}

// A loose pack (no walls) of about n floes, in a World.
std::unique_ptr<dynamics::World> loose_pack(int n, std::uint64_t seed) {
  tsupport::PackSpec ps;
  ps.walls = false;
  const tsupport::Pack pack = tsupport::make_pack(n, ps, seed);
  auto w = std::make_unique<dynamics::World>(tsupport::no_drift());
  for (const auto& d : pack.bodies) w->add_body(d);
  w->step(1e-4);
  return w;
}

}  // namespace

TEST(WorldOrder, TheOrderBodiesAreAddedInChangesNoBitOfTheDynamicsTheStateOrTheSums) {
  tsupport::PackSpec ps;
  ps.speed = 0.3;  // the pack jostles: contacts open and close
  ps.shuffle = false;
  const tsupport::Pack pack = tsupport::make_pack(400, ps, 3u);
  std::vector<dynamics::BodyDesc> shuffled = pack.bodies;
  std::shuffle(shuffled.begin(), shuffled.end(), std::mt19937_64(5));

  // b also stores its bodies in space order, re-stored as they move: its indices change, its results must not.
  dynamics::WorldSettings sorting = tsupport::no_drift();
  sorting.store_in_space_order = true;
  dynamics::World a(tsupport::no_drift()), b(sorting);
  for (const auto& d : pack.bodies) a.add_body(d);
  for (const auto& d : shuffled) b.add_body(d);
  auto same_bits = [](const auto& x, const auto& y) { return std::memcmp(&x, &y, sizeof(x)) == 0; };
  // Every body's pose, velocity, force and torque, by id.
  auto expect_same = [&](const dynamics::World& x, const dynamics::World& y, int step) {
    for (int i = 0; i < static_cast<int>(x.size()); ++i) {
      const int j = y.index_of(x.id(i));
      ASSERT_GE(j, 0);
      ASSERT_TRUE(same_bits(x.positions()[i], y.positions()[j])) << "body " << x.id(i) << ", step " << step;
      ASSERT_TRUE(same_bits(x.yaws()[i], y.yaws()[j])) << "body " << x.id(i) << ", step " << step;
      ASSERT_TRUE(same_bits(x.velocities()[i], y.velocities()[j])) << "body " << x.id(i) << ", step " << step;
      ASSERT_TRUE(same_bits(x.angular_velocities()[i], y.angular_velocities()[j])) << "body " << x.id(i);
      ASSERT_TRUE(same_bits(x.forces()[i], y.forces()[j])) << "body " << x.id(i) << ", step " << step;
      ASSERT_TRUE(same_bits(x.torques()[i], y.torques()[j])) << "body " << x.id(i) << ", step " << step;
    }
    EXPECT_EQ(x.kinetic_energy(), y.kinetic_energy());
    EXPECT_EQ(x.angular_momentum(), y.angular_momentum());
  };
  const double dt = a.shortest_contact_duration(1.0) / 40.0;
  for (int step = 1; step <= 300; ++step) {
    a.step(dt);
    b.step(dt);
    if (step % 50 != 0) continue;
    ASSERT_FALSE(a.contacts().empty());
    EXPECT_EQ(contact_ids(a), contact_ids(b)) << "step " << step;
    expect_same(a, b, step);
    if (HasFatalFailure()) return;
  }
  expect_vertices_follow_bodies(b);
  EXPECT_EQ(a.body_reorders(), 0u);
  EXPECT_GE(b.body_reorders(), 1u);
  int moved = 0;  // bodies no longer where they were added
  for (std::size_t k = 0; k < shuffled.size(); ++k) moved += b.id(static_cast<int>(k)) != shuffled[k].id;
  EXPECT_GT(moved, 300);
  // The state lists the bodies in id order, whatever the order they were added in: the same rows, bit for bit.
  const dynamics::WorldState sa = a.state(), sb = b.state();
  ASSERT_TRUE(std::is_sorted(sa.ids.begin(), sa.ids.end()));
  EXPECT_EQ(sa.ids, sb.ids);
  for (std::size_t k = 0; k < sa.ids.size(); ++k) {
    ASSERT_TRUE(same_bits(sa.position[k], sb.position[k])) << "row " << k;
    ASSERT_TRUE(same_bits(sa.velocity[k], sb.velocity[k])) << "row " << k;
  }
  EXPECT_EQ(sa.contact_history.size(), sb.contact_history.size());
  // A's state restored into a world whose bodies were added in the shuffled order continues as a does, bitwise.
  dynamics::World c(sorting);
  for (const auto& d : shuffled) c.add_body(d);
  c.restore(sa);
  for (int step = 301; step <= 400; ++step) {
    a.step(dt);
    c.step(dt);
  }
  expect_same(a, c, 400);
}

TEST(WorldOrder, AFrozenSheetBreaksAlikeStoredInTheOrderItWasAddedOrInSpaceOrder) {
  constexpr int kSide = 8;
  constexpr double kS = 5.0;  // element side [m]
  const auto square = std::make_shared<const geometry::ConvexPolygon>(geometry::ConvexPolygon::rectangle(kS, kS));
  std::vector<dynamics::BodyDesc> lattice;
  std::mt19937_64 rng(9);
  std::uniform_real_distribution<double> jitter(-0.02, 0.02);
  for (int k = 0; k < kSide * kSide; ++k) {
    const int i = k % kSide, j = k / kSide;
    lattice.push_back({.id = static_cast<dynamics::BodyId>(1000 - k),  // ids against the lattice order, too
                       .shape = square,
                       .position = {i * kS, j * kS},
                       .velocity = {(i < kSide / 2 ? -0.4 : 0.4) + jitter(rng), jitter(rng)},
                       .angular_velocity = 0.1 * jitter(rng)});
  }
  std::vector<dynamics::BodyDesc> shuffled = lattice;
  std::shuffle(shuffled.begin(), shuffled.end(), std::mt19937_64(4));
  auto build = [&](const std::vector<dynamics::BodyDesc>& bodies, bool store) {
    dynamics::WorldSettings ws = tsupport::no_drift();
    ws.store_in_space_order = store;
    auto w = std::make_unique<dynamics::World>(ws);
    for (const auto& d : bodies) w->add_body(d);
    bonds::BondSet set(tsupport::bond::material(2e5));  // weak: the pull breaks the middle column of faces
    auto face = [&](int ka, int kb, Vec2 p0, Vec2 p1) {
      const auto& A = lattice[static_cast<std::size_t>(ka)];
      const auto& B = lattice[static_cast<std::size_t>(kb)];
      set.add_face({.a = w->index_of(A.id),
                    .b = w->index_of(B.id),
                    .id_a = A.id,
                    .id_b = B.id,
                    .p0 = p0,
                    .p1 = p1,
                    .thickness = 1.0,
                    .centre_a = A.position,
                    .centre_b = B.position});
    };
    for (int k = 0; k < kSide * kSide; ++k) {
      const int i = k % kSide, j = k / kSide;
      if (i + 1 < kSide) face(k, k + 1, {(i + 0.5) * kS, (j - 0.5) * kS}, {(i + 0.5) * kS, (j + 0.5) * kS});
      if (j + 1 < kSide) face(k, k + kSide, {(i - 0.5) * kS, (j + 0.5) * kS}, {(i + 0.5) * kS, (j + 0.5) * kS});
    }
    w->set_bonds(std::move(set));
    return w;
  };
  auto a = build(lattice, false), b = build(shuffled, true);
  const double dt = tsupport::bond::safe_dt(*a);
  for (int step = 1; step <= 600; ++step) {
    a->step(dt);
    b->step(dt);
  }
  const std::size_t faces = a->bonds()->faces();
  EXPECT_LT(a->bonds()->intact_faces(), faces) << "the pull must break some faces";
  EXPECT_GT(a->bonds()->intact_faces(), 0u);
  EXPECT_EQ(a->bonds()->intact_faces(), b->bonds()->intact_faces());
  for (std::size_t f = 0; f < faces; ++f) EXPECT_EQ(a->bonds()->face_intact(f), b->bonds()->face_intact(f)) << f;
  EXPECT_GE(b->body_reorders(), 1u);
  EXPECT_EQ(contact_ids(*a), contact_ids(*b));
  for (int i = 0; i < static_cast<int>(a->size()); ++i) {
    const int j = b->index_of(a->id(i));
    ASSERT_EQ(std::memcmp(&a->positions()[i], &b->positions()[j], sizeof(Vec2)), 0) << "body " << a->id(i);
    ASSERT_EQ(std::memcmp(&a->velocities()[i], &b->velocities()[j], sizeof(Vec2)), 0) << "body " << a->id(i);
    ASSERT_EQ(a->yaws()[i], b->yaws()[j]) << "body " << a->id(i);
  }
}

TEST(WorldOrder, BodiesThatJumpAcrossTheFieldKeepTheirShapesAndContacts) {
  const auto world = loose_pack(300, 4u);
  dynamics::World& w = *world;
  EXPECT_EQ(contact_ids(w), brute_force_contacts(w));
  // Mirror the field through its centre in one step: every body crosses most others, so the slot order is
  // rebuilt from scratch; then mirror it back.
  Vec2 centre{0.0, 0.0};
  for (const Vec2& p : w.positions()) centre += p;
  centre /= static_cast<double>(w.size());
  const double dt = 1e-3;
  for (int round = 0; round < 2; ++round) {
    for (int i = 0; i < static_cast<int>(w.size()); ++i) w.set_velocity(i, 2.0 * (centre - w.positions()[i]) / dt, 0.0);
    w.step(dt);
    expect_vertices_follow_bodies(w);
    EXPECT_EQ(contact_ids(w), brute_force_contacts(w)) << "round " << round;
    for (int i = 0; i < static_cast<int>(w.size()); ++i) w.set_velocity(i, Vec2{0.0, 0.0}, 0.0);
    w.step(dt);
    expect_vertices_follow_bodies(w);
    EXPECT_EQ(contact_ids(w), brute_force_contacts(w)) << "round " << round << ", at rest";
    EXPECT_FALSE(w.contacts().empty());
  }
}

TEST(WorldOrder, ANonFiniteBodyLeavesTheOthersShapesAndContactsIntact) {
  const auto world = loose_pack(200, 6u);
  dynamics::World& w = *world;
  const double nan = std::numeric_limits<double>::quiet_NaN();
  w.set_velocity(17, Vec2{nan, 0.0}, 0.0);
  w.step(1e-4);
  ASSERT_FALSE(w.positions()[17].allFinite());
  expect_vertices_follow_bodies(w);
  // The broken body enters no broad-phase cell, so it has no contact; the others keep exactly theirs.
  IdPairs want = brute_force_contacts(w, 17);
  EXPECT_FALSE(want.empty());
  EXPECT_EQ(contact_ids(w), want);
  w.step(1e-4);
  expect_vertices_follow_bodies(w);
  EXPECT_EQ(contact_ids(w), brute_force_contacts(w, 17));
}

TEST(WorldOrder, TheNeighbourListSkinChangesHowOftenTheListsAreBuiltAndNothingElse) {
  tsupport::PackSpec ps;
  ps.speed = 0.3;  // [m/s]: about 0.3 mm per step, 6 x the thin skin's half
  const tsupport::Pack pack = tsupport::make_pack(300, ps, 8u);
  std::vector<std::unique_ptr<dynamics::World>> worlds;
  for (const double skin : {1e-4, 0.0, 50.0}) {  // [m]; 0 = automatic
    dynamics::WorldSettings ws = tsupport::no_drift();
    ws.broad_phase_skin = skin;
    worlds.push_back(std::make_unique<dynamics::World>(ws));
    for (const auto& d : pack.bodies) worlds.back()->add_body(d);
  }
  const double dt = worlds[0]->shortest_contact_duration(1.0) / 40.0;
  for (int step = 1; step <= 200; ++step) {
    for (auto& w : worlds) w->step(dt);
    if (step % 25 != 0) continue;
    const IdPairs want = brute_force_contacts(*worlds[0]);
    ASSERT_FALSE(want.empty());
    for (std::size_t k = 0; k < worlds.size(); ++k) {
      const dynamics::World& w = *worlds[k];
      EXPECT_EQ(contact_ids(w), want) << "world " << k << ", step " << step;
      for (int i = 0; i < static_cast<int>(w.size()); ++i) {
        ASSERT_EQ(w.positions()[i], worlds[0]->positions()[i]) << "world " << k << ", body " << i << ", step " << step;
        ASSERT_EQ(w.velocities()[i], worlds[0]->velocities()[i]) << "world " << k << ", body " << i;
        ASSERT_EQ(w.yaws()[i], worlds[0]->yaws()[i]) << "world " << k << ", body " << i;
      }
    }
  }
  // The thin skin rebuilt the lists at most steps, the wide one once the slots were sorted, the automatic one
  // in between.
  const std::uint64_t thin = worlds[0]->neighbour_list_builds(), automatic = worlds[1]->neighbour_list_builds(),
                      wide = worlds[2]->neighbour_list_builds();
  EXPECT_GT(thin, 100u);
  EXPECT_LE(wide, 3u);
  EXPECT_LT(automatic, thin);
  EXPECT_GE(automatic, wide);
}

class WorldOrderByModel : public ::testing::TestWithParam<contact::ForceModel> {};

TEST_P(WorldOrderByModel, TheThreadCountChangesNothing) {
#ifndef _OPENMP
  GTEST_SKIP() << "built without OpenMP: the step is serial";
#endif
  // The contact sum runs in blocks of slots, 8 per thread, each adding the pairs of earlier blocks that reach into
  // it before its own: with 1, 2, 3 and 7 threads (8 to 56 blocks of 300 floes, so most slots get pairs from
  // several earlier blocks) every force, torque, state, count and extreme must be the same bits.
  tsupport::PackSpec ps;
  ps.speed = 0.3;  // [m/s]
  const tsupport::Pack pack = tsupport::make_pack(300, ps, 9u);
  dynamics::WorldSettings settings = tsupport::no_drift();
  settings.contact.force_model = GetParam();
  std::vector<std::unique_ptr<dynamics::World>> worlds;
  for (const int threads : {1, 2, 3, 7}) {
    worlds.push_back(std::make_unique<dynamics::World>(settings));
    worlds.back()->set_threads(threads);
    for (const auto& d : pack.bodies) worlds.back()->add_body(d);
  }
  const double dt = worlds[0]->shortest_contact_duration(1.0) / 40.0;
  for (int step = 1; step <= 100; ++step) {
    for (auto& w : worlds) w->step(dt);
    const dynamics::World& one = *worlds[0];
    ASSERT_GT(one.contact_count(), 100u);
    for (std::size_t k = 1; k < worlds.size(); ++k) {
      const dynamics::World& w = *worlds[k];
      ASSERT_EQ(w.contact_count(), one.contact_count()) << "threads " << w.threads() << ", step " << step;
      ASSERT_EQ(w.report().shortest.duration, one.report().shortest.duration) << "threads " << w.threads();
      ASSERT_EQ(w.report().shortest.a, one.report().shortest.a) << "threads " << w.threads();
      ASSERT_EQ(w.report().deepest.ratio, one.report().deepest.ratio) << "threads " << w.threads();
      ASSERT_EQ(w.report().deepest.a, one.report().deepest.a) << "threads " << w.threads();
      ASSERT_EQ(w.contact_cache().entries(), one.contact_cache().entries()) << "threads " << w.threads();
      ASSERT_EQ(w.profile().reused, one.profile().reused) << "threads " << w.threads() << ", step " << step;
      // The contact records listed for output (from the pairs' evaluations, in pair order) are the same too.
      if (step % 10 == 0) {
        const std::vector<dynamics::ContactRecord>&c1 = one.contacts(), &ck = w.contacts();
        ASSERT_EQ(ck.size(), one.contact_count()) << "threads " << w.threads() << ", step " << step;
        ASSERT_EQ(ck.size(), c1.size()) << "threads " << w.threads() << ", step " << step;
        for (std::size_t c = 0; c < c1.size(); ++c) {
          ASSERT_EQ(ck[c].a, c1[c].a) << "threads " << w.threads() << ", contact " << c;
          ASSERT_EQ(ck[c].b, c1[c].b) << "threads " << w.threads() << ", contact " << c;
          ASSERT_EQ(ck[c].geometry.normal, c1[c].geometry.normal) << "threads " << w.threads();
          ASSERT_EQ(ck[c].geometry.point, c1[c].geometry.point) << "threads " << w.threads();
          ASSERT_EQ(ck[c].geometry.depth, c1[c].geometry.depth) << "threads " << w.threads();
          ASSERT_EQ(ck[c].geometry.area, c1[c].geometry.area) << "threads " << w.threads();
          ASSERT_EQ(ck[c].normal_force, c1[c].normal_force) << "threads " << w.threads();
          ASSERT_EQ(ck[c].tangential_force, c1[c].tangential_force) << "threads " << w.threads();
          ASSERT_EQ(ck[c].sliding, c1[c].sliding) << "threads " << w.threads();
          ASSERT_EQ(ck[c].force, c1[c].force) << "threads " << w.threads();
          ASSERT_EQ(ck[c].energy, c1[c].energy) << "threads " << w.threads();
        }
      }
      for (int i = 0; i < static_cast<int>(w.size()); ++i) {
        ASSERT_EQ(w.forces()[i], one.forces()[i]) << "threads " << w.threads() << ", body " << i << ", step " << step;
        ASSERT_EQ(w.torques()[i], one.torques()[i]) << "threads " << w.threads() << ", body " << i;
        ASSERT_EQ(w.positions()[i], one.positions()[i]) << "threads " << w.threads() << ", body " << i;
        ASSERT_EQ(w.angular_velocities()[i], one.angular_velocities()[i]) << "threads " << w.threads();
      }
    }
  }
}

INSTANTIATE_TEST_SUITE_P(ForceModels, WorldOrderByModel,
                         ::testing::Values(contact::ForceModel::centroid, contact::ForceModel::foundation),
                         [](const auto& info) { return std::string(contact::force_model_name(info.param)); });

TEST(WorldOrder, AWorldWithoutBodiesStepsOnSeveralThreads) {
  // No slots, so no blocks for the contact sum: nothing is summed, and nothing left from an earlier step is counted.
  dynamics::World w(tsupport::no_drift());
  w.set_threads(3);
  for (int k = 0; k < 3; ++k) w.step(1e-3);
  EXPECT_EQ(w.contact_count(), 0u);
  EXPECT_EQ(w.narrow_phase_failures(), 0u);
  EXPECT_EQ(w.report().deepest.a, -1);
  EXPECT_EQ(w.report().shortest.a, -1);
}

TEST(WorldOrder, AStateRestoredAfterAStepCutShortFindsItsOwnContacts) {
  tsupport::PackSpec ps;
  ps.walls = false;
  ps.eps = -0.05;  // floes 5 % smaller than their cells: no contact
  const tsupport::Pack pack = tsupport::make_pack(200, ps, 3u);
  dynamics::WorldSettings ws = tsupport::no_drift();
  ws.drift.skin_drag = true;
  forcing::FieldSpec series;  // a current given until t = 1 s, an error after
  series.kind = forcing::FieldKind::time_series;
  series.times = {0.0, 1.0};
  series.values = {{0.1, 0.0}, {0.1, 0.0}};
  series.outside = forcing::TimeBoundary::error;
  ws.drift.ocean = forcing::make_field(series);
  dynamics::World w(ws);
  for (const auto& d : pack.bodies) w.add_body(d);
  const double dt = 0.4;
  w.step(dt);
  dynamics::WorldState s = w.state();  // at 0.4 s
  ASSERT_EQ(w.contact_count(), 0u);
  w.step(dt);
  EXPECT_THROW(w.step(dt), forcing::FieldError);  // the drift at 1.2 s, after the kick moved the floes
  // The state at 0.4 s with every tenth floe moved onto the next one (far beyond the skin from where it was).
  for (std::size_t i = 0; i + 1 < s.position.size(); i += 10) s.position[i] = s.position[i + 1] + Vec2{1e-3, 0.0};
  s.forces_ready = false;
  w.restore(s);
  w.compute_forces(0.0);
  const IdPairs want = brute_force_contacts(w);
  EXPECT_FALSE(want.empty());
  EXPECT_EQ(contact_ids(w), want);
}
