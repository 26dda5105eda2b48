// What the ranks of a DistributedWorld gather for one of them (domain/distributed_world.h): the last evaluation's
// contacts, and the bonds' state from each face's home.
#include "domain/distributed_world.h"

#include <algorithm>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <tuple>
#include <vector>

#include "domain/collectives.h"

namespace polyfloe::domain {

using dynamics::BodyId;

namespace {

// A contact record as plain numbers (Eigen's vectors are not trivially copyable), for the gather.
struct ContactWire {
  BodyId a, b;
  double normal[2], point[2], depth, area, normal_force, tangential_force, force[2], energy;
  std::uint64_t sliding;
};

}  // namespace

std::vector<DistributedWorld::Contact> DistributedWorld::gather_contacts(int root) const {
  const dynamics::World& w = *world_;
  std::vector<ContactWire> mine;
  for (const dynamics::ContactRecord& r : w.contacts()) {
    const dynamics::ContactGeometry& g = r.geometry;
    mine.push_back({w.id(r.a),
                    w.id(r.b),
                    {g.normal.x(), g.normal.y()},
                    {g.point.x(), g.point.y()},
                    g.depth,
                    g.area,
                    r.normal_force,
                    r.tangential_force,
                    {r.force.x(), r.force.y()},
                    r.energy,
                    r.sliding ? 1u : 0u});
  }
  std::vector<Contact> all;
  for (const std::vector<ContactWire>& from : gather_to(comm_, root, mine))
    for (const ContactWire& c : from) {
      Contact k{c.a, c.b, {}};
      dynamics::ContactRecord& r = k.record;
      r.geometry = {{c.normal[0], c.normal[1]}, {c.point[0], c.point[1]}, c.depth, c.area};
      r.normal_force = c.normal_force;
      r.tangential_force = c.tangential_force;
      r.sliding = c.sliding != 0;
      r.force = {c.force[0], c.force[1]};
      r.energy = c.energy;
      all.push_back(k);
    }
  std::sort(all.begin(), all.end(),
            [](const Contact& x, const Contact& y) { return std::tie(x.a, x.b) < std::tie(y.a, y.b); });
  return all;
}

namespace {

// A bonded face's state and its points' (bonds::BondState's rows), by its index in the whole ice's set.
struct FaceRow {
  std::uint64_t face;
  std::int64_t points_left;
  double broken_time;
  std::uint64_t intact, failed_last;  // failed_last: it failed in the last evaluation
};
struct PointRow {
  double sigma, tau;
  std::uint64_t intact;
};

}  // namespace

void DistributedWorld::collect_bonds(int root, dynamics::WorldState* full) const {
  const dynamics::World& w = *world_;
  const bonds::BondSet& local = *w.bonds();
  const bonds::BondState s = local.state();
  const auto k = static_cast<std::size_t>(local.material().points_per_face);
  std::vector<FaceRow> faces;
  std::vector<PointRow> points;
  for (std::size_t f = 0; f < local.faces(); ++f) {
    const BodyId lower = std::min(local.face_id_a(f), local.face_id_b(f));
    if (w.is_ghost(w.index_of(lower))) continue;  // the face's home is the rank that owns its lower-id element
    const bool failed_last = !s.face_intact[f] && s.face_broken_time[f] == w.time();
    faces.push_back(
        {local.global_face(f), s.face_points_left[f], s.face_broken_time[f], s.face_intact[f], failed_last ? 1u : 0u});
    for (std::size_t p = local.face_first_point(f); p < local.face_first_point(f) + k; ++p)
      points.push_back({s.point_sigma[p], s.point_tau[p], s.point_intact[p]});
  }
  double most[2] = {local.max_sigma(), local.max_tau()}, all_most[2] = {0.0, 0.0};
  const std::vector<std::vector<FaceRow>> face_rows =
      root < 0 ? all_gather(comm_, faces) : gather_to(comm_, root, faces);
  const std::vector<std::vector<PointRow>> point_rows =
      root < 0 ? all_gather(comm_, points) : gather_to(comm_, root, points);
  if (root < 0)
    MPI_Allreduce(most, all_most, 2, MPI_DOUBLE, MPI_MAX, comm_);
  else
    MPI_Reduce(most, all_most, 2, MPI_DOUBLE, MPI_MAX, root, comm_);
  if (root >= 0 && rank() != root) return;
  bonds::BondState b = bonds_->state();  // every face's rows, each then taken from its home
  std::size_t homed = 0;
  for (const std::vector<FaceRow>& rows : face_rows) homed += rows.size();
  if (homed != bonds_->faces())
    throw std::logic_error(std::to_string(homed) + " of " + std::to_string(bonds_->faces()) +
                           " bonded faces are held by the rank that owns their lower-id element: the halo does not "
                           "cover the bonds");
  int failed = 0;
  for (std::size_t q = 0; q < face_rows.size(); ++q)
    for (std::size_t j = 0; j < face_rows[q].size(); ++j) {
      const FaceRow& r = face_rows[q][j];
      b.face_intact[r.face] = static_cast<std::uint8_t>(r.intact);
      b.face_points_left[r.face] = static_cast<std::int32_t>(r.points_left);
      b.face_broken_time[r.face] = r.broken_time;
      failed += static_cast<int>(r.failed_last);
      for (std::size_t p = 0; p < k; ++p) {
        const PointRow& x = point_rows[q][j * k + p];
        b.point_sigma[r.face * k + p] = x.sigma;
        b.point_tau[r.face * k + p] = x.tau;
        b.point_intact[r.face * k + p] = static_cast<std::uint8_t>(x.intact);
      }
    }
  b.max_sigma = all_most[0];
  b.max_tau = all_most[1];
  if (full) {
    full->bonds = std::move(b);
    full->bonds_failed_last = failed;
  } else {
    bonds_->restore(b);
  }
}

}  // namespace polyfloe::domain
