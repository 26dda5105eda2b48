// The spatial world's contact stage (dynamics/spatial_world.h): per candidate pair the narrow phase, the points
// that carry the force, the Hertz law and the 3-D tangential spring, each pair into a record of its own (on the
// threads), then the records summed into the bodies' forces in pair order (on one thread).
#include <chrono>
#include <cmath>
#include <exception>
#include <stdexcept>
#include <string>
#include <utility>

#include "dynamics/parallel.h"
#include "dynamics/spatial_world.h"

namespace polyfloe::dynamics {

namespace {

bool finite(const Vec3& v) { return v.allFinite(); }

}  // namespace

// The narrow phase of bodies a and b (rotations rot_a, rot_b): sat, or libccd with its answer checked and sat
// behind it.
contact::SatContact SpatialWorld::measure(int a, int b, const Mat3& rot_a, const Mat3& rot_b, bool& failure) const {
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
    failure = true;
    return exact();
  }
  if (r.status == contact::CcdStatus::separated) {
    // libccd's GJK can call an overlapping pair separated (3 in 120,000 random level-floe pairs: the failure
    // map), which no check of its answer can see: every separation is confirmed exactly, a miss counted.
    const contact::SatContact c = exact();
    if (c.hit) failure = true;
    return c;
  }
  if (r.depth >
      contact::least_face_overlap(*shape_[a], rot_a, world_vertices(a), *shape_[b], rot_b, world_vertices(b)) +
          1e-9 * (shape_[a]->circumradius() + shape_[b]->circumradius())) {
    // Deeper than a face axis allows: not the minimum translation (MPR's portal depth, up to 81 % too deep on
    // vertex-into-vertex floes in the failure map; for prisms the face axes are every Minkowski face, so the
    // check is exact for floes): sat answers.
    failure = true;
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

// The forces of the contact r.k (points m) between k.a and k.b into r; whether it carries any (false: no effective
// mass along the normal).
bool SpatialWorld::apply_contact(const contact::ContactManifold& m, double dt, std::size_t& hint, PairResult& r) const {
  SpatialContact& k = r.k;
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
  const Vec3 ft = friction(r, coef, normal_total, vrel, dt, hint, r.tangential_spring);
  r.spring = coef.mu > 0.0;
  {
    const double kk = coef.k_n * m.count, mm = 1.0 / inv_m;
    const double rate = -k.normal.dot(vrel);
    const double v2 = rate * rate + 0.8 * kk * k.depth * k.depth * std::sqrt(k.depth) / mm;
    k.impact_speed = std::sqrt(v2);
    k.duration = contact::hertz_contact_duration(kk, mm, k.impact_speed);
  }
  k.normal_force = normal_total;
  k.force = fn + ft;
  if (!finite(k.force) || !finite(k.point) || !finite(torque_a) || !finite(torque_b)) {
    throw std::runtime_error("spatial contact between bodies " + std::to_string(id_[a]) + " and " +
                             std::to_string(id_[b]) + " gave a non-finite force at t = " + std::to_string(time_) +
                             " s");
  }
  r.torque_b = torque_b + rb.cross(ft);
  r.torque_a = torque_a - ra.cross(ft);
  return true;
}

// The tangential force of the contact k at its centre (relative velocity vrel there): last step's spring turned
// into today's tangent plane (length kept), advanced by the slip, capped by Coulomb on the total normal force
// (contact::tangential_spring, the planar world's too); `spring` the one to keep for the next step.
Vec3 SpatialWorld::friction(const PairResult& r, const contact::PairCoefficients& coef, double normal_total,
                            const Vec3& vrel, double dt, std::size_t& hint, Vec3& spring_kept) const {
  const SpatialContact& k = r.k;
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
  spring_kept = spring.spring;
  return spring.force;
}

// One candidate pair, apart from every other: its narrow phase, manifold and forces into r (no member written).
void SpatialWorld::evaluate_pair(const contact::CandidatePair& p, double dt, std::size_t& hint, PairResult& r) const {
  r.measured = r.failure = r.contact = r.spring = false;
  r.error = nullptr;
  int a = p.a, b = p.b;
  if (z_lo_[a] > z_hi_[b] || z_lo_[b] > z_hi_[a]) return;
  if (id_[a] > id_[b]) std::swap(a, b);
  r.measured = true;
  try {
    const Mat3 rot_a = q_[a].toRotationMatrix(), rot_b = q_[b].toRotationMatrix();
    const contact::SatContact c = measure(a, b, rot_a, rot_b, r.failure);
    if (!c.hit) return;
    r.k = SpatialContact{};
    const contact::ContactManifold m = manifold(a, b, rot_a, rot_b, c, r.k);
    if (!(r.k.depth > 0.0)) return;
    r.contact = apply_contact(m, dt, hint, r);
  } catch (...) {  // not across the threads: rethrown in pair order by add_pair
    r.error = std::current_exception();
  }
}

// A pair's record into the forces, the contacts, the springs and the counts (called in pair order).
void SpatialWorld::add_pair(PairResult& r) {
  if (r.error) std::rethrow_exception(std::exchange(r.error, nullptr));
  if (!r.measured) return;
  ++stats_.queries;
  if (r.failure) ++stats_.primary_failures;
  if (!r.contact) return;
  const SpatialContact& k = r.k;
  force_[k.b] += k.force;
  torque_[k.b] += r.torque_b;
  force_[k.a] -= k.force;
  torque_[k.a] += r.torque_a;
  if (r.spring) springs_.store(contact::make_key(id_[k.a], id_[k.b]), r.tangential_spring);
  contacts_.push_back(k);
}

void SpatialWorld::report_contacts() {
  report_.deepest = DeepestOverlap{};
  report_.shortest = ContactResolution{};
  for (const SpatialContact& c : contacts_) {
    const double r = std::min(shape_[c.a]->equivalent_radius(), shape_[c.b]->equivalent_radius());
    report_.deepest.consider(c.depth, kOverlapLimit * r, c.a, c.b);
    if (c.duration < report_.shortest.duration) report_.shortest = {c.duration, c.impact_speed, c.a, c.b};
  }
}

void SpatialWorld::compute_forces(double dt) {
  using clock = std::chrono::steady_clock;
  const auto t0 = clock::now();
  body_loads();  // gravity and buoyancy
  const auto t1 = clock::now();
  broad_.find_pairs(boxes_, is_dynamic_, pairs_);
  const auto t2 = clock::now();
  contacts_.clear();
  // Pairs come in nearly last step's order: each thread passes its lookup hint along its stretch of pairs
  // (contact::HistoryStore::previous), the index built first when several threads will only read it (one thread
  // builds it when a lookup first misses its hint, if ever).
  const auto n = static_cast<std::ptrdiff_t>(pairs_.size());
  const int threads = threads_for(pairs_.size(), 700.0);
  if (threads > 1) springs_.prepare_lookups();
  hints_.assign(static_cast<std::size_t>(threads_), 0);
  if (threads > 1) {  // every pair into a record of its own on the threads, then the records in pair order
    if (results_.size() < pairs_.size()) results_.resize(pairs_.size());
    polyfloe_parallel_for(n, threads, [&](std::ptrdiff_t p) {
      const auto k = static_cast<std::size_t>(p);
      evaluate_pair(pairs_[k], dt, hints_[static_cast<std::size_t>(polyfloe_thread_index())], results_[k]);
    });
    for (std::size_t k = 0; k < pairs_.size(); ++k) add_pair(results_[k]);
  } else {  // the same, each record added as soon as it is made (one record, in cache)
    if (results_.empty()) results_.resize(1);
    for (const contact::CandidatePair& p : pairs_) {
      evaluate_pair(p, dt, hints_[0], results_[0]);
      add_pair(results_[0]);
    }
  }
  springs_.end_step();
  report_contacts();
  forces_ready_ = true;
  profile_.forcing += std::chrono::duration<double>(t1 - t0).count();
  profile_.broad += std::chrono::duration<double>(t2 - t1).count();
  profile_.narrow_and_law += std::chrono::duration<double>(clock::now() - t2).count();
  profile_.candidates += pairs_.size();
  profile_.contacts += contacts_.size();
}

}  // namespace polyfloe::dynamics
