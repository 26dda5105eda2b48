// The planar World's bodies as arrays (a structure of arrays in body order: entry i is body i): state, loads,
// properties, body-frame vertices and drag quadrature points. add() checks a body and derives what the stages read
// of it (mass and inertia, draft and submerged side area, contact radius, quadrature points); the World owns one
// Bodies, and its stages read and write the arrays directly, as LAMMPS's styles read Atom's.
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <span>
#include <unordered_map>
#include <vector>

#include "dynamics/body.h"
#include "forcing/quadrature.h"
#include "geometry/polygon.h"

namespace polyfloe::dynamics {

struct Bodies {
  // Hot state, read and written by every step.
  std::vector<Vec2> pos, vel, force, ext_force;  // centroid [m], [m/s], total force of the last evaluation [N], [N]
  std::vector<double> yaw, omega, torque, ext_torque;  // [rad], [rad/s], [N m], [N m]
  std::vector<double> inv_mass, inv_inertia;           // 0 unless dynamic [1/kg], [1/(kg m^2)]
  std::vector<Vec2> vel_eval;                          // velocity at which velocity-dependent forces are evaluated
  std::vector<double> omega_eval;                      // [m/s], [rad/s]

  // Cold data, set by add().
  std::vector<BodyId> id;
  std::unordered_map<BodyId, int> index;
  std::vector<std::shared_ptr<const geometry::ConvexPolygon>> shape;
  std::vector<double> thickness, mass, inertia, plan_area;  // [m], [kg], [kg m^2], [m^2]
  std::vector<double> radius;  // the contact law's radius: the equivalent radius, infinite unless dynamic [m]
  std::vector<double> draft, side_area, equivalent_radius;  // [m], submerged side area [m^2], sqrt(A/pi) [m]
  std::vector<double> reach;                                // circumradius about the centroid [m]
  std::vector<Motion> motion;
  std::vector<std::uint8_t> is_dynamic;
  // 1: a ghost, the copy of a body another World owns (a domain decomposition's; World::set_ghost), 0 by add().
  std::vector<std::uint8_t> ghost;
  std::vector<int> quad_off{0};          // body i's bottom/top quadrature points: quad_off[i] .. quad_off[i+1]-1
  std::vector<double> quad_lx, quad_ly;  // body-frame lever of each point from the centroid [m]
  std::vector<double> quad_weight;       // area carried [m^2]
  std::vector<int> vert_off{0};          // prefix sums of the vertex counts (vertex count = difference)
  std::vector<Vec2> local_xy;            // body-frame vertices, from vert_off[i]: read without a pointer chase

  // Sums over the bodies, in body order.
  double dynamic_mass = 0.0;        // [kg]
  double dynamic_radius_sum = 0.0;  // of the equivalent radii [m]
  int dynamic_count = 0;
  std::size_t max_quad_points = 0, max_vertices = 0;

  std::size_t size() const { return id.size(); }
  int index_of(BodyId body) const {
    const auto it = index.find(body);
    return it == index.end() ? -1 : it->second;
  }
  // Checks `d` (shape, vertex count, thickness, density, a new id) and appends it, floating at its equilibrium
  // draft in water of `water_density` [kg/m^3] (a body denser than water fully submerged), with the drag
  // quadrature points of `rule`; returns its index. Throws std::invalid_argument naming the body.
  int add(const BodyDesc& d, double water_density, forcing::Quadrature rule);
  // Stores the bodies anew: body k becomes body from[k] of before (a permutation of 0..size()-1). The sums above
  // keep their values.
  void permute(std::span<const int> from);

  // Every per-body array: rows(a) for each array of one row per body, ranges(off, a...) for each offset table with
  // the arrays it cuts into rows. The one list of them that permute() (and anything that moves bodies) walks: a
  // member added to Bodies must be listed here, or counted among the others below (the build fails otherwise).
  template <class Self, class Rows, class Ranges>
  static void for_each_array(Self& b, Rows&& rows, Ranges&& ranges) {
    rows(b.pos), rows(b.vel), rows(b.force), rows(b.ext_force), rows(b.yaw), rows(b.omega), rows(b.torque);
    rows(b.ext_torque), rows(b.inv_mass), rows(b.inv_inertia), rows(b.vel_eval), rows(b.omega_eval);
    rows(b.id), rows(b.shape), rows(b.thickness), rows(b.mass), rows(b.inertia), rows(b.plan_area), rows(b.radius);
    rows(b.draft), rows(b.side_area), rows(b.equivalent_radius), rows(b.reach), rows(b.motion), rows(b.is_dynamic);
    rows(b.ghost);
    ranges(b.quad_off, b.quad_lx, b.quad_ly, b.quad_weight);
    ranges(b.vert_off, b.local_xy);
  }
  static constexpr std::size_t kRowArrays = 26, kRangeMembers = 6;
  // The members that are not per-body arrays: the id -> index map and the sums.
  static constexpr std::size_t kOtherMembers = 6;
};

namespace detail {
// The number of members of an aggregate (by how many values it can be brace-initialised from).
struct AnyMember {
  template <class T>
  operator T() const;
};
template <class T, class... A>
constexpr std::size_t member_count() {
  if constexpr (requires { T{A{}..., AnyMember{}}; })
    return member_count<T, A..., AnyMember>();
  else
    return sizeof...(A);
}
}  // namespace detail

static_assert(detail::member_count<Bodies>() == Bodies::kRowArrays + Bodies::kRangeMembers + Bodies::kOtherMembers,
              "a member was added to Bodies: list it in Bodies::for_each_array (or among the other members) and "
              "update the counts there");

}  // namespace polyfloe::dynamics
