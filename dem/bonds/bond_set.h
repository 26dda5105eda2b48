// Frozen ice: bonds across the shared faces of elements (paper section 1.1, Fig. 4, after Liu & Ji 2019).
//
// A face is the edge two elements share, extruded through the thickness h. It carries `points_per_face` bond points
// spread evenly along the edge (at the midpoints of equal segments), each standing for a strip of the face of area
// A_p = L h / points_per_face. In the plane every point through the thickness would see the same displacement (the
// elements do not bend out of the plane), so one point per strip stands for the column of points through the
// thickness.
//
// Each point joins an anchor on element a to one on element b (the same place when the bond forms). With
// d = anchor_b - anchor_a, n the face normal (from a to b, turned with the mean rotation of the two elements since
// bonding) and t = k x n:
//   stiffness per area  k_n = E / l,  k_s = k_n / (2 (1 + nu))   [Pa/m], l = distance between the two element
//                       centroids along n (two half-elements in series: a chain of bonded elements of length L
//                       stretches like a bar of modulus E);
//   stresses            sigma_n = k_n (d . n)  (> 0: tension), tau = k_s (d . t)  [Pa];
//   force on b          -A_p (sigma_n n + tau t) - dashpots on the points' relative velocity, sized so that the
//                       face's points together damp the pair's relative motion at ratio zeta (2 zeta sqrt(K m_red)
//                       with K the face's stiffness, shared among the points; the dashpots play no part in
//                       failure); a gets the opposite force; both act at the midpoint of the two anchors, so
//                       momentum and angular momentum are conserved;
//   failure of a point  tension: sigma_n > tensile_strength; shear (Mohr-Coulomb with a tension cut-off):
//                       |tau| > max(0, shear_strength - sigma_n tan(friction_angle)) - compression (sigma_n < 0)
//                       raises the shear capacity, so compression alone never breaks a bond;
//   failure of a face   when fewer than 2 of its points remain intact: its last points are released, and from then
//                       on the two elements meet only through the ordinary Hertz contact, which is skipped while a
//                       face between them holds.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "geometry/vec2.h"

namespace polyfloe::bonds {

using geometry::Vec2;

struct BondMaterial {
  double youngs_modulus = 1.0e9;    // E [Pa]
  double poisson_ratio = 0.3;       // nu [-]
  double tensile_strength = 1.5e6;  // normal (tensile) bond strength sigma_n-bar [Pa]
  double shear_strength = 1.5e6;    // cohesion c of the Mohr-Coulomb criterion [Pa]
  double friction_angle = 0.0;      // phi [rad]: shear capacity c - sigma_n tan(phi)
  double damping_ratio = 0.1;       // zeta [-] of each point's spring
  int points_per_face = 4;          // >= 2
};

// One face at the moment it is frozen: the two elements (indices in the caller's arrays and stable ids), the
// shared edge in the world frame, the thickness, and the two elements' poses then.
struct FaceDesc {
  int a = 0, b = 0;                  // element indices
  std::uint64_t id_a = 0, id_b = 0;  // stable ids
  Vec2 p0, p1;                       // ends of the shared edge [m]
  double thickness = 1.0;            // [m]
  Vec2 centre_a, centre_b;           // element centroids [m]
  double yaw_a = 0.0, yaw_b = 0.0;   // [rad]
};

// The state the bond forces read: element poses and velocities (all elements, indexed as in FaceDesc).
struct ElementState {
  std::span<const Vec2> position;  // centroid [m]
  std::span<const double> yaw;     // [rad]
  std::span<const Vec2> velocity;  // [m/s]
  std::span<const double> omega;   // [rad/s]
  std::span<const double> mass;    // [kg]; fixed or kinematic elements: +inf
};

// The part of a BondSet that changes as the ice breaks: what a checkpoint stores. Everything else is rebuilt from
// the scene (faces are frozen from the initial geometry).
struct BondState {
  std::vector<std::uint8_t> face_intact;       // [F]
  std::vector<std::int32_t> face_points_left;  // [F]
  std::vector<double> face_broken_time;        // [F] [s]; NaN while intact
  std::vector<std::uint8_t> point_intact;      // [P]
  std::vector<double> point_sigma, point_tau;  // [P] [Pa]
  double max_sigma = 0.0, max_tau = 0.0;       // [Pa]
};

class BondSet {
 public:
  explicit BondSet(const BondMaterial& material);
  const BondMaterial& material() const { return material_; }

  // Freezes a face. Throws std::invalid_argument for a degenerate face (zero length, a == b, a centroid on the
  // face's line, non-finite values).
  void add_face(const FaceDesc& f);

  // Adds the bond forces to `force` / `torque`, then fails the points past their strength and the faces left with
  // fewer than 2 intact points (at `time` [s]). Returns the number of faces that failed in this call.
  int apply(const ElementState& s, std::span<Vec2> force, std::span<double> torque, double time);

  // Two elements that share only a corner (the triangles of a cell around its centroid, the cells around a vertex
  // where four meet): while every face at that corner (`faces`: indices as returned in order by add_face) holds,
  // the ice around the corner is whole and the pair cannot really press into each other, so it is treated as
  // bonded (no contact law): a contact there would only see a rounding-level overlap at a degenerate corner.
  void add_corner_pair(int a, int b, std::span<const int> faces);

  // True while an intact face joins elements a and b (indices), or they are a corner pair whose corner is whole.
  bool bonded(int a, int b) const;
  // The elements were numbered anew: element e is element to[e] from now on (a permutation of the elements'
  // indices, as many as the World's bodies). Faces, points and their state keep their order.
  void renumber(std::span<const int> to);

  // A lower bound of the largest stable time step of the bonded elements: 2 / omega_max, with omega_max^2 bounded
  // per element by Gershgorin's theorem on the stiffness of its intact points, 2 (sum of the point stiffnesses) / m
  // + 2 (sum of stiffness x lever^2) / I, times the damped-oscillator factor sqrt(1 + z^2) - z with z = 2 zeta [s].
  // +inf without intact faces or when no bonded element is dynamic (mass +inf).
  double critical_time_step(std::span<const double> mass, std::span<const double> inertia) const;

  // A domain decomposition rank's share: the faces whose two elements `local_of` maps (element e of this set ->
  // its index there, -1 where it is not held), in this set's order, with their state, and the corner pairs whose
  // elements and faces are all kept. global_face() names each kept face's index in this set.
  BondSet subset(std::span<const int> local_of) const;
  // The index of face f in the set this one was taken from (subset()); f itself in a set not taken from another.
  std::size_t global_face(std::size_t f) const { return global_face_.empty() ? f : global_face_[f]; }

  // The breakable state, and its restoration into a set built from the same faces (checkpoints). restore() throws
  // std::invalid_argument when the sizes differ or the counts are inconsistent.
  BondState state() const;
  void restore(const BondState& s);

  // --- inspection (output, tests) ---
  std::size_t faces() const { return face_a_.size(); }
  std::size_t intact_faces() const { return intact_faces_; }
  std::size_t points() const { return point_area_.size(); }
  std::size_t intact_points() const { return intact_points_; }
  int face_a(std::size_t f) const { return face_a_[f]; }
  int face_b(std::size_t f) const { return face_b_[f]; }
  std::uint64_t face_id_a(std::size_t f) const { return face_id_a_[f]; }
  std::uint64_t face_id_b(std::size_t f) const { return face_id_b_[f]; }
  bool face_intact(std::size_t f) const { return face_intact_[f] != 0; }
  double face_broken_time(std::size_t f) const { return face_broken_time_[f]; }  // [s]; NaN while intact
  Vec2 face_normal0(std::size_t f) const { return face_normal_[f]; }             // world normal when frozen
  double face_length(std::size_t f) const { return face_length_[f]; }            // [m]
  Vec2 face_midpoint0(std::size_t f) const { return face_mid_[f]; }              // [m] when frozen
  std::size_t face_first_point(std::size_t f) const { return face_first_[f]; }
  bool point_intact(std::size_t p) const { return point_intact_[p] != 0; }
  Vec2 point_anchor_a(std::size_t p) const { return anchor_a_[p]; }    // lever in element a's body frame [m]
  double point_sigma(std::size_t p) const { return point_sigma_[p]; }  // last normal stress [Pa], > 0 tension
  double point_tau(std::size_t p) const { return point_tau_[p]; }      // last shear stress [Pa]
  // Of the last apply(): the largest tensile stress and the largest |shear| stress over intact points [Pa].
  double max_sigma() const { return max_sigma_; }
  double max_tau() const { return max_tau_; }

 private:
  void link(int a, int b, int face);  // elements a and b list each other with `face` (a corner pair: -1 - its index)

  BondMaterial material_;
  double tan_phi_ = 0.0;
  // faces
  std::vector<int> face_a_, face_b_;
  std::vector<std::uint64_t> face_id_a_, face_id_b_;
  std::vector<Vec2> face_normal_, face_mid_;
  std::vector<double> face_length_, face_kn_, face_ks_, face_yaw0_;  // k per area [Pa/m]; mean yaw when frozen
  std::vector<std::size_t> face_first_;
  std::vector<std::uint8_t> face_intact_;
  std::vector<int> face_points_left_;
  std::vector<double> face_broken_time_;
  // points (grouped by face)
  std::vector<Vec2> anchor_a_, anchor_b_;  // body-frame levers from each element's centroid [m]
  std::vector<double> point_area_;         // [m^2]
  std::vector<std::uint8_t> point_intact_;
  std::vector<double> point_sigma_, point_tau_;
  // per element: (neighbour, face) of every face it has, for bonded(); a corner pair k is stored as face -1 - k
  std::vector<std::vector<std::pair<int, int>>> adjacency_;
  std::vector<std::vector<int>> corner_faces_;
  std::vector<std::size_t> global_face_;  // a subset's: each face's index in the set it was taken from
  std::size_t intact_faces_ = 0, intact_points_ = 0;
  double max_sigma_ = 0.0, max_tau_ = 0.0;
};

}  // namespace polyfloe::bonds
