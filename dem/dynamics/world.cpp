#include "dynamics/world.h"
#include "geometry/space_order.h"

#include "dynamics/parallel.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <stdexcept>
#include <numbers>
#include <string>

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
  if (!d.shape) throw std::invalid_argument("body " + std::to_string(d.id) + " has no shape");
  if (index_.count(d.id)) throw std::invalid_argument("duplicate body id " + std::to_string(d.id));
  if (d.shape->size() > contact::kMaxPolygonVertices)
    throw std::invalid_argument("body " + std::to_string(d.id) + " has " + std::to_string(d.shape->size()) +
                                " vertices; at most " + std::to_string(contact::kMaxPolygonVertices) + " are allowed");
  if (!(d.thickness > 0.0) || !std::isfinite(d.thickness))
    throw std::invalid_argument("body " + std::to_string(d.id) + ": thickness must be positive");
  if (!(d.density > 0.0) || !std::isfinite(d.density))
    throw std::invalid_argument("body " + std::to_string(d.id) + ": density must be positive");
  const int i = static_cast<int>(id_.size());
  const geometry::PrismMass pm = geometry::prism_mass(*d.shape, d.thickness, d.density);
  const bool dyn = d.motion == Motion::dynamic;
  id_.push_back(d.id);
  index_[d.id] = i;
  shape_.push_back(d.shape);
  thickness_.push_back(d.thickness);
  mass_.push_back(pm.mass);
  inertia_.push_back(pm.inertia_z);
  plan_area_.push_back(d.shape->area());
  // Floating at equilibrium; a body denser than water rests fully submerged (draft = thickness).
  const double rho_w = settings_.drift.water_density;
  const double draft = std::min(d.thickness, geometry::floating_draft(d.thickness, d.density, rho_w));
  draft_.push_back(draft);
  side_area_.push_back(d.shape->perimeter() * draft);
  equivalent_radius_.push_back(d.shape->equivalent_radius());
  {
    std::vector<forcing::QuadraturePoint> q;
    forcing::polygon_quadrature(d.shape->vertices(), settings_.drift.quadrature, q);
    for (const forcing::QuadraturePoint& p : q) {
      quad_lx_.push_back(p.point.x());
      quad_ly_.push_back(p.point.y());
      quad_weight_.push_back(p.weight);
    }
    quad_off_.push_back(quad_off_.back() + static_cast<int>(q.size()));
    max_quad_points_ = std::max(max_quad_points_, q.size());
    max_vertices_ = std::max(max_vertices_, static_cast<std::size_t>(d.shape->size()));
  }
  // Walls and plates are flat and immovable for the contact law: infinite radius and mass.
  radius_.push_back(dyn ? d.shape->equivalent_radius() : contact::kInfinite);
  motion_.push_back(d.motion);
  is_dynamic_.push_back(dyn ? 1 : 0);
  if (dyn) dynamic_mass_ += mass_.back();
  drift_.forget_inverses();
  motion_ready_ = false;
  pos_.push_back(d.position);
  yaw_.push_back(d.yaw);
  vel_.push_back(d.motion == Motion::fixed ? Vec2{0.0, 0.0} : d.velocity);
  omega_.push_back(d.motion == Motion::fixed ? 0.0 : d.angular_velocity);
  force_.emplace_back(0.0, 0.0);
  torque_.push_back(0.0);
  ext_force_.push_back(d.external_force);
  ext_torque_.push_back(d.external_torque);
  inv_mass_.push_back(dyn ? 1.0 / pm.mass : 0.0);
  inv_inertia_.push_back(dyn ? 1.0 / pm.inertia_z : 0.0);
  vert_off_.push_back(vert_off_.back() + d.shape->size());
  vert_begin_.push_back(vert_off_[i]);
  world_xy_.resize(static_cast<std::size_t>(vert_off_.back()));
  local_xy_.insert(local_xy_.end(), d.shape->vertices().begin(), d.shape->vertices().end());
  rotation_.emplace_back(1.0, 0.0);
  // A new body takes the last slot (its vertices go at the end of world_xy_); the next step sorts the slots.
  if (dyn) {
    radius_sum_ += d.shape->equivalent_radius();
    ++dynamic_count_;
    order_.set_cell(geometry::space_order_cell(radius_sum_ / dynamic_count_));
  }
  lists_.set_skin(settings_.broad_phase_skin > 0.0 ? settings_.broad_phase_skin
                  : dynamic_count_ > 0             ? 0.2 * radius_sum_ / dynamic_count_
                                                   : 1.0);
  reach_.push_back(d.shape->circumradius());
  lists_.invalidate();  // rebuilt at the next evaluation
  order_.add(i);
  slot_static_.push_back(slot_static_of(i, vert_begin_[i]));
  slot_dynamic_.push_back(is_dynamic_[i]);
  boxes_.emplace_back();
  update_shape(i);
  forces_ready_ = false;
  return i;
}

SlotStatic World::slot_static_of(int i, int vert_begin) const {
  return {is_dynamic_[i] ? mass_[i] : contact::kInfinite,
          radius_[i],
          equivalent_radius_[i],
          id_[i],
          i,
          vert_begin,
          vert_off_[i + 1] - vert_off_[i]};
}

int World::index_of(BodyId id) const {
  const auto it = index_.find(id);
  return it == index_.end() ? -1 : it->second;
}

void World::set_velocity(int i, const Vec2& v, double omega) {
  if (motion_[i] == Motion::fixed) return;
  vel_[i] = v;
  omega_[i] = omega;
  forces_ready_ = false;
  motion_ready_ = false;
}

void World::set_external_load(int i, const Vec2& force, double torque) {
  ext_force_[i] = force;
  ext_torque_[i] = torque;
  forces_ready_ = false;
}

const StepReport& World::step(double dt) {
  using clock = std::chrono::steady_clock;
  if (!forces_ready_) compute_forces(0.0);
  auto t0 = clock::now();
  const bool keys_changed = kick_and_move(dt);
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

void World::compute_forces(double dt) { evaluate_forces(dt, false); }

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
  vel_eval_.resize(n);
  omega_eval_.resize(n);
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
    if (shapes && motion_[i] != Motion::fixed) update_shape(ii);
    if (half_dt > 0.0 && drift_.has_linear_model(i) && drift_.load(i).has_damping()) {
      if (refill) drift_.keep_inverse(i, dt, mass_[i], inertia_[i]);
      const DriftModel::Velocity v = drift_.implicit_velocity(i, dt, drift_.kept_inverse(i), mass_[i], inertia_[i],
                                                              vel_[i], omega_[i], force_[i], torque_[i]);
      vel_eval_[i] = v.u;
      omega_eval_[i] = v.w;
    } else {
      vel_eval_[i] = vel_[i] + (half_dt * inv_mass_[i]) * force_[i];
      omega_eval_[i] = omega_[i] + half_dt * inv_inertia_[i] * torque_[i];
    }
    force_[i] = ext_force_[i];
    torque_[i] = ext_torque_[i];
    if (linear && is_dynamic_[i] && drift_.load(i).has_damping()) {
      drift_.set_linear_load(i, vel_eval_[i], omega_eval_[i]);
      force_[i] += drift_.load(i).force;
      torque_[i] += drift_.load(i).torque;
    }
    slot_state_[static_cast<std::size_t>(order_.slot_of(ii))] = {pos_[i], vel_eval_[i], omega_eval_[i]};
  }
  if (refill) drift_.set_inverses_dt(dt);
  const auto t_pass = clock::now();
  // (a step's profile counts this pass with the shapes; compute_forces from outside, with the drift forces)
  if (shapes) profile_.shapes += std::chrono::duration<double>(t_pass - t0).count();
  // The full evaluation of every body's drift load (the steps between take the linear model's, above).
  if (!linear) drift_forcing_.apply(settings_.drift, drift_bodies(), time_ + dt, threads_, drift_, force_, torque_);
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
    drift_.fit_linear_model(i, vel_eval_[i], omega_eval_[i]);
    if (half_dt > 0.0) drift_.keep_inverse(i, dt, mass_[i], inertia_[i]);
  }
  drift_.set_inverses_dt(half_dt > 0.0 ? dt : 0.0);
  forces_ready_ = true;
}

DriftBodies World::drift_bodies() const {
  return {.id = id_,
          .dynamic = is_dynamic_,
          .position = pos_,
          .velocity = vel_eval_,
          .omega = omega_eval_,
          .rotation = rotation_,
          .mass = mass_,
          .thickness = thickness_,
          .draft = draft_,
          .side_area = side_area_,
          .equivalent_radius = equivalent_radius_,
          .plan_area = plan_area_,
          .world_xy = world_xy_,
          .vert_begin = vert_begin_,
          .vert_off = vert_off_,
          .quad_off = quad_off_,
          .quad_lx = quad_lx_,
          .quad_ly = quad_ly_,
          .quad_weight = quad_weight_,
          .max_vertices = max_vertices_,
          .max_quad_points = max_quad_points_};
}

double World::kinetic_energy() const {
  double e = 0.0;
  for (std::size_t i = 0; i < size(); ++i)
    if (is_dynamic_[i]) e += 0.5 * mass_[i] * vel_[i].squaredNorm() + 0.5 * inertia_[i] * omega_[i] * omega_[i];
  return e;
}

Vec2 World::linear_momentum() const {
  Vec2 p{0.0, 0.0};
  for (std::size_t i = 0; i < size(); ++i)
    if (is_dynamic_[i]) p += mass_[i] * vel_[i];
  return p;
}

double World::angular_momentum() const {
  double l = 0.0;
  for (std::size_t i = 0; i < size(); ++i)
    if (is_dynamic_[i]) l += mass_[i] * geometry::cross(pos_[i], vel_[i]) + inertia_[i] * omega_[i];
  return l;
}

double World::max_speed() const {
  double v = 0.0;
  for (std::size_t i = 0; i < size(); ++i)
    if (is_dynamic_[i]) v = std::max(v, vel_[i].norm());
  return v;
}

double World::shortest_hertz_contact_duration(double speed) const {
  double m_min = contact::kInfinite, r_min = contact::kInfinite;
  for (std::size_t i = 0; i < size(); ++i) {
    if (!is_dynamic_[i]) continue;
    m_min = std::min(m_min, mass_[i]);
    r_min = std::min(r_min, radius_[i]);
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
    if (!is_dynamic_[i]) continue;
    const auto& v = shape_[i]->vertices();
    double longest = 0.0;
    for (std::size_t k = 0; k < v.size(); ++k) longest = std::max(longest, (v[(k + 1) % v.size()] - v[k]).norm());
    t = std::min(t, std::numbers::pi * std::sqrt(0.5 * mass_[i] / (2.0 * law_.foundation_modulus() * longest)));
  }
  return t;
}

double World::shortest_contact_duration(double speed) const {
  return std::min(shortest_hertz_contact_duration(speed), shortest_flat_contact_duration());
}

WorldState World::state() const {
  WorldState s;
  copy_members_out(s, [this](auto&& f) { state_members(*this, f); });
  s.ids = id_;
  s.drift_load = drift_.loads();
  s.lin_force = drift_.linear_force();
  s.lin_torque = drift_.linear_torque();
  s.contact_history = cache_.entries();
  if (bonds_) s.bonds = bonds_->state();
  return s;
}

void World::restore(const WorldState& s) {
  const std::size_t n = size();
  auto bad = [](const std::string& what) { throw std::invalid_argument("world state: " + what); };
  if (s.ids.size() != n) bad("it has " + std::to_string(s.ids.size()) + " bodies, this world has " + std::to_string(n));
  for (std::size_t i = 0; i < n; ++i)
    if (s.ids[i] != id_[i])
      bad("body " + std::to_string(i) + " has id " + std::to_string(s.ids[i]) + ", this world's has id " +
          std::to_string(id_[i]));
  // every per-body array a row per body (the drift model's may be empty)
  if (const std::string problem = body_row_problem(s, false); !problem.empty()) bad(problem);
  if (s.lin_force.size() != s.lin_torque.size() || (!s.lin_force.empty() && s.drift_load.size() != n))
    bad("the linear drift model does not match the drift loads");
  if (s.bonds.has_value() != bonds_.has_value())
    bad(s.bonds ? "it has bonds, this world has none" : "it has no bonds, this world has");
  if (!std::isfinite(s.time) || s.time < 0.0) bad("time must be finite and >= 0");
  for (std::size_t i = 0; i < n; ++i) {
    if (!s.position[i].allFinite() || !s.velocity[i].allFinite() || !std::isfinite(s.yaw[i]) ||
        !std::isfinite(s.omega[i]))
      bad("body " + std::to_string(id_[i]) + " has a non-finite pose or velocity");
    if (motion_[i] == Motion::fixed && (s.position[i] != pos_[i] || s.yaw[i] != yaw_[i]))
      bad("fixed body " + std::to_string(id_[i]) + " is not where the scene puts it");
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

}  // namespace polyfloe::dynamics
