// The planar World cut among MPI ranks (domain/distributed_world.h), run by CTest under mpirun at 1, 2, 3 and 4
// ranks. Every rank is given the same jostling pack of 300 floes; checked against one World holding every floe:
//   - the pack with and without an ocean current, on 1 and 2 threads per rank, and a gas of floes at up to 10 m/s
//     that cross the ranks' regions (some floes migrate at 3 and 4 ranks), with a halo margin small enough that the
//     halo is renewed every few steps (47 renewals in the pack's 300 steps, 126 in the gas's 800): every rank's own
//     floes have bitwise the one World's poses, velocities, forces and torques at every 20th step, and the contacts
//     evaluated on all ranks add up to the one World's;
//   - the state gathered from the ranks is bitwise one World's state() (every field, contact histories included),
//     and a state restored on all the ranks, or on one rank fewer, runs on bitwise as the one World (a restart on
//     another number of ranks); a state that does not fit the bodies is refused on every rank;
//   - corner cases: a floe larger than any rank's region (an 80 m square among 5-15 m floes driven at it), and
//     every floe crossing one cut within the same few steps (two files of floes that meet head on where the ranks'
//     regions part, all of them migrating, the regions then cut anew): bitwise as one World;
//   - the load balance: a pack beside open water, first cut for equal counts, is cut anew on the floes' measured
//     cost (the pack's ranks then own fewer floes), bitwise as one World;
//   - a floe that moves more than half the margin between two renewals stops the run on every rank with a message
//     that says so (and that the time step is far too large); one rank has no halo and does not test it.
#include <gtest/gtest.h>
#include <mpi.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <optional>
#include <string>
#include <vector>

#include "dense_pack.h"
#include "floe_gas.h"
#include "domain/distributed_world.h"
#include "dynamics/world.h"
#include "mpi_test_main.h"
#include "state_bytes.h"
#include "shared_ice.h"

using namespace polyfloe;
using tsupport::mpi_rank;
using tsupport::mpi_ranks;

namespace {

struct Case {
  bool drift = false;
  int threads = 1;
  bool gas = false;  // a gas of floes at up to 10 m/s instead of the pack: they cross the ranks' regions
};

class Distributed : public ::testing::TestWithParam<Case> {};

TEST_P(Distributed, FloesMigrateAndMoveBitwiseAsInOneWorld) {
  const Case c = GetParam();
  std::vector<dynamics::BodyDesc> bodies;
  if (c.gas) {
    bodies = tsupport::make_field(7u, 200, 16.0, 10.0, 0.5).bodies;
  } else {
    tsupport::PackSpec ps;
    ps.speed = 0.3;  // [m/s]
    ps.walls = false;
    bodies = tsupport::make_pack(200, ps, 11u).bodies;
  }
  const dynamics::WorldSettings ws = tsupport::shared_ice_settings(contact::ForceModel::centroid, c.drift);
  dynamics::World one(ws);
  for (const auto& d : bodies) one.add_body(d);
  const double dt = one.shortest_contact_duration(c.gas ? 10.0 : 1.0) / 40.0;
  // A margin of 3 cm (the gas: 30 cm): the halo is renewed every centimetre of drift (the gas: 7.5 cm).
  domain::DistributedWorld dw(MPI_COMM_WORLD, ws, bodies, c.gas ? 0.3 : 0.03);
  dw.set_threads(c.threads);
  EXPECT_EQ(dw.local().space_order_cell(), one.space_order_cell());
  std::size_t contacts_seen = 0;
  for (int round = 1; round <= (c.gas ? 30 : 15); ++round) {
    for (int s = 0; s < 20; ++s) {
      one.step(dt);
      dw.step(dt);
    }
    const int step = 20 * round;
    const std::size_t owned = tsupport::expect_owned_as_in_one(dw.local(), one, step);
    if (tsupport::any_rank_failed()) return;
    std::uint64_t counts[2] = {owned, dw.local().contact_count()}, all[2] = {0, 0};
    MPI_Allreduce(counts, all, 2, MPI_UINT64_T, MPI_SUM, MPI_COMM_WORLD);
    ASSERT_EQ(all[0], one.size()) << "step " << step;  // each floe owned by one rank
    if (!c.gas) {
      ASSERT_GT(one.contact_count(), 100u);
    }
    contacts_seen += one.contact_count();
    ASSERT_EQ(all[1], one.contact_count()) << "step " << step;  // each pair evaluated by one rank
  }
  if (mpi_ranks() > 1) {
    EXPECT_GE(dw.renewals(), 3u);
  }
  std::uint64_t migrated = dw.migrated(), all_migrated = 0;
  MPI_Allreduce(&migrated, &all_migrated, 1, MPI_UINT64_T, MPI_SUM, MPI_COMM_WORLD);
  // Floes changed ranks (in the gas at 3 and 4 ranks; at 2 the one cut lies in a wide gap of the gas's lattice, and
  // none reaches it in these 800 steps).
  if (mpi_ranks() > 2 && c.gas) {
    EXPECT_GT(all_migrated, 0u);
  }
  if (mpi_rank() == 0)
    std::printf("%zu contacts seen, %llu renewals (%llu rebalanced), %llu floes migrated\n", contacts_seen,
                static_cast<unsigned long long>(dw.renewals()), static_cast<unsigned long long>(dw.rebalances()),
                static_cast<unsigned long long>(all_migrated));
}

INSTANTIATE_TEST_SUITE_P(Packs, Distributed,
                         ::testing::Values(Case{false, 1}, Case{true, 1}, Case{true, 2}, Case{false, 1, true}),
                         [](const auto& info) {
                           return std::string(info.param.gas     ? "Gas"
                                              : info.param.drift ? "Drifting"
                                                                 : "Jostling") +
                                  "_" + std::to_string(info.param.threads) + "Threads";
                         });

// Steps `one` and `dw` together for `steps` steps of dt, each rank's floes checked bitwise against the one World every
// `every` steps; returns the contacts the one World had at those checks, summed.
// Every field of `a` bitwise that of `b` (state_bytes.h: a failure naming each field that differs).
void expect_same_state(const dynamics::WorldState& a, const dynamics::WorldState& b, const std::string& where) {
  const auto x = tsupport::state_bytes(a), y = tsupport::state_bytes(b);
  ASSERT_EQ(x.size(), y.size());
  for (std::size_t k = 0; k < x.size(); ++k)
    EXPECT_TRUE(x[k].second == y[k].second) << where << ": the state's field " << x[k].first << " differs";
}

std::size_t run_as_one(dynamics::World& one, domain::DistributedWorld& dw, double dt, int steps, int every) {
  std::size_t contacts = 0;
  for (int step = 1; step <= steps; ++step) {
    one.step(dt);
    dw.step(dt);
    if (step % every != 0) continue;
    const std::size_t owned = tsupport::expect_owned_as_in_one(dw.local(), one, step);
    std::uint64_t counts[2] = {owned, dw.local().contact_count()}, all[2] = {0, 0};
    MPI_Allreduce(counts, all, 2, MPI_UINT64_T, MPI_SUM, MPI_COMM_WORLD);
    EXPECT_EQ(all[0], one.size()) << "step " << step;
    EXPECT_EQ(all[1], one.contact_count()) << "step " << step;
    if (tsupport::any_rank_failed()) return contacts;
    contacts += one.contact_count();
  }
  return contacts;
}

std::uint64_t sum_over_ranks(std::uint64_t x) {
  std::uint64_t all = 0;
  MPI_Allreduce(&x, &all, 1, MPI_UINT64_T, MPI_SUM, MPI_COMM_WORLD);
  return all;
}

// One World and a DistributedWorld of the same bodies (no drift), the step a 40th of the shortest contact at `speed`
// [m/s], stepped together by run(seconds, every) (run_as_one).
struct SideBySide {
  SideBySide(const std::vector<dynamics::BodyDesc>& bodies, double speed, double margin)
      : one(settings()), dw(MPI_COMM_WORLD, settings(), bodies, margin) {
    for (const auto& d : bodies) one.add_body(d);
    dt = one.shortest_contact_duration(speed) / 40.0;
  }
  static dynamics::WorldSettings settings() {
    return tsupport::shared_ice_settings(contact::ForceModel::centroid, false);
  }
  std::size_t run(double seconds, int every) {
    const std::size_t contacts = run_as_one(one, dw, dt, static_cast<int>(seconds / dt), every);
    migrated = sum_over_ranks(dw.migrated());
    if (mpi_rank() == 0)
      std::printf("dt %.3g s, %zu contacts seen, %llu renewals (%llu rebalanced), %llu floes migrated\n", dt, contacts,
                  static_cast<unsigned long long>(dw.renewals()), static_cast<unsigned long long>(dw.rebalances()),
                  static_cast<unsigned long long>(migrated));
    return contacts;
  }
  dynamics::World one;
  domain::DistributedWorld dw;
  double dt = 0.0;             // [s]
  std::uint64_t migrated = 0;  // over all ranks
};

TEST(DistributedCorners, AFloeLargerThanARegion) {
  // 5-15 m floes on a 16 m lattice, those within 8 m of the square taken out, all driven towards the origin (at up
  // to 4.8 m/s), where an 80 m square floe lies across every rank's region.
  std::vector<dynamics::BodyDesc> bodies;
  for (dynamics::BodyDesc d : tsupport::make_field(3u, 144, 16.0, 0.2, 0.05).bodies) {
    if (std::abs(d.position.x()) < 48.0 && std::abs(d.position.y()) < 48.0) continue;
    d.velocity -= 0.1 * d.position;  // [1/s]
    bodies.push_back(d);
  }
  dynamics::BodyDesc giant;
  giant.id = 1000;
  giant.shape = tsupport::shape_of({{-40.0, -40.0}, {40.0, -40.0}, {40.0, 40.0}, {-40.0, 40.0}});
  bodies.push_back(giant);
  SideBySide both(bodies, 6.0, 1.0);
  EXPECT_GT(both.run(2.0, 25), 20u);
  const dynamics::World& one = both.one;
  EXPECT_GT(one.velocities()[static_cast<std::size_t>(one.index_of(1000))].norm(), 0.0);  // struck (from rest)
  // The square is held by one rank and as a ghost by others (its box reaches several regions; which ones depends
  // on where the measured load has put the cuts).
  const dynamics::World& mine = both.dw.local();
  const int i = mine.index_of(1000);
  EXPECT_GE(sum_over_ranks(i >= 0 ? 1 : 0), static_cast<std::uint64_t>(std::min(mpi_ranks(), 2)));
  EXPECT_EQ(sum_over_ranks(i >= 0 && !mine.is_ghost(i) ? 1 : 0), 1u);
}

TEST(DistributedCorners, WallsAlongTheWholePackDoNotTakeEveryFloeIntoTheHalo) {
  // A pack of 1,500 floes jammed between four walls as long as its sides: the rank that owns a wall holds as ghosts
  // the floes along it and near the cuts, not every floe its wall's box would reach as one box with its own floes.
  const tsupport::Pack pack = tsupport::make_pack(1500, tsupport::PackSpec{}, 7u);
  domain::DistributedWorld dw(MPI_COMM_WORLD, tsupport::no_drift(), pack.bodies);
  const dynamics::World& w = dw.local();
  std::uint64_t ghosts = 0;
  for (int i = 0; i < static_cast<int>(w.size()); ++i) ghosts += w.is_ghost(i);
  const std::uint64_t all = sum_over_ranks(ghosts);
  if (mpi_rank() == 0) std::printf("%llu ghosts on %d ranks\n", static_cast<unsigned long long>(all), mpi_ranks());
  // Each cut of the 39 x 39 lattice is crossed by about 2 x 39 floe-widths of halo on each side.
  EXPECT_LE(all, static_cast<std::uint64_t>(200 * (mpi_ranks() - 1)));
}

TEST(DistributedCorners, EveryFloeCrossingOneCutAtOnce) {
  // Two files of 6 hexagonal floes (0.3 m to the corners), at x = -3 m and x = +3 m, the first running at the second
  // at 2 m/s: the field is wider than high, so the first cut parts the files; every floe of the first file crosses
  // it within the same step, then they all strike the second file.
  std::vector<dynamics::BodyDesc> bodies;
  std::vector<geometry::Vec2> hexagon;
  for (int k = 0; k < 6; ++k) hexagon.push_back(0.3 * geometry::Vec2{std::cos(k * M_PI / 3), std::sin(k * M_PI / 3)});
  for (int side = 0; side < 2; ++side)
    for (int row = 0; row < 6; ++row) {
      dynamics::BodyDesc d;
      d.id = static_cast<dynamics::BodyId>(1 + 6 * side + row);
      d.shape = tsupport::shape_of(hexagon);
      d.position = {side ? 3.0 : -3.0, 0.8 * row - 2.0};
      d.velocity = {side ? 0.0 : 2.0, 0.0};
      bodies.push_back(d);
    }
  SideBySide both(bodies, 4.0, 0.1);
  EXPECT_GT(both.run(3.0, 10), 6u);  // the files met
  if (mpi_ranks() > 1) {
    EXPECT_GE(both.migrated, 6u);  // the first file crossed to the other side
  }
}

TEST(DistributedBalance, AnUnevenLoadIsCutAnewOnItsMeasuredCost) {
  // 400 floes jammed between walls (about two contacts each) beside 400 floes apart in open water, which drift
  // slowly and touch nothing: the first regions, cut for equal counts, give the ranks on the pack's side most of the
  // work. The ranks' measured busy times part by more than kImbalance, so the regions are cut anew on the floes'
  // measured cost at one of the checks every kLoadCheck steps, although no floe moves far enough for a renewal of
  // its own: the ranks on the pack's side then own fewer floes than the others (on average, by 20 % or more), and
  // every floe still moves bitwise as in one World.
  std::vector<dynamics::BodyDesc> bodies = tsupport::make_pack(400, tsupport::PackSpec{}, 5u).bodies;
  double right = -1e300;
  for (const auto& d : bodies) right = std::max(right, d.position.x());
  std::vector<dynamics::BodyDesc> open = tsupport::make_field(9u, 400, 16.0, 0.05, 0.01).bodies;
  double left = 1e300;
  for (const auto& d : open) left = std::min(left, d.position.x());
  for (dynamics::BodyDesc d : open) {
    d.id += 100000;
    d.position.x() += right - left + 40.0;  // [m]
    bodies.push_back(d);
  }
  SideBySide both(bodies, 1.0, 1.0);
  // Each rank's owned floes: of the pack, and in open water.
  auto owned = [&](std::vector<int>& pack, std::vector<int>& water) {
    int mine[2] = {0, 0};
    const dynamics::World& w = both.dw.local();
    for (int i = 0; i < static_cast<int>(w.size()); ++i)
      if (!w.is_ghost(i)) ++mine[w.id(i) < 100000 ? 0 : 1];
    pack.assign(static_cast<std::size_t>(mpi_ranks()), 0);
    water = pack;
    MPI_Allgather(&mine[0], 1, MPI_INT, pack.data(), 1, MPI_INT, MPI_COMM_WORLD);
    MPI_Allgather(&mine[1], 1, MPI_INT, water.data(), 1, MPI_INT, MPI_COMM_WORLD);
  };
  std::vector<int> pack_before, water_before, pack_after, water_after;
  owned(pack_before, water_before);
  EXPECT_GT(run_as_one(both.one, both.dw, both.dt, 3 * domain::DistributedWorld::kLoadCheck, 25), 2000u);
  owned(pack_after, water_after);
  if (mpi_ranks() == 1) return;
  EXPECT_GE(both.dw.rebalances(), 1u);
  // The ranks that hold mostly pack own fewer floes, on average, than those that hold mostly open water.
  double floes[2] = {0.0, 0.0}, ranks_of[2] = {0.0, 0.0};
  for (std::size_t r = 0; r < pack_after.size(); ++r) {
    const int kind = pack_after[r] > water_after[r] ? 0 : 1;
    floes[kind] += pack_after[r] + water_after[r];
    ranks_of[kind] += 1.0;
  }
  ASSERT_GT(ranks_of[0] * ranks_of[1], 0.0) << "no rank holds mostly pack, or none mostly open water";
  EXPECT_LT(floes[0] / ranks_of[0], 0.8 * floes[1] / ranks_of[1]) << "the regions were not cut for the floes' costs";
  if (mpi_rank() == 0) {
    std::printf(
        "floes owned per rank (pack + open water), cut for equal counts -> cut on measured cost (%llu "
        "rebalances):",
        static_cast<unsigned long long>(both.dw.rebalances()));
    for (std::size_t r = 0; r < pack_after.size(); ++r)
      std::printf(" %d+%d -> %d+%d", pack_before[r], water_before[r], pack_after[r], water_after[r]);
    std::printf("\n");
  }
}

TEST(DistributedState, GatheredIsOneWorldsAndRestoresOnAnyNumberOfRanks) {
  tsupport::PackSpec ps;
  ps.speed = 0.3;  // [m/s]
  ps.walls = false;
  const std::vector<dynamics::BodyDesc> bodies = tsupport::make_pack(200, ps, 5u).bodies;
  const dynamics::WorldSettings ws = tsupport::shared_ice_settings(contact::ForceModel::centroid, true);
  dynamics::World one(ws);
  for (const auto& d : bodies) one.add_body(d);
  const double dt = one.shortest_contact_duration(1.0) / 40.0;
  domain::DistributedWorld dw(MPI_COMM_WORLD, ws, bodies, 0.03);
  for (int s = 0; s < 100; ++s) {
    one.step(dt);
    dw.step(dt);
  }
  ASSERT_GT(one.contact_count(), 100u);
  const std::optional<dynamics::WorldState> gathered = dw.gather(0);
  EXPECT_EQ(gathered.has_value(), mpi_rank() == 0);
  if (gathered) expect_same_state(*gathered, one.state(), "gathered at step 100");
  if (tsupport::any_rank_failed()) return;
  // Restored from the one World's state (which the gathered state is, bit for bit) on every rank, and on one rank
  // fewer: 100 more steps, bitwise as the one World.
  const dynamics::WorldState at100 = one.state();
  for (int s = 0; s < 100; ++s) one.step(dt);
  const dynamics::WorldState at200 = one.state();
  for (const int fewer : {0, 1}) {
    const int ranks = std::max(1, mpi_ranks() - fewer);
    MPI_Comm comm = MPI_COMM_NULL;
    MPI_Comm_split(MPI_COMM_WORLD, mpi_rank() < ranks ? 0 : MPI_UNDEFINED, mpi_rank(), &comm);
    if (comm == MPI_COMM_NULL) continue;
    domain::DistributedWorld again(comm, ws, bodies, 0.03);
    again.restore(at100);
    for (int s = 0; s < 100; ++s) again.step(dt);
    const std::optional<dynamics::WorldState> end = again.gather(0);
    if (end) expect_same_state(*end, at200, "restored on " + std::to_string(ranks) + " ranks, step 200");
    MPI_Comm_free(&comm);
  }
}

TEST(DistributedState, AStateThatDoesNotFitIsRefusedOnEveryRank) {
  tsupport::PackSpec ps;
  ps.walls = false;
  const std::vector<dynamics::BodyDesc> bodies = tsupport::make_pack(60, ps, 4u).bodies;
  dynamics::World one(tsupport::no_drift());
  for (const auto& d : bodies) one.add_body(d);
  domain::DistributedWorld dw(MPI_COMM_WORLD, tsupport::no_drift(), bodies);
  auto refused = [&](dynamics::WorldState s, const std::string& says) {
    try {
      dw.restore(s);
      ADD_FAILURE() << "no error for a state that " << says;
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find(says), std::string::npos) << e.what();
    }
  };
  dynamics::WorldState s = one.state();
  s.ids[3] = 999;
  refused(s, "a body of id 999");
  s = one.state();
  s.ids[3] = s.ids[4];
  refused(s, "twice");
  s = one.state();
  s.velocity.pop_back();
  refused(s, "velocity");
  s = one.state();
  s.contact_history.push_back({contact::make_key(1, 777), {}});
  refused(s, "777");
  s = one.state();
  s.bonds.emplace();
  refused(s, "bonds");
  dw.restore(one.state());  // and the right one is taken
  dw.step(1e-4);
}

TEST(DistributedRefuses, AFloeOutrunningTheHalo) {
  tsupport::PackSpec ps;
  ps.walls = false;
  tsupport::Pack pack = tsupport::make_pack(60, ps, 4u);
  pack.bodies[7].velocity = {20.0, 0.0};  // [m/s]: 2 mm in one step of 0.1 ms
  domain::DistributedWorld dw(MPI_COMM_WORLD, tsupport::no_drift(), pack.bodies, 0.001);
  if (mpi_ranks() == 1) {  // one rank has no halo: nothing to miss, nothing to test
    EXPECT_NO_THROW(dw.step(1e-4));
    return;
  }
  try {
    dw.step(1e-4);
    ADD_FAILURE() << "no error";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("more than half the halo's margin"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("time step is far too large"), std::string::npos) << e.what();
  }
}

}  // namespace
