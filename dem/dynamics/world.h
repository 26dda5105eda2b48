// The World: every body's state as arrays, and one step of the planar (x, y, yaw) dynamics.
//
// Hot state is kept as structure-of-arrays, indexed 0..size()-1; cold data (shape, id, material) lives apart.
// Indices are internal: anything that must survive (contact history, output, checkpoints) uses BodyId.
// The World never touches files; the run driver above it does.
#pragma once

#include <memory>
#include <optional>
#include <span>
#include <unordered_map>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include "bonds/bond_set.h"
#include "contact/broad_phase.h"
#include "contact/contact_cache.h"
#include "contact/contact_law.h"
#include "dynamics/bodies.h"
#include "dynamics/body.h"
#include "dynamics/contact_stage.h"
#include "dynamics/drift_model.h"
#include "dynamics/forcing_stage.h"
#include "dynamics/neighbour_lists.h"
#include "dynamics/slots.h"
#include "dynamics/state_fields.h"
#include "dynamics/step_exchange.h"
#include "dynamics/step_report.h"
#include "forcing/drift.h"

namespace polyfloe::dynamics {

// The fewest time steps per contact duration at which the step stays stable, with margin: the velocity-Verlet limit
// of an undamped central Hertz impact is t_c / dt = 2.015, but corner contacts on elongated floes (small effective
// mass, the tangential spring), damping and jammed packs (several contacts per floe) need up to 10 (measured:
// tests/bench/bench_stability, docs/performance.md "Stability map"). The run guard stops a run whose stiffest
// contact gets fewer; the scene reader refuses run.steps_per_contact below it.
inline constexpr double kMinStepsPerContact = 10.0;

struct WorldSettings {
  contact::ContactLawSettings contact;
  PlanarNarrowPhase narrow_phase = PlanarNarrowPhase::exact;
  forcing::DriftSettings drift;
  double broad_phase_cell = 0.0;  // grid cell size [m]; 0 = automatic
  // Skin of the broad phase's neighbour lists [m]; 0 = automatic (0.2 x the mean equivalent radius of the dynamic
  // bodies). A speed knob only: the contacts found, their order and so every result are the same for any value.
  double broad_phase_skin = 0.0;
  // Store the bodies in space order (the slots' order), re-stored as they drift apart from it: the per-body passes
  // of the step then read and write memory in the order of space, however the bodies were added (a field in random
  // order runs as fast as one in lattice order). A speed knob only: every result is the same, bitwise. Indices then
  // change between steps (the World's id_order() and index_of() follow; anything kept from step to step uses ids).
  // Off, indices are the order of add_body() for good. The scene's worlds (scene::build_world) store in space order.
  bool store_in_space_order = false;
  // The cell of the slots' order [m]; 0 = automatic (4 x the mean equivalent radius of the dynamic bodies). The
  // order in which each body's contact forces are added follows it: Worlds that share the ice (ghosts, set_ghost)
  // must share it to give the same bits.
  double space_order_cell = 0.0;
};

// Everything that carries from one step to the next and is not rebuilt from the scene: what a checkpoint stores
// so that a restarted run continues bitwise as the uninterrupted one would. Shapes, masses, quadrature points,
// bond geometry and world-frame vertices are rebuilt from the scene and the poses.
struct WorldState {
  double time = 0.0;  // [s]
  std::uint64_t steps = 0;
  bool forces_ready = false;                                    // forces below belong to this state
  std::vector<BodyId> ids;                                      // [N], the order of every array below
  std::vector<Vec2> position, velocity, force, external_force;  // [N] [m, m/s, N, N]
  std::vector<double> yaw, omega, torque, external_torque;      // [N] [rad, rad/s, N m, N m]
  // The drift load of the last evaluation with its damping matrix, and its linear model's load at v = 0 (empty
  // or [N]): the next step's velocity prediction reads them.
  std::vector<forcing::DriftLoad> drift_load;
  std::vector<Vec2> lin_force;
  std::vector<double> lin_torque;
  std::vector<contact::ContactCache::Entry> contact_history;  // per touching pair (contact/contact_cache.h)
  std::optional<bonds::BondState> bonds;
  int bonds_failed_last = 0;
};

// The fields of a WorldState (dynamics/state_fields.h), in the checkpoint's layout: scalars at the top, the
// per-body arrays in `world`, the contact history in `contacts`, the bonds' state in `bonds`.
template <class V, class S>
requires std::is_same_v<std::remove_const_t<S>, WorldState>
void visit_fields(V& v, S& s) {
  v.attribute("time", s.time);
  v.count("steps", "step count", s.steps, 1e12);
  v.attribute("forces_ready", s.forces_ready);
  v.attribute("bonds_failed_last", s.bonds_failed_last);
  v.group("world", [&] {
    v.bodies("ids", s.ids);
    v.bodies("position", s.position);
    v.bodies("yaw", s.yaw);
    v.bodies("velocity", s.velocity);
    v.bodies("omega", s.omega);
    v.bodies("force", s.force);
    v.bodies("torque", s.torque);
    v.bodies("external_force", s.external_force);
    v.bodies("external_torque", s.external_torque);
    v.bodies_or_none("drift_load", s.drift_load);
    v.bodies_or_none("lin_force", s.lin_force);
    v.bodies_or_none("lin_torque", s.lin_torque);
  });
  v.group("contacts", [&] { v.history(s.contact_history); });
  v.optional_group("bonds", s.bonds, [&](auto& b) {
    v.rows("face_intact", b.face_intact);
    v.rows("face_points_left", b.face_points_left);
    v.rows("face_broken_time", b.face_broken_time);
    v.rows("point_intact", b.point_intact);
    v.rows("point_sigma", b.point_sigma);
    v.rows("point_tau", b.point_tau);
    v.attribute("max_sigma", b.max_sigma);
    v.attribute("max_tau", b.max_tau);
  });
}

class World {
 public:
  explicit World(const WorldSettings& settings);

  // Adds a body and returns its index. Throws std::invalid_argument on a duplicate id or bad values.
  int add_body(const BodyDesc& desc);
  std::size_t size() const { return bodies_.id.size(); }

  // Advance by dt [s]: velocity-Verlet (kick, move, kick), forces evaluated at the new positions with the
  // half-step velocities. Returns the step's report: the bodies' motion (gathered in the final kick's loop, no
  // pass of its own; its energy summed in fixed blocks of bodies, so any thread count gives the same bits), the
  // deepest overlap and the shortest contact of the force evaluation.
  const StepReport& step(double dt);

  // Worker threads of step() (OpenMP; 1 = serial, the default). The result does not depend on it, bitwise: the
  // per-body stages write only their own body, and the contact stage evaluates every candidate pair apart, then
  // adds the forces up in the broad phase's order on one thread. Without OpenMP in the build it is ignored.
  void set_threads(int threads) { threads_ = threads < 1 ? 1 : threads; }
  int threads() const { return threads_; }

  double time() const { return time_; }  // [s]
  std::uint64_t step_count() const { return steps_; }
  void set_time(double t, std::uint64_t steps) {
    time_ = t;
    steps_ = steps;
  }

  // --- state (indices 0..size()-1) ---
  std::span<const Vec2> positions() const { return bodies_.pos; }               // [m]
  std::span<const double> yaws() const { return bodies_.yaw; }                  // [rad]
  std::span<const Vec2> velocities() const { return bodies_.vel; }              // [m/s]
  std::span<const double> angular_velocities() const { return bodies_.omega; }  // [rad/s]
  std::span<const Vec2> forces() const { return bodies_.force; }      // total force of the last evaluation [N]
  std::span<const double> torques() const { return bodies_.torque; }  // [N m]
  void set_velocity(int i, const Vec2& v, double omega);
  void set_external_load(int i, const Vec2& force, double torque);

  // --- cold data ---
  BodyId id(int i) const { return bodies_.id[i]; }
  int index_of(BodyId id) const;  // -1 if absent
  // The bodies' indices in increasing id: the order of every output, diagnostic sum and checkpoint, whatever order
  // the bodies are stored in (indices are where a body is stored; anything kept from one step to the next uses ids).
  std::span<const int> id_order() const;
  const geometry::ConvexPolygon& shape(int i) const { return *bodies_.shape[i]; }
  double thickness(int i) const { return bodies_.thickness[i]; }  // [m]
  double reach(int i) const { return bodies_.reach[i]; }          // the shape's circumradius about its centroid [m]
  double draft(int i) const { return bodies_.draft[i]; }          // floating draft h rho_ice / rho_w, at most h [m]
  double mass(int i) const { return bodies_.mass[i]; }            // [kg] (of the prism, also for walls)
  double inertia(int i) const { return bodies_.inertia[i]; }      // [kg m^2]
  Motion motion(int i) const { return bodies_.motion[i]; }
  // World-frame vertices of body i as of the last step (counter-clockwise).
  std::span<const Vec2> world_vertices(int i) const {
    return {world_xy_.data() + vert_begin_[i], static_cast<std::size_t>(bodies_.vert_off[i + 1] - bodies_.vert_off[i])};
  }

  // --- bonds between elements (frozen ice): none until set ---
  // Replaces the bond set (its element indices are this World's body indices). Pairs joined by an intact face skip
  // the contact law; bond forces are added in every force evaluation.
  void set_bonds(bonds::BondSet bonds);
  const bonds::BondSet* bonds() const { return bonds_ ? &*bonds_ : nullptr; }
  // Faces that failed in the last force evaluation.
  int bonds_failed_last() const { return bonds_failed_last_; }

  // --- a domain decomposition (domain/): owned bodies and ghosts ---
  // Marks body i a ghost (or owned again): a copy of a body another World owns, which may touch this World's own. A
  // ghost is not integrated here: its pose and its predicted velocity come from its owner through the step's
  // exchange (set_exchange; dynamics/step_exchange.h), and each pair whose lower-id body is a ghost is evaluated by
  // that body's owner, whose force on the pair's other body arrives through take_pair_forces(). A ghost's force,
  // torque and velocity here mean nothing: the sums over the bodies (kinetic_energy, ...) and the step's report
  // leave ghosts out. Each owned body then gets, bit for bit, the force it would get in one World holding every
  // body: its contacts are added in the order of the slots (a function of the positions and ids alone) wherever
  // they were evaluated, provided the slots' cell is the same everywhere (WorldSettings::space_order_cell).
  void set_ghost(int i, bool ghost);
  bool is_ghost(int i) const { return bodies_.ghost[i] != 0; }
  // The exchange the step calls (not owned; nullptr: none, the default).
  void set_exchange(StepExchange* exchange) { exchange_ = exchange; }
  // From the exchange: ghost i's pose after the move [m, rad], and its predicted velocity [m/s, rad/s].
  void set_ghost_pose(int i, const Vec2& position, double yaw);
  void set_ghost_prediction(int i, const Vec2& velocity, double omega);
  // The velocity at which this step's velocity-dependent forces are evaluated (predicted at its end) [m/s, rad/s].
  const Vec2& predicted_velocity(int i) const { return bodies_.vel_eval[i]; }
  double predicted_omega(int i) const { return bodies_.omega_eval[i]; }
  // The forces of the pairs evaluated here whose higher-id body is a ghost (for its owner), of the last evaluation.
  std::span<const PairForce> outgoing_pair_forces() const { return outgoing_; }
  // Forces other Worlds evaluated for pairs whose higher-id body this World owns (see PlanarContactStage).
  void take_pair_forces(std::span<const PairForce> in);

  // --- contacts of the last force evaluation ---
  // Listed from the last evaluation when first asked for after it (not safe to call from several threads at once),
  // in order of the pairs' ids (a's, then b's), whatever the storage order, threads or ranks.
  const std::vector<ContactRecord>& contacts() const;
  // A World that shows ice stepped elsewhere (a domain decomposition's state, gathered and restore()d here): the
  // contacts that were evaluated there, with this World's indices, listed by contacts() until the next evaluation
  // or restore(). Sorted here into contacts()'s order.
  void show_contacts(std::vector<ContactRecord> records);
  std::size_t contact_count() const { return contact_count_; }
  const contact::ContactCache& contact_cache() const { return cache_; }
  // Pairs the 2-D GJK-EPA narrow phase failed on (measured by the exact method instead), since the start.
  std::uint64_t narrow_phase_failures() const { return narrow_phase_failures_; }
  contact::ContactCache& contact_cache() { return cache_; }

  // --- diagnostics ---
  double kinetic_energy() const;    // dynamic bodies, translation + rotation [J]
  Vec2 linear_momentum() const;     // dynamic bodies [kg m/s]
  double angular_momentum() const;  // about the origin, z [kg m^2/s]
  double max_speed() const;         // [m/s]

  // The last step's report (dynamics/step_report.h), as step() returned it; its motion summary anew after a
  // change from outside (add_body, set_velocity, restore). Its overlap limit is kOverlapLimit x the smaller
  // equivalent radius of a pair.
  const StepReport& report() const;
  static constexpr double kOverlapLimit = 0.5;
  double dynamic_mass() const { return bodies_.dynamic_mass; }  // [kg], summed in body order

  // Duration of the shortest Hertz impact between the bodies present (smallest dynamic mass and radius) at
  // `speed` [m/s]; with the foundation force model also of the stiffest flat-face contact (a floe's longest edge
  // on an equal floe's), at any speed. The time step is a fraction of it [s].
  double shortest_contact_duration(double speed) const;
  // Its two parts: the Hertz impact at `speed`, and the flat-face contact (infinite unless the foundation model) [s].
  double shortest_hertz_contact_duration(double speed) const;
  double shortest_flat_contact_duration() const;

  const WorldSettings& settings() const { return settings_; }
  double space_order_cell() const { return order_.cell(); }  // the slots' cell in use [m]
  const contact::ContactLaw& contact_law() const { return law_; }
  const StepProfile& profile() const { return profile_; }
  // How often the broad phase's neighbour lists were rebuilt (a diagnostic of the skin; see WorldSettings).
  std::uint64_t neighbour_list_builds() const { return lists_.builds(); }
  // How often the bodies were stored anew in space order (WorldSettings::store_in_space_order).
  std::uint64_t body_reorders() const { return reorders_; }

  // The state a checkpoint needs (see WorldState), its bodies in id order, and its restoration into a World built
  // from the same scene (its rows in any order of the ids). restore() throws std::invalid_argument, naming the
  // first mismatch, when the bodies (their ids) or the bonds differ, or an array has the wrong size or a non-finite
  // value.
  WorldState state() const;
  void restore(const WorldState& s);

  // Recompute forces at the current state without moving (called once before the first step, and after a
  // restart). step() keeps them current afterwards.
  void compute_forces(double dt);

 private:
  // The members WorldState holds as plain copies, each with its field (dynamics/state_fields.h copy_members_*).
  template <class Self, class F>
  static void state_members(Self& w, F&& f) {
    f(&WorldState::time, w.time_);
    f(&WorldState::steps, w.steps_);
    f(&WorldState::forces_ready, w.forces_ready_);
    f(&WorldState::position, w.bodies_.pos);
    f(&WorldState::yaw, w.bodies_.yaw);
    f(&WorldState::velocity, w.bodies_.vel);
    f(&WorldState::omega, w.bodies_.omega);
    f(&WorldState::force, w.bodies_.force);
    f(&WorldState::torque, w.bodies_.torque);
    f(&WorldState::external_force, w.bodies_.ext_force);
    f(&WorldState::external_torque, w.bodies_.ext_torque);
    f(&WorldState::bonds_failed_last, w.bonds_failed_last_);
  }
  // compute_forces; with `shapes` (step()) its first pass also moves the world-frame shapes (the slots sorted).
  void evaluate_forces(double dt, bool shapes);
  // The first half kick, then the positions over the whole step and the slot keys there; whether a key changed.
  bool kick_and_move(double dt);
  void add_motion(std::size_t i, MotionSummary& s) const;  // body i's share of the motion summary
  static constexpr int kSummaryBlock = 64;                 // bodies per block of the motion summary's sums
  void kick_implicit(double dt);
  void update_shapes();
  void update_shape(int i);
  // Re-sorts the contact stage's slots (below) by the bodies' current positions and lays out the moved ones anew.
  // The slots in order of their keys (set by kick_and_move() or set_slot_keys(); `keys_changed`: whether any
  // changed since the last sort).
  void sort_slots(bool keys_changed);
  // With store_in_space_order: the bodies stored in slot order (body k the one in slot k), once the slots moved
  // since the last time cover an eighth of the bodies (at once on the first sort).
  void store_in_slot_order();
  std::size_t slots_moved_since_store_ = 0;
  std::uint64_t reorders_ = 0;
  bool set_slot_keys();  // every body's slot key at its position; whether any changed
  // Body i's packed slot data, its vertices starting at `vert_begin` in world_xy_.
  SlotStatic slot_static_of(int i, int vert_begin) const;
  void contact_forces(double dt);
  // The slots as the neighbour lists read them.
  SlotView slot_view() const;
  void bond_forces(double t);

  WorldSettings settings_;
  contact::ContactLaw law_;
  // The broad phase: the neighbour lists over the grid (dynamics/neighbour_lists.h).
  NeighbourLists lists_;
  contact::ContactCache cache_;
  std::optional<bonds::BondSet> bonds_;
  std::vector<double> bond_mass_;  // mass of each body for the bonds, +inf unless dynamic [kg]
  int bonds_failed_last_ = 0;
  double time_ = 0.0;
  std::uint64_t steps_ = 0;
  bool forces_ready_ = false;

  // The bodies' arrays (dynamics/bodies.h).
  Bodies bodies_;
  // The drift forcing's loads, their linear model and the final kick's damped inverses (dynamics/drift_model.h).
  DriftModel drift_;
  // world-frame shapes, refreshed after each move
  std::vector<int> vert_begin_;  // where body i's world-frame vertices start in world_xy_ (slot order, below)
  std::vector<Vec2> world_xy_;
  // The foundation force model's edge lines of each body's world-frame polygon (contact::EdgeLines about its first
  // vertex), beside world_xy_; empty under the other force models.
  std::vector<double> edge_nx_, edge_ny_, edge_offset_;
  std::vector<Vec2> rotation_;  // (cos yaw, sin yaw) of the world-frame shape

  // The contact stage works on "slots": the bodies sorted by position (dynamics/slots.h), so that bodies close in
  // space are close in memory whatever order they were added in; re-sorted every step. Indices stay the public
  // handle; slots are private to the step. World-frame vertices and boxes are stored in slot order. The order's
  // cell is 4 x the mean equivalent radius of the dynamic bodies.
  SlotOrder order_;
  std::vector<SlotStatic> slot_static_;
  std::vector<SlotState> slot_state_;
  std::vector<std::uint8_t> slot_dynamic_;
  std::vector<geometry::Aabb> boxes_;  // world-frame bounding boxes, by slot
  // scratch
  int threads_ = 1;
  mutable std::vector<int> by_id_;  // id_order(), listed when first asked for after a change
  mutable bool by_id_ready_ = false;
  mutable std::vector<ContactRecord> contacts_;  // listed on demand (contacts())
  mutable bool contacts_ready_ = true;
  std::size_t contact_count_ = 0;
  mutable StepReport report_;  // see report()
  mutable bool motion_ready_ = false;
  mutable std::vector<MotionSummary> motion_blocks_;  // by block of kSummaryBlock bodies, in the final kick
  void merge_motion_blocks() const;                   // motion_blocks_ into report_.motion, in block order
  // The contact stage (dynamics/contact_stage.h): pairs, their results and sums.
  PlanarContactStage contact_stage_;
  // The drift forcing stage (dynamics/forcing_stage.h) and what it reads of the bodies.
  DriftForcing drift_forcing_;
  DriftBodies drift_bodies() const;
  StepProfile profile_;
  std::uint64_t narrow_phase_failures_ = 0;
  // The domain decomposition's: the step's exchange, whether a ghost's key changed in it, the forces for ghosts.
  StepExchange* exchange_ = nullptr;
  bool ghost_keys_changed_ = false;
  std::vector<PairForce> outgoing_;
};

}  // namespace polyfloe::dynamics
