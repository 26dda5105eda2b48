#include "dynamics/spatial_world.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include <Eigen/Eigenvalues>

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
  for (std::size_t i = 0; i < size(); ++i) {
    if (!is_dynamic_[i]) continue;
    vel_[i] += half_dt * inv_mass_[i] * force_[i];
    ang_mom_[i] += half_dt * torque_[i];
  }
}

void SpatialWorld::drift(double dt) {
  for (std::size_t i = 0; i < size(); ++i) {
    if (motion_[i] == Motion::fixed) continue;
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
  }
}

void SpatialWorld::step(double dt) {
  if (!forces_ready_) compute_forces(dt);
  kick(0.5 * dt);
  drift(dt);
  time_ += dt;
  ++steps_;
  compute_forces(dt);
  kick(0.5 * dt);
}

void SpatialWorld::body_loads() {
  const std::size_t n = size();
  for (std::size_t i = 0; i < n; ++i) {
    force_[i].setZero();
    torque_[i].setZero();
    if (!is_dynamic_[i]) continue;
    force_[i] += mass_[i] * settings_.gravity;
    if (settings_.buoyancy) {
      const auto sub = geometry::submerged_part(*shape_[i], world_vertices(static_cast<int>(i)), settings_.water_level);
      if (sub.volume > 0.0) {
        const Vec3 fb = -settings_.water_density * sub.volume * settings_.gravity;
        force_[i] += fb;
        torque_[i] += (sub.centroid - pos_[i]).cross(fb);
      }
    }
  }
}

// The narrow phase of bodies a and b (rotations rot_a, rot_b): sat, or libccd with its answer checked and sat
// behind it.
contact::SatContact SpatialWorld::measure(int a, int b, const Mat3& rot_a, const Mat3& rot_b) {
  auto exact = [&] {
    return contact::sat_penetration(*shape_[a], rot_a, world_vertices(a), pos_[a], *shape_[b], rot_b, world_vertices(b),
                                    pos_[b]);
  };
  if (settings_.narrow_phase == SpatialNarrowPhase::sat) return exact();
  const auto method = settings_.narrow_phase == SpatialNarrowPhase::mpr       ? contact::CcdMethod::mpr
                      : settings_.narrow_phase == SpatialNarrowPhase::gjk_epa ? contact::CcdMethod::gjk_epa
                                                                              : contact::CcdMethod::gjk_epa_tiebreak;
  const auto r = contact::ccd_penetration(world_vertices(a), world_vertices(b), method, settings_.ccd);
  if (r.status == contact::CcdStatus::failed) {
    ++stats_.primary_failures;
    return exact();
  }
  if (r.status == contact::CcdStatus::separated) {
    // libccd's GJK can call an overlapping pair separated (3 in 120,000 random level-floe pairs: the failure
    // map), which no check of its answer can see: every separation is confirmed exactly, a miss counted.
    const contact::SatContact c = exact();
    if (c.hit) ++stats_.primary_failures;
    return c;
  }
  if (r.depth >
      contact::least_face_overlap(*shape_[a], rot_a, world_vertices(a), *shape_[b], rot_b, world_vertices(b)) +
          1e-9 * (shape_[a]->circumradius() + shape_[b]->circumradius())) {
    // Deeper than a face axis allows: not the minimum translation (MPR's portal depth, up to 81 % too deep on
    // vertex-into-vertex floes in the failure map; for prisms the face axes are every Minkowski face, so the
    // check is exact for floes): sat answers.
    ++stats_.primary_failures;
    return exact();
  }
  contact::SatContact c;
  c.hit = r.depth > 0.0;
  c.depth = r.depth;
  c.normal = r.normal;
  c.point = r.point;
  c.feature = contact::SatFeature::face_a;  // unknown: let the manifold look for faces
  return c;
}

// The points that carry the normal force of the contact c between a and b: the manifold's, or the narrow phase's
// one point; k takes its normal, centre, depth and point count.
contact::ContactManifold SpatialWorld::manifold(int a, int b, const Mat3& rot_a, const Mat3& rot_b,
                                                const contact::SatContact& c, SpatialContact& k) const {
  k.a = a;
  k.b = b;
  k.normal = c.normal;
  k.point = c.point;
  k.depth = c.depth;
  contact::ContactManifold m;
  // sat: only for face contacts (an edge-edge contact is one point, whatever faces lie near its normal)
  if (settings_.contact_point == ContactPointModel::manifold && c.feature != contact::SatFeature::edge_edge) {
    m = contact::clip_manifold(*shape_[a], rot_a, world_vertices(a), *shape_[b], rot_b, world_vertices(b), c.normal);
  }
  if (m.count > 0) {
    k.normal = m.normal;
    k.point = m.centre();
    k.depth = m.max_depth();
    k.manifold_points = m.count;
  } else {
    m.count = 1;
    m.points[0] = c.point;
    m.depths[0] = c.depth;
  }
  return m;
}

// The forces of the contact k (points m) between k.a and k.b added to the bodies; whether it carries any (false:
// no effective mass along the normal).
bool SpatialWorld::apply_contact(const contact::ContactManifold& m, double dt, std::size_t& hint, SpatialContact& k) {
  const int a = k.a, b = k.b;
  auto relative_velocity = [&](const Vec3& x) {
    return Vec3(vel_[b] + angular_velocity(b).cross(x - pos_[b]) - vel_[a] - angular_velocity(a).cross(x - pos_[a]));
  };
  const Vec3 ra = k.point - pos_[a], rb = k.point - pos_[b];
  // Effective mass of the pair along the normal at the contact centre (rotation included): the damping that gives
  // restitution e for a point mass gives it for an eccentric impact too.
  double inv_m = 0.0;
  for (const auto& [i, r] : {std::pair<int, Vec3>{a, ra}, std::pair<int, Vec3>{b, rb}}) {
    if (!is_dynamic_[i]) continue;
    const Vec3 rn = r.cross(k.normal);
    inv_m += inv_mass_[i] + rn.dot(world_inverse_inertia(i) * rn);
  }
  if (!(inv_m > 0.0)) return false;
  const double ra_eff = is_dynamic_[a] ? radius_[a] : contact::kInfinite;
  const double rb_eff = is_dynamic_[b] ? radius_[b] : contact::kInfinite;
  auto coef = law_.coefficients(ra_eff, rb_eff, 1.0 / inv_m, contact::kInfinite);
  // Each point is a Hertz contact of its own depth (W = sum 2/5 k_n d_k^2.5: conservative, a flat face on a face
  // is stiffer than a corner), applied where it is. N points at one depth act as one contact of stiffness N k_n;
  // the damping that keeps its restitution e scales as sqrt(k) (speed-independent model: c = zeta sqrt(m k)) or
  // k^0.6 (paper model: c ~ k^0.6 m^0.4), so each point gets N^(1/2 or 0.6) c / N.
  const auto point_coef = [&] {
    auto pc = coef;
    const double exponent = law_.settings().damping == contact::DampingModel::paper ? -0.4 : -0.5;
    pc.damping = coef.damping * std::pow(static_cast<double>(m.count), exponent);
    return pc;
  }();
  Vec3 fn = Vec3::Zero(), torque_a = Vec3::Zero(), torque_b = Vec3::Zero();
  double normal_total = 0.0;
  k.stored_energy = 0.0;
  for (int p = 0; p < m.count; ++p) {
    const double d = m.depths[p];
    const double rate = -k.normal.dot(relative_velocity(m.points[p]));
    const double f = law_.evaluate(point_coef, d, rate, 0.0, 0.0, dt).normal;
    const Vec3 fp = f * k.normal;
    fn += fp;
    torque_b += (m.points[p] - pos_[b]).cross(fp);
    torque_a -= (m.points[p] - pos_[a]).cross(fp);
    normal_total += f;
    k.stored_energy += 0.4 * coef.k_n * d * d * std::sqrt(d);
  }
  const Vec3 vrel = relative_velocity(k.point);
  const Vec3 ft = friction(k, coef, normal_total, vrel, dt, hint);
  {
    const double kk = coef.k_n * m.count, mm = 1.0 / inv_m;
    const double rate = -k.normal.dot(vrel);
    const double v2 = rate * rate + 0.8 * kk * k.depth * k.depth * std::sqrt(k.depth) / mm;
    k.duration = contact::hertz_contact_duration(kk, mm, std::sqrt(v2));
  }
  k.normal_force = normal_total;
  k.force = fn + ft;
  if (!finite(k.force) || !finite(k.point) || !finite(torque_a) || !finite(torque_b)) {
    throw std::runtime_error("spatial contact between bodies " + std::to_string(id_[a]) + " and " +
                             std::to_string(id_[b]) + " gave a non-finite force at t = " + std::to_string(time_) +
                             " s");
  }
  force_[b] += k.force;
  torque_[b] += torque_b + rb.cross(ft);
  force_[a] -= k.force;
  torque_[a] += torque_a - ra.cross(ft);
  return true;
}

// The tangential force of the contact k at its centre (relative velocity vrel there): last step's spring turned
// into today's tangent plane (length kept), advanced by the slip, capped by Coulomb on the total normal force
// (contact::tangential_spring, the planar world's too); the spring kept for the next step where there is friction.
Vec3 SpatialWorld::friction(const SpatialContact& k, const contact::PairCoefficients& coef, double normal_total,
                            const Vec3& vrel, double dt, std::size_t& hint) {
  const contact::PairKey key = contact::make_key(id_[k.a], id_[k.b]);
  Vec3 s = Vec3::Zero();
  bool found = false;
  if (const Vec3 last = springs_.previous(key, hint, &found); found) {
    const double len = last.norm();
    s = last - k.normal * k.normal.dot(last);
    const double l2 = s.norm();
    s = l2 > 0.0 ? Vec3(s * (len / l2)) : Vec3::Zero();
  }
  const Vec3 slip = vrel - k.normal * k.normal.dot(vrel);
  const contact::TangentialSpring<Vec3> spring =
      contact::tangential_spring(s, slip, coef.k_s * std::sqrt(k.depth), coef.mu * normal_total, dt);
  if (coef.mu > 0.0) springs_.store(key, spring.spring);
  return spring.force;
}

void SpatialWorld::compute_forces(double dt) {
  body_loads();  // gravity and buoyancy
  broad_.find_pairs(boxes_, is_dynamic_, pairs_);
  contacts_.clear();
  std::size_t hint = 0;  // pairs come in nearly last step's order (contact::HistoryStore::previous)
  for (const auto& p : pairs_) {
    int a = p.a, b = p.b;
    if (z_lo_[a] > z_hi_[b] || z_lo_[b] > z_hi_[a]) continue;
    if (id_[a] > id_[b]) std::swap(a, b);
    ++stats_.queries;
    const Mat3 rot_a = q_[a].toRotationMatrix(), rot_b = q_[b].toRotationMatrix();
    const contact::SatContact c = measure(a, b, rot_a, rot_b);
    if (!c.hit) continue;
    SpatialContact k;
    const contact::ContactManifold m = manifold(a, b, rot_a, rot_b, c, k);
    if (!(k.depth > 0.0)) continue;
    if (apply_contact(m, dt, hint, k)) contacts_.push_back(k);
  }
  springs_.end_step();
  forces_ready_ = true;
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
