// Worlds that share the ice (dynamics/world.h "owned bodies and ghosts", dynamics/step_exchange.h): each World owns
// the floes of one stripe of a jostling pack and holds ghosts of the floes of the others that can touch its own;
// their steps exchange the ghosts' poses and predicted velocities and the contact forces of the pairs that cross
// stripes. The Worlds run side by side, one thread each, in lock step (an exchange through memory, with barriers),
// as ranks would under MPI. Checked against one World holding every floe:
//   - 2, 3 and 4 stripes, with the centroid and the foundation force models, with and without an ocean current
//     and wind (semi-implicit drag: the ghosts' predicted velocities matter), stored in space order: every owned
//     floe's pose, velocity, force and torque is bitwise the one World's at every 10th of 150 steps; the contacts
//     evaluated in all the Worlds together are the one World's, each evaluated by exactly one World, with the same
//     stored springs; the kinetic energy and momentum of the owned floes add up to the one World's (to rounding:
//     the sums run in a different order).
//   - A World whose ghosts leave out a floe that touches one of its own refuses the force evaluated for that pair
//     elsewhere with a message naming both bodies.
#include <gtest/gtest.h>

#include <algorithm>
#include <barrier>
#include <memory>
#include <string>
#include <thread>
#include <unordered_map>
#include <vector>

#include "dense_pack.h"
#include "dynamics/step_exchange.h"
#include "dynamics/world.h"
#include "shared_ice.h"

using namespace polyfloe;
using dynamics::BodyId;
using geometry::Vec2;

namespace {

// What the Worlds share: themselves, who owns which body, and each one's outgoing contact forces.
struct Shared {
  explicit Shared(int n) : sync(n), out(static_cast<std::size_t>(n)), error(static_cast<std::size_t>(n)) {}
  std::barrier<> sync;
  std::vector<dynamics::World*> worlds;
  std::unordered_map<BodyId, int> owner;
  std::vector<std::vector<dynamics::PairForce>> out;
  std::vector<std::string> error;  // by World: what take_pair_forces threw (the others then do not wait forever)
};

// The exchange of World `rank`: reads the owners' arrays between barriers (nobody writes them meanwhile).
class LockStep : public dynamics::StepExchange {
 public:
  LockStep(Shared& s, int rank) : s_(s), rank_(rank) {}
  void poses(dynamics::World& w) override {
    s_.sync.arrive_and_wait();  // every World moved its own
    for_ghosts(w, [&](int i, const dynamics::World& o, int j) { w.set_ghost_pose(i, o.positions()[j], o.yaws()[j]); });
    s_.sync.arrive_and_wait();  // every ghost read before any owner goes on
  }
  void predictions(dynamics::World& w) override {
    s_.sync.arrive_and_wait();
    for_ghosts(w, [&](int i, const dynamics::World& o, int j) {
      w.set_ghost_prediction(i, o.predicted_velocity(j), o.predicted_omega(j));
    });
    s_.sync.arrive_and_wait();
  }
  void pair_forces(dynamics::World& w) override {
    const auto mine = w.outgoing_pair_forces();
    s_.out[static_cast<std::size_t>(rank_)].assign(mine.begin(), mine.end());
    s_.sync.arrive_and_wait();
    std::vector<dynamics::PairForce> in;
    for (std::size_t r = 0; r < s_.out.size(); ++r)
      for (const dynamics::PairForce& f : s_.out[r])
        if (s_.owner.at(f.b) == rank_) in.push_back(f);
    try {
      w.take_pair_forces(in);
    } catch (const std::exception& e) {
      s_.error[static_cast<std::size_t>(rank_)] = e.what();
    }
    s_.sync.arrive_and_wait();
  }

 private:
  template <class F>
  void for_ghosts(const dynamics::World& w, F&& f) {
    for (int i = 0; i < static_cast<int>(w.size()); ++i) {
      if (!w.is_ghost(i)) continue;
      const dynamics::World& o = *s_.worlds[static_cast<std::size_t>(s_.owner.at(w.id(i)))];
      f(i, o, o.index_of(w.id(i)));
    }
  }
  Shared& s_;
  int rank_;
};

struct Case {
  int worlds = 2;
  contact::ForceModel model = contact::ForceModel::centroid;
  bool drift = false;
};

dynamics::WorldSettings settings_of(const Case& c) { return tsupport::shared_ice_settings(c.model, c.drift); }

// The floes of `pack` cut into `n` stripes of x (as many floes each), with the ghosts each stripe's World needs: the
// floes not its own whose circumscribed box, grown by `margin` [m], overlaps the box around its own grown the same.
struct Split {
  std::vector<int> owner;                // by floe of the pack
  std::vector<std::vector<int>> ghosts;  // by World: floes of the pack
};

Split split(const std::vector<dynamics::BodyDesc>& bodies, int n, double margin) {
  Split s;
  std::vector<int> by_x(bodies.size());
  for (std::size_t k = 0; k < bodies.size(); ++k) by_x[k] = static_cast<int>(k);
  std::sort(by_x.begin(), by_x.end(), [&](int a, int b) { return bodies[a].position.x() < bodies[b].position.x(); });
  s.owner.resize(bodies.size());
  for (std::size_t r = 0; r < by_x.size(); ++r)
    s.owner[static_cast<std::size_t>(by_x[r])] = static_cast<int>(r * static_cast<std::size_t>(n) / by_x.size());
  auto box = [&](std::size_t k) {
    const double reach = bodies[k].shape->circumradius() + margin;
    return geometry::Aabb{bodies[k].position - Vec2{reach, reach}, bodies[k].position + Vec2{reach, reach}};
  };
  s.ghosts.resize(static_cast<std::size_t>(n));
  for (int r = 0; r < n; ++r) {
    geometry::Aabb own{{1e300, 1e300}, {-1e300, -1e300}};
    for (std::size_t k = 0; k < bodies.size(); ++k)
      if (s.owner[k] == r) own = {own.lo.cwiseMin(box(k).lo), own.hi.cwiseMax(box(k).hi)};
    for (std::size_t k = 0; k < bodies.size(); ++k)
      if (s.owner[k] != r && box(k).overlaps(own)) s.ghosts[static_cast<std::size_t>(r)].push_back(static_cast<int>(k));
  }
  return s;
}

// The Worlds of a split, each with its exchange.
struct SharedIce {
  SharedIce(const std::vector<dynamics::BodyDesc>& bodies, const Split& sp, const dynamics::WorldSettings& ws)
      : shared(static_cast<int>(sp.ghosts.size())) {
    const int n = static_cast<int>(sp.ghosts.size());
    for (int r = 0; r < n; ++r) {
      worlds.push_back(std::make_unique<dynamics::World>(ws));
      exchanges.push_back(std::make_unique<LockStep>(shared, r));
      shared.worlds.push_back(worlds.back().get());
    }
    for (std::size_t k = 0; k < bodies.size(); ++k) {
      shared.owner[bodies[k].id] = sp.owner[k];
      worlds[static_cast<std::size_t>(sp.owner[k])]->add_body(bodies[k]);
    }
    for (int r = 0; r < n; ++r) {
      dynamics::World& w = *worlds[static_cast<std::size_t>(r)];
      for (const int k : sp.ghosts[static_cast<std::size_t>(r)]) w.set_ghost(w.add_body(bodies[k]), true);
      w.set_exchange(exchanges[static_cast<std::size_t>(r)].get());
    }
  }
  // `steps` steps of every World, each on its own thread.
  void step(double dt, int steps) {
    std::vector<std::thread> threads;
    for (auto& w : worlds)
      threads.emplace_back([&w, dt, steps] {
        for (int s = 0; s < steps; ++s) w->step(dt);
      });
    for (auto& t : threads) t.join();
  }
  Shared shared;
  std::vector<std::unique_ptr<dynamics::World>> worlds;
  std::vector<std::unique_ptr<LockStep>> exchanges;
};

class Ghosts : public ::testing::TestWithParam<Case> {};

TEST_P(Ghosts, WorldsSharingThePackGiveEachOwnedFloeTheBitsOfOneWorld) {
  const Case c = GetParam();
  tsupport::PackSpec ps;
  ps.speed = 0.3;  // [m/s]: the pack jostles, contacts open and close
  ps.walls = false;
  const tsupport::Pack pack = tsupport::make_pack(300, ps, 11u);
  dynamics::WorldSettings ws = settings_of(c);
  dynamics::World one(ws);
  for (const auto& d : pack.bodies) one.add_body(d);
  // The slots' cell is the one World's: the Worlds hold different floes, and the order of each floe's contact sum
  // follows the cell (WorldSettings::space_order_cell).
  ws.space_order_cell = one.space_order_cell();
  const double dt = one.shortest_contact_duration(1.0) / 40.0;
  const Split sp = split(pack.bodies, c.worlds, 0.5 * ps.spacing);  // (the floes move < 1 m in 150 steps)
  SharedIce ice(pack.bodies, sp, ws);
  std::size_t ghosts = 0;
  for (const auto& g : sp.ghosts) ghosts += g.size();
  ASSERT_GT(ghosts, 20u);
  for (int round = 1; round <= 15; ++round) {
    for (int s = 0; s < 10; ++s) one.step(dt);
    ice.step(dt, 10);
    for (const std::string& e : ice.shared.error) ASSERT_EQ(e, "");
    const int step = 10 * round;
    std::size_t contacts = 0, owned = 0;
    double energy = 0.0;
    std::vector<contact::ContactCache::Entry> springs;
    for (const auto& w : ice.worlds) {
      owned += tsupport::expect_owned_as_in_one(*w, one, step);
      if (HasFailure()) return;
      contacts += w->contact_count();
      energy += w->kinetic_energy();
      const auto& e = w->contact_cache().entries();
      springs.insert(springs.end(), e.begin(), e.end());
    }
    ASSERT_EQ(owned, one.size());
    ASSERT_GT(one.contact_count(), 100u);
    ASSERT_EQ(contacts, one.contact_count()) << "step " << step;  // each pair evaluated once
    auto by_key = [](const auto& x, const auto& y) {
      return x.first.lo != y.first.lo ? x.first.lo < y.first.lo : x.first.hi < y.first.hi;
    };
    std::sort(springs.begin(), springs.end(), by_key);
    std::vector<contact::ContactCache::Entry> one_springs = one.contact_cache().entries();
    std::sort(one_springs.begin(), one_springs.end(), by_key);
    ASSERT_EQ(springs, one_springs) << "step " << step;
    EXPECT_NEAR(energy, one.kinetic_energy(), 1e-12 * one.kinetic_energy());
  }
}

INSTANTIATE_TEST_SUITE_P(
    Stripes, Ghosts,
    ::testing::Values(Case{2, contact::ForceModel::centroid, false}, Case{3, contact::ForceModel::centroid, false},
                      Case{4, contact::ForceModel::centroid, false}, Case{3, contact::ForceModel::foundation, false},
                      Case{3, contact::ForceModel::centroid, true}, Case{4, contact::ForceModel::foundation, true}),
    [](const auto& info) {
      return std::to_string(info.param.worlds) + "Worlds_" + std::string(contact::force_model_name(info.param.model)) +
             (info.param.drift ? "_Drifting" : "");
    });

TEST(GhostsRefuse, AForceForAPairTheGhostsDoNotCover) {
  // Two Worlds, the second missing a ghost of a floe of the first's that touches one of its own.
  tsupport::PackSpec ps;
  ps.walls = false;
  const tsupport::Pack pack = tsupport::make_pack(60, ps, 4u);
  const dynamics::WorldSettings ws = settings_of({});
  Split sp = split(pack.bodies, 2, 0.5 * ps.spacing);
  // Drop the first World's floes from the second World's ghosts: every pair across the cut then arrives unasked.
  sp.ghosts[1].clear();
  SharedIce ice(pack.bodies, sp, ws);
  ice.step(1e-4, 1);
  EXPECT_EQ(ice.shared.error[0], "");
  EXPECT_NE(ice.shared.error[1].find("the ghosts do not cover the pairs"), std::string::npos) << ice.shared.error[1];
  EXPECT_NE(ice.shared.error[1].find("contact force between bodies"), std::string::npos);
}

}  // namespace
