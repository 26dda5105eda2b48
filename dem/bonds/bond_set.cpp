#include "bonds/bond_set.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace polyfloe::bonds {

namespace {

Vec2 rotate(const Vec2& v, double angle) {
  const double c = std::cos(angle), s = std::sin(angle);
  return {c * v.x() - s * v.y(), s * v.x() + c * v.y()};
}

Vec2 perp_left(const Vec2& v) { return {-v.y(), v.x()}; }
double cross(const Vec2& a, const Vec2& b) { return a.x() * b.y() - a.y() * b.x(); }

}  // namespace

BondSet::BondSet(const BondMaterial& m) : material_(m) {
  auto bad = [](const std::string& what) { throw std::invalid_argument("bond material: " + what); };
  if (!(m.youngs_modulus > 0.0) || !std::isfinite(m.youngs_modulus)) bad("Young's modulus must be positive");
  if (!(m.poisson_ratio >= 0.0 && m.poisson_ratio < 0.5)) bad("Poisson's ratio must lie in [0, 0.5)");
  if (!(m.tensile_strength > 0.0)) bad("tensile strength must be positive");
  if (!(m.shear_strength > 0.0)) bad("shear strength must be positive");
  if (!(m.friction_angle >= 0.0 && m.friction_angle < 0.5 * 3.141592653589793))
    bad("friction angle must lie in [0, pi/2)");
  if (!(m.damping_ratio >= 0.0 && m.damping_ratio <= 10.0)) bad("damping ratio must lie in [0, 10]");
  if (m.points_per_face < 2 || m.points_per_face > 64) bad("points per face must lie in 2..64");
  tan_phi_ = std::tan(m.friction_angle);
}

void BondSet::add_face(const FaceDesc& f) {
  const Vec2 e = f.p1 - f.p0;
  const double length = e.norm();
  auto bad = [&](const std::string& what) {
    throw std::invalid_argument("bond face between elements " + std::to_string(f.id_a) + " and " +
                                std::to_string(f.id_b) + ": " + what);
  };
  if (f.a == f.b || f.a < 0 || f.b < 0) bad("needs two distinct elements");
  if (!(length > 0.0) || !std::isfinite(length) || !f.centre_a.allFinite() || !f.centre_b.allFinite())
    bad("the shared edge must have a positive, finite length");
  if (!(f.thickness > 0.0)) bad("the thickness must be positive");
  // Normal from a to b.
  Vec2 n = perp_left(e) / length;
  if (n.dot(f.centre_b - f.centre_a) < 0.0) n = -n;
  const double da = n.dot(f.p0 - f.centre_a), db = n.dot(f.centre_b - f.p0);
  if (!(da > 0.0) || !(db > 0.0)) bad("each element's centroid must lie on its own side of the shared edge");
  const double kn = material_.youngs_modulus / (da + db);          // [Pa/m]
  const double ks = kn / (2.0 * (1.0 + material_.poisson_ratio));  // [Pa/m]
  const int k = material_.points_per_face;
  const double area = length * f.thickness / k;  // [m^2]

  const std::size_t face = face_a_.size();
  face_a_.push_back(f.a);
  face_b_.push_back(f.b);
  face_id_a_.push_back(f.id_a);
  face_id_b_.push_back(f.id_b);
  face_normal_.push_back(n);
  face_mid_.push_back(0.5 * (f.p0 + f.p1));
  face_length_.push_back(length);
  face_kn_.push_back(kn);
  face_ks_.push_back(ks);
  face_yaw0_.push_back(0.5 * (f.yaw_a + f.yaw_b));
  face_first_.push_back(point_area_.size());
  face_intact_.push_back(1);
  face_points_left_.push_back(k);
  face_broken_time_.push_back(std::numeric_limits<double>::quiet_NaN());
  for (int j = 0; j < k; ++j) {
    const Vec2 p = f.p0 + ((j + 0.5) / k) * e;
    anchor_a_.push_back(rotate(p - f.centre_a, -f.yaw_a));
    anchor_b_.push_back(rotate(p - f.centre_b, -f.yaw_b));
    point_area_.push_back(area);
    point_intact_.push_back(1);
    point_sigma_.push_back(0.0);
    point_tau_.push_back(0.0);
  }
  link(f.a, f.b, static_cast<int>(face));
  ++intact_faces_;
  intact_points_ += static_cast<std::size_t>(k);
}

void BondSet::add_corner_pair(int a, int b, std::span<const int> faces) {
  if (a == b || a < 0 || b < 0) throw std::invalid_argument("corner pair: needs two distinct elements");
  for (int f : faces)
    if (f < 0 || static_cast<std::size_t>(f) >= face_a_.size())
      throw std::invalid_argument("corner pair: face " + std::to_string(f) + " does not exist");
  const int k = static_cast<int>(corner_faces_.size());
  corner_faces_.emplace_back(faces.begin(), faces.end());
  link(a, b, -1 - k);
}

void BondSet::link(int a, int b, int face) {
  const std::size_t need = static_cast<std::size_t>(std::max(a, b)) + 1;
  if (adjacency_.size() < need) adjacency_.resize(need);
  adjacency_[static_cast<std::size_t>(a)].emplace_back(b, face);
  adjacency_[static_cast<std::size_t>(b)].emplace_back(a, face);
}

void BondSet::renumber(std::span<const int> to) {
  for (int& a : face_a_) a = to[static_cast<std::size_t>(a)];
  for (int& b : face_b_) b = to[static_cast<std::size_t>(b)];
  std::vector<std::vector<std::pair<int, int>>> adjacency(std::max(adjacency_.size(), to.size()));
  for (std::size_t e = 0; e < adjacency_.size(); ++e) {
    for (auto& [other, face] : adjacency_[e]) other = to[static_cast<std::size_t>(other)];
    adjacency[static_cast<std::size_t>(to[e])] = std::move(adjacency_[e]);
  }
  adjacency_ = std::move(adjacency);
}

BondSet BondSet::subset(std::span<const int> local_of) const {
  BondSet out(material_);
  out.tan_phi_ = tan_phi_;
  const auto k = static_cast<std::size_t>(material_.points_per_face);
  auto held = [&](int e) { return static_cast<std::size_t>(e) < local_of.size() ? local_of[e] : -1; };
  std::vector<int> kept(face_a_.size(), -1);  // this set's face -> the subset's
  for (std::size_t f = 0; f < face_a_.size(); ++f) {
    const int a = held(face_a_[f]), b = held(face_b_[f]);
    if (a < 0 || b < 0) continue;
    kept[f] = static_cast<int>(out.face_a_.size());
    out.face_a_.push_back(a);
    out.face_b_.push_back(b);
    out.face_id_a_.push_back(face_id_a_[f]);
    out.face_id_b_.push_back(face_id_b_[f]);
    out.face_normal_.push_back(face_normal_[f]);
    out.face_mid_.push_back(face_mid_[f]);
    out.face_length_.push_back(face_length_[f]);
    out.face_kn_.push_back(face_kn_[f]);
    out.face_ks_.push_back(face_ks_[f]);
    out.face_yaw0_.push_back(face_yaw0_[f]);
    out.face_first_.push_back(out.point_area_.size());
    out.face_intact_.push_back(face_intact_[f]);
    out.face_points_left_.push_back(face_points_left_[f]);
    out.face_broken_time_.push_back(face_broken_time_[f]);
    out.global_face_.push_back(global_face(f));
    for (std::size_t p = face_first_[f]; p < face_first_[f] + k; ++p) {
      out.anchor_a_.push_back(anchor_a_[p]);
      out.anchor_b_.push_back(anchor_b_[p]);
      out.point_area_.push_back(point_area_[p]);
      out.point_intact_.push_back(point_intact_[p]);
      out.point_sigma_.push_back(point_sigma_[p]);
      out.point_tau_.push_back(point_tau_[p]);
      out.intact_points_ += point_intact_[p] ? 1 : 0;
    }
    out.intact_faces_ += face_intact_[f] ? 1 : 0;
    out.link(a, b, kept[f]);
  }
  // Corner pair c joins elements e < other (each lists the other with -1 - c).
  for (std::size_t e = 0; e < adjacency_.size(); ++e)
    for (const auto& [other, face] : adjacency_[e]) {
      if (face >= 0 || static_cast<int>(e) > other) continue;
      const int a = held(static_cast<int>(e)), b = held(other);
      const std::vector<int>& ring = corner_faces_[static_cast<std::size_t>(-1 - face)];
      if (a < 0 || b < 0 || std::any_of(ring.begin(), ring.end(), [&](int f) { return kept[f] < 0; })) continue;
      std::vector<int> faces;
      for (const int f : ring) faces.push_back(kept[f]);
      out.add_corner_pair(a, b, faces);
    }
  out.max_sigma_ = max_sigma_;
  out.max_tau_ = max_tau_;
  return out;
}

bool BondSet::bonded(int a, int b) const {
  if (a < 0 || static_cast<std::size_t>(a) >= adjacency_.size()) return false;
  for (const auto& [other, face] : adjacency_[static_cast<std::size_t>(a)]) {
    if (other != b) continue;
    if (face >= 0) {
      if (face_intact_[static_cast<std::size_t>(face)]) return true;
    } else {
      const std::vector<int>& ring = corner_faces_[static_cast<std::size_t>(-1 - face)];
      if (std::all_of(ring.begin(), ring.end(), [&](int f) { return face_intact_[static_cast<std::size_t>(f)] != 0; }))
        return true;
    }
  }
  return false;
}

int BondSet::apply(const ElementState& s, std::span<Vec2> force, std::span<double> torque, double time) {
  int failed = 0;
  max_sigma_ = max_tau_ = 0.0;
  const double zeta = material_.damping_ratio;
  for (std::size_t f = 0; f < face_a_.size(); ++f) {
    if (!face_intact_[f]) continue;
    const auto a = static_cast<std::size_t>(face_a_[f]), b = static_cast<std::size_t>(face_b_[f]);
    const double ya = s.yaw[a], yb = s.yaw[b];
    const Vec2 n = rotate(face_normal_[f], 0.5 * (ya + yb) - face_yaw0_[f]);
    const Vec2 t = perp_left(n);
    const double kn = face_kn_[f], ks = face_ks_[f];
    const double ma = s.mass[a], mb = s.mass[b];
    if (std::isinf(ma) && std::isinf(mb)) continue;  // two fixed or kinematic elements: nothing can move the bond
    // Reduced mass of the pair (one side fixed: the other's mass).
    const double m_red = std::isinf(ma) ? mb : std::isinf(mb) ? ma : ma * mb / (ma + mb);
    const std::size_t p0 = face_first_[f], p1 = p0 + static_cast<std::size_t>(material_.points_per_face);
    const double ca = std::cos(ya), sa = std::sin(ya), cb = std::cos(yb), sb = std::sin(yb);
    for (std::size_t p = p0; p < p1; ++p) {
      if (!point_intact_[p]) continue;
      const Vec2 ra{ca * anchor_a_[p].x() - sa * anchor_a_[p].y(), sa * anchor_a_[p].x() + ca * anchor_a_[p].y()};
      const Vec2 rb{cb * anchor_b_[p].x() - sb * anchor_b_[p].y(), sb * anchor_b_[p].x() + cb * anchor_b_[p].y()};
      const Vec2 xa = s.position[a] + ra, xb = s.position[b] + rb;
      const Vec2 d = xb - xa;
      const Vec2 v = (s.velocity[b] + s.omega[b] * perp_left(rb)) - (s.velocity[a] + s.omega[a] * perp_left(ra));
      const double sigma = kn * d.dot(n), tau = ks * d.dot(t);  // [Pa]
      point_sigma_[p] = sigma;
      point_tau_[p] = tau;
      const double area = point_area_[p];
      // Dashpots: the face's points together damp the pair's relative motion at ratio zeta, 2 zeta sqrt(K m_red)
      // with K = k A_face = points x k A_p, shared evenly among the points.
      const double per = static_cast<double>(material_.points_per_face);
      const double cn = 2.0 * zeta * std::sqrt(kn * area * m_red / per);
      const double cs = 2.0 * zeta * std::sqrt(ks * area * m_red / per);
      const Vec2 fb = (area * sigma + cn * v.dot(n)) * n + (area * tau + cs * v.dot(t)) * t;
      // Both act at the midpoint of the anchors: equal and opposite, no net moment.
      const Vec2 mid = 0.5 * (xa + xb);
      force[b] -= fb;  // the spring pulls b back towards a when d opens
      force[a] += fb;
      torque[b] -= cross(mid - s.position[b], fb);
      torque[a] += cross(mid - s.position[a], fb);
      max_sigma_ = std::max(max_sigma_, sigma);
      max_tau_ = std::max(max_tau_, std::abs(tau));
    }
    // Failure after the forces of this evaluation: a point past its strength lets go from the next one on.
    for (std::size_t p = p0; p < p1; ++p) {
      if (!point_intact_[p]) continue;
      const double sigma = point_sigma_[p];
      const double capacity = std::max(0.0, material_.shear_strength - sigma * tan_phi_);
      if (sigma > material_.tensile_strength || std::abs(point_tau_[p]) > capacity) {
        point_intact_[p] = 0;
        --intact_points_;
        --face_points_left_[f];
      }
    }
    if (face_points_left_[f] < 2) {
      for (std::size_t p = p0; p < p1; ++p) {
        if (point_intact_[p]) {
          point_intact_[p] = 0;
          --intact_points_;
        }
      }
      face_points_left_[f] = 0;
      face_intact_[f] = 0;
      face_broken_time_[f] = time;
      --intact_faces_;
      ++failed;
    }
  }
  return failed;
}

double BondSet::critical_time_step(std::span<const double> mass, std::span<const double> inertia) const {
  std::vector<double> k_sum(mass.size(), 0.0), k_lever(mass.size(), 0.0);
  for (std::size_t f = 0; f < face_a_.size(); ++f) {
    if (!face_intact_[f]) continue;
    const std::size_t a = static_cast<std::size_t>(face_a_[f]), b = static_cast<std::size_t>(face_b_[f]);
    const double kn = face_kn_[f];  // the normal spring is the stiffer one
    const std::size_t p0 = face_first_[f], p1 = p0 + static_cast<std::size_t>(material_.points_per_face);
    for (std::size_t p = p0; p < p1; ++p) {
      if (!point_intact_[p]) continue;
      const double k = kn * point_area_[p];  // [N/m]
      k_sum[a] += k;
      k_sum[b] += k;
      k_lever[a] += k * anchor_a_[p].squaredNorm();
      k_lever[b] += k * anchor_b_[p].squaredNorm();
    }
  }
  double w2 = 0.0;
  for (std::size_t i = 0; i < mass.size(); ++i) {
    if (k_sum[i] == 0.0 || std::isinf(mass[i])) continue;
    w2 = std::max(w2, 2.0 * k_sum[i] / mass[i] + 2.0 * k_lever[i] / inertia[i]);
  }
  if (!(w2 > 0.0)) return std::numeric_limits<double>::infinity();
  // Explicit dashpots shrink the stable step of a damped oscillator to (2 / omega) (sqrt(1 + z^2) - z); the modes
  // of a chain or sheet see up to about 1.4 times the face's damping ratio: z = 2 zeta keeps a margin (measured
  // limits on a 12-element chain: 1.1 / 1.3 / 0.81 / 0.42 / 0.30 of the undamped bound at zeta = 0 / 0.1 / 0.3 / 0.7
  // / 1, against 1 / 0.82 / 0.57 / 0.32 / 0.24 here).
  const double z = 2.0 * material_.damping_ratio;
  return 2.0 / std::sqrt(w2) * (std::sqrt(1.0 + z * z) - z);
}

BondState BondSet::state() const {
  BondState s;
  s.face_intact = face_intact_;
  s.face_points_left.assign(face_points_left_.begin(), face_points_left_.end());
  s.face_broken_time = face_broken_time_;
  s.point_intact = point_intact_;
  s.point_sigma = point_sigma_;
  s.point_tau = point_tau_;
  s.max_sigma = max_sigma_;
  s.max_tau = max_tau_;
  return s;
}

void BondSet::restore(const BondState& s) {
  const std::size_t nf = faces(), np = points();
  if (s.face_intact.size() != nf || s.face_points_left.size() != nf || s.face_broken_time.size() != nf ||
      s.point_intact.size() != np || s.point_sigma.size() != np || s.point_tau.size() != np) {
    throw std::invalid_argument("bond state for " + std::to_string(s.face_intact.size()) + " faces and " +
                                std::to_string(s.point_intact.size()) + " points; this ice has " + std::to_string(nf) +
                                " faces and " + std::to_string(np) + " points");
  }
  std::size_t faces_left = 0, points_left = 0;
  for (std::size_t f = 0; f < nf; ++f) {
    const int k = material_.points_per_face;
    int left = 0;
    for (std::size_t q = face_first_[f]; q < face_first_[f] + static_cast<std::size_t>(k); ++q)
      left += s.point_intact[q] ? 1 : 0;
    if (left != s.face_points_left[f] || (s.face_intact[f] != 0) != (left >= 2))
      throw std::invalid_argument("bond state: face " + std::to_string(f) + " is inconsistent (" +
                                  std::to_string(left) + " intact points)");
    faces_left += s.face_intact[f] ? 1 : 0;
    points_left += static_cast<std::size_t>(left);
  }
  face_intact_ = s.face_intact;
  face_points_left_.assign(s.face_points_left.begin(), s.face_points_left.end());
  face_broken_time_ = s.face_broken_time;
  point_intact_ = s.point_intact;
  point_sigma_ = s.point_sigma;
  point_tau_ = s.point_tau;
  max_sigma_ = s.max_sigma;
  max_tau_ = s.max_tau;
  intact_faces_ = faces_left;
  intact_points_ = points_left;
}

}  // namespace polyfloe::bonds
