#include "dynamics/spatial_world.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <stdexcept>
#include <string>

#include <Eigen/Eigenvalues>

#include "dynamics/parallel.h"

namespace polyfloe::dynamics {

namespace {

// Rotation by the rotation vector w dt (exact exponential map).
Quat exp_map(const Vec3& w, double dt) {
  const double angle = w.norm() * dt;
  if (angle < 1e-300) return Quat::Identity();
  return Quat(Eigen::AngleAxisd(angle, w / w.norm()));
}

bool finite(const Vec3& v) { return v.allFinite(); }

}  // namespace

const char* to_string(SpatialNarrowPhase m) {
  switch (m) {
    case SpatialNarrowPhase::sat: return "sat";
    case SpatialNarrowPhase::gjk_epa_tiebreak: return "gjk_epa_tiebreak";
    case SpatialNarrowPhase::gjk_epa: return "gjk_epa";
    case SpatialNarrowPhase::mpr: return "mpr";
  }
  return "?";
}

SpatialWorld::SpatialWorld(const SpatialSettings& settings) : settings_(settings), law_(settings.contact) {}

int SpatialWorld::add_body(const SpatialBodyDesc& d) {
  if (!d.shape) throw std::invalid_argument("spatial body " + std::to_string(d.id) + ": no shape");
  if (index_.count(d.id)) throw std::invalid_argument("spatial body id " + std::to_string(d.id) + " is used twice");
  if (!(d.density > 0.0) || !std::isfinite(d.density)) {
    throw std::invalid_argument("spatial body " + std::to_string(d.id) + ": density must be finite and > 0 kg/m^3");
  }
  if (!finite(d.position) || !finite(d.velocity) || !finite(d.angular_velocity) ||
      !d.orientation.coeffs().allFinite() || !(d.orientation.norm() > 0.0)) {
    throw std::invalid_argument("spatial body " + std::to_string(d.id) +
                                ": non-finite position, orientation or velocity");
  }
  const int i = static_cast<int>(id_.size());
  id_.push_back(d.id);
  index_[d.id] = i;
  shape_.push_back(d.shape);
  motion_.push_back(d.motion);
  const bool dynamic = d.motion == Motion::dynamic;
  is_dynamic_.push_back(dynamic ? 1 : 0);
  const double m = d.density * d.shape->volume();
  mass_.push_back(m);
  radius_.push_back(d.shape->equivalent_radius());
  const Mat3 inertia = d.density * d.shape->unit_inertia();
  inertia_body_.push_back(inertia);
  inv_inertia_body_.push_back(inertia.inverse());
  inv_mass_.push_back(dynamic ? 1.0 / m : 0.0);
  pos_.push_back(d.position);
  const Quat q = d.orientation.normalized();
  q_.push_back(q);
  vel_.push_back(d.motion == Motion::fixed ? Vec3::Zero() : d.velocity);
  const Mat3 r = q.toRotationMatrix();
  ang_mom_.push_back(dynamic ? Vec3(r * inertia * r.transpose() * d.angular_velocity) : Vec3::Zero());
  omega_kinematic_.push_back(d.motion == Motion::kinematic ? d.angular_velocity : Vec3::Zero());
  force_.push_back(Vec3::Zero());
  torque_.push_back(Vec3::Zero());
  vert_off_.push_back(vert_off_.back() + static_cast<int>(d.shape->vertices().size()));
  world_.resize(vert_off_.back());
  boxes_.emplace_back();
  z_lo_.push_back(0.0);
  z_hi_.push_back(0.0);
  update_world_vertices(i);
  forces_ready_ = false;
  motion_ready_ = false;
  return i;
}

Vec3 SpatialWorld::angular_velocity(int i) const {
  if (motion_[i] == Motion::kinematic) return omega_kinematic_[i];
  if (!is_dynamic_[i]) return Vec3::Zero();
  return world_inverse_inertia(i) * ang_mom_[i];
}

Mat3 SpatialWorld::world_inverse_inertia(int i) const {
  const Mat3 r = q_[i].toRotationMatrix();
  return r * inv_inertia_body_[i] * r.transpose();
}

void SpatialWorld::update_world_vertices(int i) {
  const Mat3 r = q_[i].toRotationMatrix();
  const auto& body = shape_[i]->vertices();
  Vec3 lo = Vec3::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
  for (std::size_t k = 0; k < body.size(); ++k) {
    const Vec3 w = r * body[k] + pos_[i];
    world_[vert_off_[i] + k] = w;
    lo = lo.cwiseMin(w);
    hi = hi.cwiseMax(w);
  }
  boxes_[i].lo = {lo.x(), lo.y()};
  boxes_[i].hi = {hi.x(), hi.y()};
  z_lo_[i] = lo.z();
  z_hi_[i] = hi.z();
}

void SpatialWorld::kick(double half_dt) {
  polyfloe_parallel_for(static_cast<std::ptrdiff_t>(size()), threads_for(size(), 3.0), [&](std::ptrdiff_t k) {
    const auto i = static_cast<std::size_t>(k);
    if (!is_dynamic_[i]) return;
    vel_[i] += half_dt * inv_mass_[i] * force_[i];
    ang_mom_[i] += half_dt * torque_[i];
  });
}

void SpatialWorld::drift(double dt) {
  polyfloe_parallel_for(static_cast<std::ptrdiff_t>(size()), threads_for(size(), 250.0), [&](std::ptrdiff_t k) {
    const auto i = static_cast<std::size_t>(k);
    if (motion_[i] == Motion::fixed) return;
    pos_[i] += dt * vel_[i];
    if (motion_[i] == Motion::kinematic) {
      q_[i] = (exp_map(omega_kinematic_[i], dt) * q_[i]).normalized();
    } else {
      // Implicit midpoint in the orientation: w at the half-step orientation reached by that same w.
      const Quat q0 = q_[i];
      Vec3 w = world_inverse_inertia(static_cast<int>(i)) * ang_mom_[i];
      for (int it = 0; it < 4; ++it) {
        const Mat3 rm = (exp_map(w, 0.5 * dt) * q0).toRotationMatrix();
        const Vec3 wn = rm * inv_inertia_body_[i] * rm.transpose() * ang_mom_[i];
        const bool done = (wn - w).squaredNorm() <= 1e-28 * wn.squaredNorm();
        w = wn;
        if (done) break;
      }
      q_[i] = (exp_map(w, dt) * q0).normalized();
    }
    update_world_vertices(static_cast<int>(i));
  });
}

const StepReport& SpatialWorld::step(double dt) {
  using clock = std::chrono::steady_clock;
  if (!forces_ready_) compute_forces(dt);
  const auto t0 = clock::now();
  kick(0.5 * dt);
  drift(dt);
  time_ += dt;
  ++steps_;
  profile_.integrate += std::chrono::duration<double>(clock::now() - t0).count();
  compute_forces(dt);
  const auto t1 = clock::now();
  kick(0.5 * dt);
  profile_.integrate += std::chrono::duration<double>(clock::now() - t1).count();
  ++profile_.steps;
  motion_ready_ = false;
  return report();
}

const StepReport& SpatialWorld::report() const {
  if (motion_ready_) return report_;
  MotionSummary& m = report_.motion;
  m = MotionSummary{};
  for (std::size_t i = 0; i < size(); ++i) {
    const Vec3 w = angular_velocity(static_cast<int>(i));
    m.all_finite &= pos_[i].allFinite() && q_[i].coeffs().allFinite() && vel_[i].allFinite() && w.allFinite();
    if (!is_dynamic_[i]) continue;
    const double v2 = vel_[i].squaredNorm();
    m.max_speed2 = std::max(m.max_speed2, v2);
    m.max_spin_speed = std::max(m.max_spin_speed, w.norm() * shape_[i]->circumradius());
    m.energy += 0.5 * mass_[i] * v2 + 0.5 * w.dot(ang_mom_[i]);
  }
  motion_ready_ = true;
  return report_;
}

void SpatialWorld::body_loads() {
  polyfloe_parallel_for(static_cast<std::ptrdiff_t>(size()), threads_for(size(), settings_.buoyancy ? 200.0 : 3.0),
                        [&](std::ptrdiff_t k) {
                          const auto i = static_cast<std::size_t>(k);
                          force_[i].setZero();
                          torque_[i].setZero();
                          if (!is_dynamic_[i]) return;
                          force_[i] += mass_[i] * settings_.gravity;
                          if (settings_.buoyancy) {
                            const auto sub = geometry::submerged_part(*shape_[i], world_vertices(static_cast<int>(i)),
                                                                      settings_.water_level);
                            if (sub.volume > 0.0) {
                              const Vec3 fb = -settings_.water_density * sub.volume * settings_.gravity;
                              force_[i] += fb;
                              torque_[i] += (sub.centroid - pos_[i]).cross(fb);
                            }
                          }
                        });
}

std::span<const int> SpatialWorld::id_order() const {
  if (by_id_.size() != id_.size()) sort_by_id(id_, by_id_);  // bodies are only ever added
  return by_id_;
}

SpatialWorldState SpatialWorld::state() const {
  SpatialWorldState s;
  copy_members_out(s, [this](auto&& f) { state_members(*this, f); });
  s.ids = id_;
  s.contact_history = springs_.entries();
  return s;
}

void SpatialWorld::restore(const SpatialWorldState& s) {
  const std::size_t n = size();
  auto bad = [](const std::string& what) { throw std::invalid_argument("spatial world state: " + what); };
  if (s.ids != id_) bad("its bodies (ids, order) are not this world's");
  if (const std::string problem = body_row_problem(s, true); !problem.empty()) bad(problem);
  if (!std::isfinite(s.time) || s.time < 0.0) bad("time must be finite and >= 0");
  for (std::size_t i = 0; i < n; ++i) {
    if (std::abs(s.orientation[i].norm() - 1.0) > 1e-9)
      bad("the orientation of body " + std::to_string(id_[i]) + " is not a unit quaternion");
    if (motion_[i] == Motion::fixed && (s.position[i] != pos_[i] || s.orientation[i].coeffs() != q_[i].coeffs()))
      bad("fixed body " + std::to_string(id_[i]) + " is not where the scene puts it");
    if (!is_dynamic_[i] && (s.velocity[i] != vel_[i] || s.angular_momentum[i] != ang_mom_[i]))
      bad(std::string(to_string(motion_[i])) + " body " + std::to_string(id_[i]) +
          " does not move as the scene prescribes");
  }
  for (const auto& [key, spring] : s.contact_history)
    if (!(key.lo < key.hi) || !index_.count(key.lo) || !index_.count(key.hi) || !spring.allFinite())
      bad("the contact history holds a spring of bodies " + std::to_string(key.lo) + " and " + std::to_string(key.hi) +
          " that is not a finite spring of a pair of this world");
  copy_members_in(s, [this](auto&& f) { state_members(*this, f); });
  springs_.restore(s.contact_history);
  contacts_.clear();
  report_ = StepReport{};
  motion_ready_ = false;
  for (std::size_t i = 0; i < n; ++i) update_world_vertices(static_cast<int>(i));
}

double SpatialWorld::kinetic_energy() const {
  double e = 0.0;
  for (std::size_t i = 0; i < size(); ++i) {
    if (!is_dynamic_[i]) continue;
    e += 0.5 * mass_[i] * vel_[i].squaredNorm() + 0.5 * angular_velocity(static_cast<int>(i)).dot(ang_mom_[i]);
  }
  return e;
}

double SpatialWorld::contact_energy() const {
  double e = 0.0;
  for (const auto& c : contacts_) e += c.stored_energy;
  return e;
}

Vec3 SpatialWorld::linear_momentum() const {
  Vec3 p = Vec3::Zero();
  for (std::size_t i = 0; i < size(); ++i) {
    if (is_dynamic_[i]) p += mass_[i] * vel_[i];
  }
  return p;
}

Vec3 SpatialWorld::angular_momentum() const {
  Vec3 l = Vec3::Zero();
  for (std::size_t i = 0; i < size(); ++i) {
    if (is_dynamic_[i]) l += pos_[i].cross(mass_[i] * vel_[i]) + ang_mom_[i];
  }
  return l;
}

double SpatialWorld::shortest_contact_duration(double speed) const {
  double t = contact::kInfinite;
  const double e_star = law_.effective_modulus();
  for (std::size_t i = 0; i < size(); ++i) {
    if (!is_dynamic_[i]) continue;
    // The least effective mass of an impact on this body: 1 / (1/m + |r x n|^2 / I) with |r x n| at most the
    // circumradius and I at least the smallest principal moment.
    const double i_min =
        Eigen::SelfAdjointEigenSolver<Mat3>(inertia_body_[i], Eigen::EigenvaluesOnly).eigenvalues().minCoeff();
    const double rc = shape_[i]->circumradius();
    const double m = 1.0 / (1.0 / mass_[i] + rc * rc / i_min);
    // like against like (m* = m/2, R* = r/2) and against a fixed flat body (m* = m, R* = r); a face on a face has
    // up to kMaxManifoldPoints Hertz points at one depth: that many times the stiffness
    const double points = settings_.contact_point == ContactPointModel::manifold ? contact::kMaxManifoldPoints : 1;
    for (const auto& [mm, r] : {std::pair{0.5 * m, 0.5 * radius_[i]}, std::pair{m, radius_[i]}}) {
      t = std::min(t, contact::hertz_contact_duration(points * 4.0 / 3.0 * e_star * std::sqrt(r), mm, speed));
    }
  }
  return t;
}

}  // namespace polyfloe::dynamics
