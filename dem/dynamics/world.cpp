#include "dynamics/world.h"
#include "geometry/space_order.h"

#include "dynamics/parallel.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <stdexcept>
#include <numbers>
#include <string>
#include <utility>

namespace polyfloe::dynamics {

World::World(const WorldSettings& settings)
    : settings_(settings), law_(settings.contact), lists_(settings.broad_phase_cell) {
  // (the scene reader says the same naming the scene's key, forcing.update_every)
  const forcing::DriftSettings& d = settings.drift;
  if (d.update_every < 1 || d.update_every > 1000)
    throw std::invalid_argument("DriftSettings::update_every is " + std::to_string(d.update_every) +
                                "; it must be in [1, 1000]");
  if (d.update_every > 1 && d.treatment != forcing::DriftTreatment::semi_implicit)
    throw std::invalid_argument("DriftSettings::update_every = " + std::to_string(d.update_every) +
                                " needs the semi-implicit treatment (the linear model between full evaluations "
                                "is its damping matrix); use 1 with the explicit one");
  if (settings.contact.force_model == contact::ForceModel::foundation &&
      settings.narrow_phase == PlanarNarrowPhase::gjk_epa)
    throw std::invalid_argument(
        "the foundation force model needs the exact narrow phase (it integrates over the "
        "overlap polygon)");
}

int World::add_body(const BodyDesc& d) {
  const int i = bodies_.add(d, settings_.drift.water_density, settings_.drift.quadrature);
  const bool dyn = bodies_.is_dynamic[i] != 0;
  drift_.forget_inverses();
  motion_ready_ = false;
  vert_begin_.push_back(bodies_.vert_off[i]);
  world_xy_.resize(static_cast<std::size_t>(bodies_.vert_off.back()));
  if (settings_.contact.force_model == contact::ForceModel::foundation) {
    edge_nx_.resize(world_xy_.size());
    edge_ny_.resize(world_xy_.size());
    edge_offset_.resize(world_xy_.size());
  }
  rotation_.emplace_back(1.0, 0.0);
  // A new body takes the last slot (its vertices go at the end of world_xy_); the next step sorts the slots.
  if (settings_.space_order_cell > 0.0)
    order_.set_cell(settings_.space_order_cell);
  else if (dyn)
    order_.set_cell(geometry::space_order_cell(bodies_.dynamic_radius_sum / bodies_.dynamic_count));
  lists_.set_skin(settings_.broad_phase_skin > 0.0 ? settings_.broad_phase_skin
                  : bodies_.dynamic_count > 0      ? 0.2 * bodies_.dynamic_radius_sum / bodies_.dynamic_count
                                                   : 1.0);
  lists_.invalidate();  // rebuilt at the next evaluation
  order_.add(i, d.id);
  by_id_ready_ = false;
  slot_static_.push_back(slot_static_of(i, vert_begin_[i]));
  slot_dynamic_.push_back(bodies_.is_dynamic[i]);
  boxes_.emplace_back();
  update_shape(i);
  forces_ready_ = false;
  return i;
}

SlotStatic World::slot_static_of(int i, int vert_begin) const {
  return {bodies_.is_dynamic[i] ? bodies_.mass[i] : contact::kInfinite,
          bodies_.radius[i],
          bodies_.equivalent_radius[i],
          bodies_.id[i],
          i,
          vert_begin,
          bodies_.vert_off[i + 1] - bodies_.vert_off[i],
          bodies_.ghost[i]};
}

int World::index_of(BodyId id) const { return bodies_.index_of(id); }

std::span<const int> World::id_order() const {
  if (!by_id_ready_) {
    sort_by_id(bodies_.id, by_id_);
    by_id_ready_ = true;
  }
  return by_id_;
}

void World::set_velocity(int i, const Vec2& v, double omega) {
  if (bodies_.motion[i] == Motion::fixed) return;
  bodies_.vel[i] = v;
  bodies_.omega[i] = omega;
  forces_ready_ = false;
  motion_ready_ = false;
}

void World::set_ghost(int i, bool ghost) {
  bodies_.ghost[i] = ghost ? 1 : 0;
  slot_static_[static_cast<std::size_t>(order_.slot_of(i))].ghost = bodies_.ghost[i];
  forces_ready_ = false;
  motion_ready_ = false;
}

void World::set_ghost_pose(int i, const Vec2& position, double yaw) {
  const auto k = static_cast<std::size_t>(i);
  bodies_.pos[k] = position;
  bodies_.yaw[k] = yaw;
  ghost_keys_changed_ = order_.set_key(i, position) || ghost_keys_changed_;
  // (the move's test against the lists' skin left ghosts out)
  if (lists_.built_for(size()) && !lists_.within(k, position, yaw, bodies_.reach[k])) lists_.set_kick_verdict(true);
}

void World::set_ghost_prediction(int i, const Vec2& velocity, double omega) {
  const auto k = static_cast<std::size_t>(i);
  bodies_.vel_eval[k] = velocity;
  bodies_.omega_eval[k] = omega;
  slot_state_[static_cast<std::size_t>(order_.slot_of(i))] = {bodies_.pos[k], velocity, omega};
}

void World::take_pair_forces(std::span<const PairForce> in) { contact_stage_.take_incoming(slot_static_, in); }

void World::set_external_load(int i, const Vec2& force, double torque) {
  bodies_.ext_force[i] = force;
  bodies_.ext_torque[i] = torque;
  forces_ready_ = false;
}

const StepReport& World::step(double dt) {
  using clock = std::chrono::steady_clock;
  if (!forces_ready_) compute_forces(0.0);
  auto t0 = clock::now();
  bool keys_changed = kick_and_move(dt);
  if (exchange_) {
    ghost_keys_changed_ = false;
    exchange_->poses(*this);
    keys_changed = keys_changed || ghost_keys_changed_;
  }
  auto t1 = clock::now();
  sort_slots(keys_changed);
  profile_.integrate += std::chrono::duration<double>(t1 - t0).count();
  profile_.shapes += std::chrono::duration<double>(clock::now() - t1).count();
  evaluate_forces(dt, true);  // the world-frame shapes in its first loop
  auto t3 = clock::now();
  kick_implicit(dt);
  profile_.integrate += std::chrono::duration<double>(clock::now() - t3).count();
  time_ += dt;
  ++steps_;
  ++profile_.steps;
  return report_;
}

void World::compute_forces(double dt) {
  // The slots sorted (and the shapes drawn where they lie) first, as every step's evaluation has them: the order of
  // the contact sums then does not depend on the order the bodies were added in.
  if (exchange_) exchange_->poses(*this);
  update_shapes();
  evaluate_forces(dt, false);
}

void World::evaluate_forces(double dt, bool shapes) {
  using clock = std::chrono::steady_clock;
  // Velocity-dependent forces (damping, friction history, drag) see the velocity predicted at the end of the
  // step from the half-step velocity and the last forces: second-order accurate, where the half-step velocity
  // alone lags by dt/2 (measured at e = 0.2 and 40 steps per contact: restitution error 3 % with the half-step
  // velocity, < 1.8 % with the prediction).
  const std::size_t n = size();
  // Where the last step treated drag and Coriolis semi-implicitly, the prediction is the final kick with the last
  // forces and linear drift model: an explicit prediction overshoots wildly once dt exceeds the drag relaxation
  // time, and the drag coefficients frozen at it would then be meaningless.
  bodies_.vel_eval.resize(n);
  bodies_.omega_eval.resize(n);
  const double half_dt = 0.5 * dt;
  const int n_int = static_cast<int>(n);
  const auto t0 = clock::now();
  // Between full evaluations of the drift loads (DriftSettings::update_every), each body's load comes from the
  // last one's linear model F_d(v) = b - D v (dynamics/drift_model.h) at the
  // velocity predicted here, in the same pass.
  // With `shapes` (a step, after the slots were sorted) the same pass first moves each body's world-frame vertices
  // and box; and it gathers the contact stage's packed state by slot.
  const bool linear = drift_.linear_step(settings_.drift, steps_, dt, n);
  slot_state_.resize(n);
  // The damped inverses for this dt, where none are kept (the drag matrices of the last full evaluation).
  const bool refill = drift_.begin_inverses(n, dt);
  POLYFLOE_OMP_FOR(threads_)
  for (int ii = 0; ii < n_int; ++ii) {
    const auto i = static_cast<std::size_t>(ii);
    if (shapes && bodies_.motion[i] != Motion::fixed) update_shape(ii);
    if (half_dt > 0.0 && drift_.has_linear_model(i) && drift_.load(i).has_damping()) {
      if (refill) drift_.keep_inverse(i, dt, bodies_.mass[i], bodies_.inertia[i]);
      const DriftModel::Velocity v =
          drift_.implicit_velocity(i, dt, drift_.kept_inverse(i), bodies_.mass[i], bodies_.inertia[i], bodies_.vel[i],
                                   bodies_.omega[i], bodies_.force[i], bodies_.torque[i]);
      bodies_.vel_eval[i] = v.u;
      bodies_.omega_eval[i] = v.w;
    } else {
      bodies_.vel_eval[i] = bodies_.vel[i] + (half_dt * bodies_.inv_mass[i]) * bodies_.force[i];
      bodies_.omega_eval[i] = bodies_.omega[i] + half_dt * bodies_.inv_inertia[i] * bodies_.torque[i];
    }
    bodies_.force[i] = bodies_.ext_force[i];
    bodies_.torque[i] = bodies_.ext_torque[i];
    if (linear && bodies_.is_dynamic[i] && drift_.load(i).has_damping()) {
      drift_.set_linear_load(i, bodies_.vel_eval[i], bodies_.omega_eval[i]);
      bodies_.force[i] += drift_.load(i).force;
      bodies_.torque[i] += drift_.load(i).torque;
    }
    slot_state_[static_cast<std::size_t>(order_.slot_of(ii))] = {bodies_.pos[i], bodies_.vel_eval[i],
                                                                 bodies_.omega_eval[i]};
  }
  if (refill) drift_.set_inverses_dt(dt);
  if (exchange_) exchange_->predictions(*this);
  const auto t_pass = clock::now();
  // (a step's profile counts this pass with the shapes; compute_forces from outside, with the drift forces)
  if (shapes) profile_.shapes += std::chrono::duration<double>(t_pass - t0).count();
  // The full evaluation of every body's drift load (the steps between take the linear model's, above).
  if (!linear)
    drift_forcing_.apply(settings_.drift, drift_bodies(), time_ + dt, threads_, drift_, bodies_.force, bodies_.torque);
  const auto t1 = clock::now();
  contact_forces(dt);
  profile_.forcing += std::chrono::duration<double>(t1 - (shapes ? t_pass : t0)).count();
  if (bonds_) bond_forces(time_ + dt);
  // The linear model of the drift load in the body's velocity, F_d(v) = b - D v with b = F_d(v*) + D v*; kept as
  // it is where this step's loads came from it.
  if (linear) {
    forces_ready_ = true;
    return;
  }
  drift_.resize_linear_model(n);
  // With the new drag matrices, their damped inverses for this dt (the final kick's and the next steps').
  POLYFLOE_OMP_FOR(threads_)
  for (int ii = 0; ii < n_int; ++ii) {
    const auto i = static_cast<std::size_t>(ii);
    if (!drift_.load(i).has_damping()) continue;
    drift_.fit_linear_model(i, bodies_.vel_eval[i], bodies_.omega_eval[i]);
    if (half_dt > 0.0) drift_.keep_inverse(i, dt, bodies_.mass[i], bodies_.inertia[i]);
  }
  drift_.set_inverses_dt(half_dt > 0.0 ? dt : 0.0);
  forces_ready_ = true;
}

DriftBodies World::drift_bodies() const {
  return {.id = bodies_.id,
          .dynamic = bodies_.is_dynamic,
          .position = bodies_.pos,
          .velocity = bodies_.vel_eval,
          .omega = bodies_.omega_eval,
          .rotation = rotation_,
          .mass = bodies_.mass,
          .thickness = bodies_.thickness,
          .draft = bodies_.draft,
          .side_area = bodies_.side_area,
          .equivalent_radius = bodies_.equivalent_radius,
          .plan_area = bodies_.plan_area,
          .world_xy = world_xy_,
          .vert_begin = vert_begin_,
          .vert_off = bodies_.vert_off,
          .quad_off = bodies_.quad_off,
          .quad_lx = bodies_.quad_lx,
          .quad_ly = bodies_.quad_ly,
          .quad_weight = bodies_.quad_weight,
          .max_vertices = bodies_.max_vertices,
          .max_quad_points = bodies_.max_quad_points};
}

// The sums over the bodies run in id order: their bits do not depend on where the bodies are stored.
double World::kinetic_energy() const {
  double e = 0.0;
  for (const int i : id_order())
    if (bodies_.is_dynamic[i] && !bodies_.ghost[i])
      e += 0.5 * bodies_.mass[i] * bodies_.vel[i].squaredNorm() +
           0.5 * bodies_.inertia[i] * bodies_.omega[i] * bodies_.omega[i];
  return e;
}

Vec2 World::linear_momentum() const {
  Vec2 p{0.0, 0.0};
  for (const int i : id_order())
    if (bodies_.is_dynamic[i] && !bodies_.ghost[i]) p += bodies_.mass[i] * bodies_.vel[i];
  return p;
}

double World::angular_momentum() const {
  double l = 0.0;
  for (const int i : id_order())
    if (bodies_.is_dynamic[i] && !bodies_.ghost[i])
      l += bodies_.mass[i] * geometry::cross(bodies_.pos[i], bodies_.vel[i]) + bodies_.inertia[i] * bodies_.omega[i];
  return l;
}

double World::max_speed() const {
  double v = 0.0;
  for (std::size_t i = 0; i < size(); ++i)
    if (bodies_.is_dynamic[i] && !bodies_.ghost[i]) v = std::max(v, bodies_.vel[i].norm());
  return v;
}

double World::shortest_hertz_contact_duration(double speed) const {
  double m_min = contact::kInfinite, r_min = contact::kInfinite;
  for (std::size_t i = 0; i < size(); ++i) {
    if (!bodies_.is_dynamic[i]) continue;
    m_min = std::min(m_min, bodies_.mass[i]);
    r_min = std::min(r_min, bodies_.radius[i]);
  }
  if (std::isinf(m_min)) return contact::kInfinite;
  // Two of the lightest, smallest floes meeting: m* = m/2, R* = R/2.
  const double k_n = 4.0 / 3.0 * law_.effective_modulus() * std::sqrt(0.5 * r_min);
  return contact::hertz_contact_duration(k_n, 0.5 * m_min, speed);
}

double World::shortest_flat_contact_duration() const {
  if (law_.settings().force_model != contact::ForceModel::foundation) return contact::kInfinite;
  // A flat face pressed on a face is a linear spring 2 kappa L (contact/foundation.h): half a period
  // pi sqrt(m* / (2 kappa L)) at any speed. The shortest: a floe's longest edge against an equal floe's, m* = m/2.
  double t = contact::kInfinite;
  for (std::size_t i = 0; i < size(); ++i) {
    if (!bodies_.is_dynamic[i]) continue;
    const auto& v = bodies_.shape[i]->vertices();
    double longest = 0.0;
    for (std::size_t k = 0; k < v.size(); ++k) longest = std::max(longest, (v[(k + 1) % v.size()] - v[k]).norm());
    t = std::min(t, std::numbers::pi * std::sqrt(0.5 * bodies_.mass[i] / (2.0 * law_.foundation_modulus() * longest)));
  }
  return t;
}

double World::shortest_contact_duration(double speed) const {
  return std::min(shortest_hertz_contact_duration(speed), shortest_flat_contact_duration());
}

WorldState World::state() const {
  WorldState s;
  copy_members_out(s, [this](auto&& f) { state_members(*this, f); });
  s.ids = bodies_.id;
  s.drift_load = drift_.loads();
  s.lin_force = drift_.linear_force();
  s.lin_torque = drift_.linear_torque();
  s.contact_history = cache_.entries();
  if (bonds_) s.bonds = bonds_->state();
  gather_body_rows(s, id_order());
  return s;
}

void World::restore(const WorldState& state) {
  const std::size_t n = size();
  auto bad = [](const std::string& what) { throw std::invalid_argument("world state: " + what); };
  if (state.ids.size() != n)
    bad("it has " + std::to_string(state.ids.size()) + " bodies, this world has " + std::to_string(n));
  // every per-body array a row per body (the drift model's may be empty)
  if (const std::string problem = body_row_problem(state, false); !problem.empty()) bad(problem);
  // Its rows in the order this World stores its bodies: the row of body i's id.
  std::vector<int> from(n, -1);
  for (std::size_t k = 0; k < n; ++k) {
    const int i = bodies_.index_of(state.ids[k]);
    if (i < 0) bad("it has a body of id " + std::to_string(state.ids[k]) + ", this world has none");
    if (from[static_cast<std::size_t>(i)] >= 0)
      bad("it lists the body of id " + std::to_string(state.ids[k]) + " twice");
    from[static_cast<std::size_t>(i)] = static_cast<int>(k);
  }
  WorldState s = state;
  gather_body_rows(s, from);
  if (s.lin_force.size() != s.lin_torque.size() || (!s.lin_force.empty() && s.drift_load.size() != n))
    bad("the linear drift model does not match the drift loads");
  if (s.bonds.has_value() != bonds_.has_value())
    bad(s.bonds ? "it has bonds, this world has none" : "it has no bonds, this world has");
  if (!std::isfinite(s.time) || s.time < 0.0) bad("time must be finite and >= 0");
  for (std::size_t i = 0; i < n; ++i) {
    if (!s.position[i].allFinite() || !s.velocity[i].allFinite() || !std::isfinite(s.yaw[i]) ||
        !std::isfinite(s.omega[i]))
      bad("body " + std::to_string(bodies_.id[i]) + " has a non-finite pose or velocity");
    if (bodies_.motion[i] == Motion::fixed && (s.position[i] != bodies_.pos[i] || s.yaw[i] != bodies_.yaw[i]))
      bad("fixed body " + std::to_string(bodies_.id[i]) + " is not where the scene puts it");
  }
  if (bonds_) bonds_->restore(*s.bonds);  // first: it may throw, leaving this World unchanged
  copy_members_in(s, [this](auto&& f) { state_members(*this, f); });
  drift_.restore(s.drift_load, s.lin_force, s.lin_torque);
  cache_.restore(s.contact_history);
  contacts_.clear();
  contacts_ready_ = true;
  contact_count_ = 0;
  report_ = StepReport{};
  update_shapes();
  lists_.forget_kick_verdict();  // the poses changed since any kick tested them
  motion_ready_ = false;
}

SlotView World::slot_view() const {
  return {order_.slots(), order_.body_slots(), slot_static_, boxes_,       slot_dynamic_,
          world_xy_,      bodies_.pos,         bodies_.yaw,  bodies_.reach};
}

// The contact stage (dynamics/contact_stage.h) on the slots: everything there works on slots (bodies sorted by
// position), so the pairs, the bodies' hot state and the force sums are read and written in memory order close to
// the order of space. slot_state_: gathered by evaluate_forces' first pass.
void World::contact_forces(double dt) {
  using clock = std::chrono::steady_clock;
  const auto t0 = clock::now();
  contact_stage_.find_pairs(slot_view(), law_, settings_.narrow_phase, threads_, lists_);
  const auto t1 = clock::now();
  const PlanarContactInput in{.statics = slot_static_,
                              .states = slot_state_,
                              .world_xy = world_xy_,
                              .edge_nx = edge_nx_,
                              .edge_ny = edge_ny_,
                              .edge_offset = edge_offset_,
                              .inv_mass = bodies_.inv_mass,
                              .inv_inertia = bodies_.inv_inertia,
                              .bonds = bonds_ ? &*bonds_ : nullptr,
                              .narrow_phase = settings_.narrow_phase,
                              .dt = dt,
                              .overlap_limit = kOverlapLimit,
                              .threads = threads_};
  contact_stage_.evaluate(in, law_, lists_, cache_);
  if (exchange_) {
    outgoing_.clear();
    contact_stage_.outgoing(slot_static_, outgoing_);
    exchange_->pair_forces(*this);
  }
  const ContactSum::Totals& t = contact_stage_.sum(in, lists_, cache_);
  // Into the bodies' sums, in body order: each thread writes its own stretch of the bodies' forces and torques
  // (written by slot, neighbouring bodies of different blocks would share cache lines).
  const int n = static_cast<int>(size());
  POLYFLOE_OMP_FOR(threads_)
  for (int i = 0; i < n; ++i) {
    const int k = order_.slot_of(i);
    bodies_.force[i] += contact_stage_.slot_force(k);
    bodies_.torque[i] += contact_stage_.slot_torque(k);
  }
  contacts_ready_ = false;  // the records are listed from the stage when asked for (contacts())
  contact_count_ = t.hits;
  narrow_phase_failures_ += t.failures;
  report_.deepest = t.deepest;
  report_.shortest = t.shortest;
  profile_.reused += t.reused;
  profile_.broad += std::chrono::duration<double>(t1 - t0).count();
  profile_.candidates += contact_stage_.candidates();
  profile_.contacts += contact_count_;
  profile_.narrow_and_law += std::chrono::duration<double>(clock::now() - t1).count();
}

void World::show_contacts(std::vector<ContactRecord> records) {
  auto key = [this](const ContactRecord& r) { return std::make_pair(bodies_.id[r.a], bodies_.id[r.b]); };
  std::sort(records.begin(), records.end(),
            [&](const ContactRecord& x, const ContactRecord& y) { return key(x) < key(y); });
  contacts_ = std::move(records);
  contacts_ready_ = true;
  contact_count_ = contacts_.size();
}

const std::vector<ContactRecord>& World::contacts() const {
  if (!contacts_ready_) {
    contact_stage_.list_contacts(slot_static_, contacts_);
    contacts_ready_ = true;
  }
  return contacts_;
}

}  // namespace polyfloe::dynamics
