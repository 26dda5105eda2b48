// The halo over MPI (domain/halo.h), run by CTest under mpirun at 1, 2, 3 and 4 ranks. Every rank builds the same
// jostling pack of 300 floes; Zoltan's RCB (domain/partition.h) gives each floe its owner, halo_layout() each rank
// its ghosts, and each rank steps a World of its own floes and its ghosts with a HaloExchange. Checked against one
// World holding every floe, at every 10th of 150 steps:
//   - every rank's own floes have bitwise the one World's poses, velocities, forces and torques, with the centroid
//     and the foundation force models, with and without an ocean current (semi-implicit drag);
//   - the contacts evaluated on all ranks add up to the one World's (each pair evaluated by one rank);
//   - the same with the last rank owning no floe at all (the floes dealt to the others by x);
//   - the layout: each rank's ghosts are owned elsewhere and sent by their owner, and with several ranks the ranks
//     exchange messages.
#include <gtest/gtest.h>
#include <mpi.h>

#include <algorithm>
#include <memory>
#include <string>
#include <unordered_map>
#include <vector>

#include "dense_pack.h"
#include "domain/halo.h"
#include "domain/partition.h"
#include "dynamics/world.h"
#include "mpi_test_main.h"
#include "shared_ice.h"

using namespace polyfloe;
using dynamics::BodyId;
using geometry::Vec2;
using tsupport::mpi_rank;
using tsupport::mpi_ranks;

namespace {

struct Case {
  contact::ForceModel model = contact::ForceModel::centroid;
  bool drift = false;
  bool empty_rank = false;  // the last rank owns nothing
};

// Each floe's owner: by Zoltan's RCB (its centroid's region), or dealt by x to all ranks but the last.
std::vector<int> owners(const std::vector<dynamics::BodyDesc>& bodies, bool empty_rank) {
  std::vector<int> owner(bodies.size());
  if (empty_rank && mpi_ranks() > 1) {
    std::vector<std::size_t> by_x(bodies.size());
    for (std::size_t k = 0; k < by_x.size(); ++k) by_x[k] = k;
    std::sort(by_x.begin(), by_x.end(),
              [&](std::size_t a, std::size_t b) { return bodies[a].position.x() < bodies[b].position.x(); });
    const std::size_t holders = static_cast<std::size_t>(mpi_ranks() - 1);
    for (std::size_t r = 0; r < by_x.size(); ++r) owner[by_x[r]] = static_cast<int>(r * holders / by_x.size());
    return owner;
  }
  domain::Partition part(MPI_COMM_WORLD);
  std::vector<domain::PartitionItem> items;  // each rank offers a share: where they start must not matter
  for (std::size_t k = 0; k < bodies.size(); ++k)
    if (static_cast<int>(k % static_cast<std::size_t>(mpi_ranks())) == mpi_rank())
      items.push_back({bodies[k].id, bodies[k].position, 1.0});
  part.balance(items);
  for (std::size_t k = 0; k < bodies.size(); ++k) owner[k] = part.rank_of(bodies[k].position);
  return owner;
}

class Halo : public ::testing::TestWithParam<Case> {};

TEST_P(Halo, EachRanksFloesMoveBitwiseAsInOneWorld) {
  const Case c = GetParam();
  tsupport::PackSpec ps;
  ps.speed = 0.3;  // [m/s]
  ps.walls = false;
  const tsupport::Pack pack = tsupport::make_pack(300, ps, 11u);
  dynamics::WorldSettings ws = tsupport::shared_ice_settings(c.model, c.drift);
  dynamics::World one(ws);
  for (const auto& d : pack.bodies) one.add_body(d);
  ws.space_order_cell = one.space_order_cell();  // shared by every rank's World
  const double dt = one.shortest_contact_duration(1.0) / 40.0;

  const std::vector<int> owner = owners(pack.bodies, c.empty_rank);
  std::unordered_map<BodyId, std::size_t> by_id;
  std::vector<domain::HaloItem> mine;
  for (std::size_t k = 0; k < pack.bodies.size(); ++k) {
    const dynamics::BodyDesc& d = pack.bodies[k];
    by_id[d.id] = k;
    const double r = d.shape->circumradius();
    if (owner[k] == mpi_rank()) mine.push_back({d.id, {d.position - Vec2{r, r}, d.position + Vec2{r, r}}});
  }
  if (c.empty_rank && mpi_ranks() > 1 && mpi_rank() == mpi_ranks() - 1) {
    ASSERT_TRUE(mine.empty());
  }
  domain::HaloExchange halo(MPI_COMM_WORLD, domain::halo_layout(MPI_COMM_WORLD, mine, 0.5 * ps.spacing));
  dynamics::World w(ws);
  for (const domain::HaloItem& it : mine) w.add_body(pack.bodies[by_id.at(it.id)]);
  std::size_t ghosts = 0;
  for (int q = 0; q < mpi_ranks(); ++q)
    for (const BodyId id : halo.layout().recv[static_cast<std::size_t>(q)]) {
      ASSERT_NE(q, mpi_rank());
      ASSERT_NE(owner[by_id.at(id)], mpi_rank()) << "ghost " << id;
      ASSERT_EQ(owner[by_id.at(id)], q) << "ghost " << id;
      w.set_ghost(w.add_body(pack.bodies[by_id.at(id)]), true);
      ++ghosts;
    }
  w.set_exchange(&halo);
  std::size_t all_ghosts = 0;
  MPI_Allreduce(&ghosts, &all_ghosts, 1, MPI_UINT64_T, MPI_SUM, MPI_COMM_WORLD);
  if (const int holders = c.empty_rank ? mpi_ranks() - 1 : mpi_ranks(); holders > 1) {
    ASSERT_GT(all_ghosts, 10u);
  }

  for (int round = 1; round <= 15; ++round) {
    for (int s = 0; s < 10; ++s) {
      one.step(dt);
      w.step(dt);
    }
    const int step = 10 * round;
    tsupport::expect_owned_as_in_one(w, one, step);
    if (tsupport::any_rank_failed()) return;
    const std::uint64_t contacts = w.contact_count();
    std::uint64_t all = 0;
    MPI_Allreduce(&contacts, &all, 1, MPI_UINT64_T, MPI_SUM, MPI_COMM_WORLD);
    ASSERT_GT(one.contact_count(), 100u);
    ASSERT_EQ(all, one.contact_count()) << "step " << step;
  }
  if (all_ghosts > 0 && !mine.empty()) {
    EXPECT_GT(halo.messages_sent(), 0u);
  }
}

INSTANTIATE_TEST_SUITE_P(Packs, Halo,
                         ::testing::Values(Case{contact::ForceModel::centroid, false, false},
                                           Case{contact::ForceModel::foundation, false, false},
                                           Case{contact::ForceModel::centroid, true, false},
                                           Case{contact::ForceModel::centroid, false, true}),
                         [](const auto& info) {
                           return std::string(contact::force_model_name(info.param.model)) +
                                  (info.param.drift ? "_Drifting" : "") + (info.param.empty_rank ? "_EmptyRank" : "");
                         });

}  // namespace
