// The planar World cut among MPI ranks (domain/distributed_world.h), run by CTest under mpirun at 1, 2, 3 and 4
// ranks. Every rank is given the same jostling pack of 300 floes; checked against one World holding every floe:
//   - the pack with and without an ocean current, on 1 and 2 threads per rank, and a gas of floes at up to 10 m/s
//     that cross the ranks' regions (some floes migrate at 3 and 4 ranks), with a halo margin small enough that the
//     halo is renewed every few steps (47 renewals in the pack's 300 steps, 126 in the gas's 800): every rank's own
//     floes have bitwise the one World's poses, velocities, forces and torques at every 20th step, and the contacts
//     evaluated on all ranks add up to the one World's;
//   - a floe that moves more than half the margin between two renewals stops the run on every rank with a message
//     that says so (and that the time step is far too large).
#include <gtest/gtest.h>
#include <mpi.h>

#include <cstdio>
#include <string>
#include <vector>

#include "dense_pack.h"
#include "floe_gas.h"
#include "domain/distributed_world.h"
#include "dynamics/world.h"
#include "mpi_test_main.h"
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
    if (HasFailure()) return;
    std::uint64_t counts[2] = {owned, dw.local().contact_count()}, all[2] = {0, 0};
    MPI_Allreduce(counts, all, 2, MPI_UINT64_T, MPI_SUM, MPI_COMM_WORLD);
    ASSERT_EQ(all[0], one.size()) << "step " << step;  // each floe owned by one rank
    if (!c.gas) {
      ASSERT_GT(one.contact_count(), 100u);
    }
    contacts_seen += one.contact_count();
    ASSERT_EQ(all[1], one.contact_count()) << "step " << step;  // each pair evaluated by one rank
  }
  EXPECT_GE(dw.renewals(), 3u);
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

TEST(DistributedRefuses, AFloeOutrunningTheHalo) {
  tsupport::PackSpec ps;
  ps.walls = false;
  tsupport::Pack pack = tsupport::make_pack(60, ps, 4u);
  pack.bodies[7].velocity = {20.0, 0.0};  // [m/s]: 2 mm in one step of 0.1 ms
  domain::DistributedWorld dw(MPI_COMM_WORLD, tsupport::no_drift(), pack.bodies, 0.001);
  try {
    dw.step(1e-4);
    ADD_FAILURE() << "no error";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("more than half the halo's margin"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("time step is far too large"), std::string::npos) << e.what();
  }
}

}  // namespace
