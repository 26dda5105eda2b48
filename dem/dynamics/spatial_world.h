// The spatial World: rigid convex polyhedra with six degrees of freedom (position, quaternion orientation, full
// inertia tensor), for scenes that leave the horizontal plane (the cube striking a plate, tilted or stacked ice).
//
// Separate from the planar World on purpose: level floes keep their exact planar method and 3-DOF state and never
// pay for the spatial machinery (one step function per mode, no per-body branching).
//
// One step (velocity Verlet, kick-drift-kick):
//   kick     v += dt/2 F/m,  L += dt/2 tau            (L: angular momentum about the centre, world frame)
//   drift    x += dt v,  q <- exp(dt w_mid) q, w_mid = R_mid I_body^-1 R_mid^T L at the mid-step orientation
//            (fixed-point iterations; time-symmetric: a free rotor's energy error is O(dt^3) per step and does not
//            drift)
//   forces   broad phase (grid on the xy boxes, then z), narrow phase (exact separating axes, or libccd behind
//            contact/narrow_phase_ccd.h with sat behind it), witness point or manifold (contact/manifold.h), contact
//            law (Hertz + damping + 3-D tangential spring capped by Coulomb), gravity and buoyancy (optional)
//   kick     as above.
#pragma once

#include <memory>
#include <span>
#include <exception>
#include <string>
#include <type_traits>
#include <unordered_map>
#include <vector>

#include <Eigen/Geometry>

#include "contact/broad_phase.h"
#include "contact/contact_cache.h"
#include "contact/contact_law.h"
#include "contact/manifold.h"
#include "contact/narrow_phase_ccd.h"
#include "contact/narrow_phase_sat3d.h"
#include "dynamics/body.h"
#include "dynamics/state_fields.h"
#include "dynamics/step_report.h"
#include "geometry/polyhedron.h"

namespace polyfloe::dynamics {

using geometry::Mat3;
using geometry::Vec3;
using Quat = Eigen::Quaterniond;

// How a pair's penetration depth, normal and point are measured.
enum class SpatialNarrowPhase {
  sat,               // exact separating axes (contact/narrow_phase_sat3d.h): no failure mode, energy-consistent point
  gjk_epa_tiebreak,  // libccd GJK-EPA with the support ties broken (contact/narrow_phase_ccd.h); a failed query or
                     // a "separated" that sat finds overlapping is answered by sat
  gjk_epa,           // libccd GJK-EPA as it comes
  mpr,               // libccd MPR
};
const char* to_string(SpatialNarrowPhase m);

// Where the contact force of a pair acts.
enum class ContactPointModel {
  witness,   // one force at the narrow phase's point: sat's witness (the deepest vertex, or the centroid of
             // vertices tied for deepest, or the closest points of two edges: W(depth) exactly, energy-consistent);
             // libccd's own heuristic point
  manifold,  // face clipping (contact/manifold.h): each point of the clipped patch a Hertz contact of its own depth
             // along the reference face's normal (no rocking of a face resting on a face); edge-edge contacts keep
             // the one point. Not exactly conservative (docs/validation.md: energy drift in the tumbling test)
};

struct SpatialSettings {
  contact::ContactLawSettings contact;
  SpatialNarrowPhase narrow_phase = SpatialNarrowPhase::sat;  // a libccd query that fails falls back to sat
  contact::CcdSettings ccd;
  ContactPointModel contact_point = ContactPointModel::witness;
  Vec3 gravity{0.0, 0.0, 0.0};    // [m/s^2]; e.g. (0, 0, -9.81)
  bool buoyancy = false;          // Archimedes' force at the centre of the submerged volume below z = water_level
  double water_density = 1025.0;  // [kg/m^3]
  double water_level = 0.0;       // [m]
};

struct SpatialBodyDesc {
  BodyId id = 0;
  std::shared_ptr<const geometry::ConvexPolyhedron> shape;  // body frame, centroid at the origin
  double density = 920.0;                                   // [kg/m^3]
  Vec3 position{0.0, 0.0, 0.0};                             // centroid [m]
  Quat orientation = Quat::Identity();                      // body to world
  Vec3 velocity{0.0, 0.0, 0.0};                             // [m/s]
  Vec3 angular_velocity{0.0, 0.0, 0.0};                     // world frame [rad/s]
  Motion motion = Motion::dynamic;
};

struct SpatialContact {
  int a = 0, b = 0;  // body indices, id(a) < id(b); the normal points from a to b
  Vec3 normal{0.0, 0.0, 1.0};
  Vec3 point{0.0, 0.0, 0.0};   // where the force acts [m]
  double depth = 0.0;          // [m]
  int manifold_points = 0;     // 0 = the narrow phase's single point
  double normal_force = 0.0;   // [N]
  Vec3 force{0.0, 0.0, 0.0};   // total contact force on b [N]
  double stored_energy = 0.0;  // 2/5 k_n d^2.5 [J]
  // Hertz duration of this impact at the speed it implies (approach rate and stored energy,
  // v^2 = d_dot^2 + (4/5) k d^2.5 / m*, k = points x k_n): a step that does not resolve it is unstable [s].
  double duration = 0.0;
  double impact_speed = 0.0;  // that speed v [m/s]
};

// Failures of a libccd narrow phase met so far, each answered by sat instead: queries it reported as failed,
// "separated" verdicts that sat found overlapping (every libccd separation is confirmed by sat), and depths deeper
// than a face axis allows (not the minimum translation: MPR).
struct NarrowPhaseStats {
  std::uint64_t queries = 0, primary_failures = 0;
};

// Everything that carries from one step to the next (what a checkpoint stores; see WorldState): shapes, masses
// and world-frame vertices are rebuilt from the scene and the poses.
struct SpatialWorldState {
  double time = 0.0;  // [s]
  std::uint64_t steps = 0;
  bool forces_ready = false;                                          // force and torque below belong to this state
  std::vector<BodyId> ids;                                            // [N], the order of every array below
  std::vector<Vec3> position, velocity;                               // [N] [m, m/s]
  std::vector<Quat> orientation;                                      // [N] body to world
  std::vector<Vec3> angular_momentum, force, torque;                  // [N] [kg m^2/s about the centre, N, N m]
  std::vector<contact::HistoryStore<Vec3>::Entry> contact_history;    // the tangential springs [m]
  std::uint64_t narrow_phase_queries = 0, narrow_phase_failures = 0;  // NarrowPhaseStats
};

// The fields of a SpatialWorldState (dynamics/state_fields.h), laid out as a WorldState's.
template <class V, class S>
requires std::is_same_v<std::remove_const_t<S>, SpatialWorldState>
void visit_fields(V& v, S& s) {
  v.attribute("time", s.time);
  v.count("steps", "step count", s.steps, 1e12);
  v.attribute("forces_ready", s.forces_ready);
  v.count("narrow_phase_queries", "narrow phase query count", s.narrow_phase_queries, 1e18);
  v.count("narrow_phase_failures", "narrow phase failure count", s.narrow_phase_failures, 1e18);
  v.group("world", [&] {
    v.bodies("ids", s.ids);
    v.bodies("position", s.position);
    v.bodies("orientation", s.orientation);
    v.bodies("velocity", s.velocity);
    v.bodies("angular_momentum", s.angular_momentum);
    v.bodies("force", s.force);
    v.bodies("torque", s.torque);
  });
  v.group("contacts", [&] { v.history(s.contact_history); });
}

class SpatialWorld {
 public:
  explicit SpatialWorld(const SpatialSettings& settings);

  // Throws std::invalid_argument on a duplicate id, a missing shape or a non-finite or non-positive value.
  int add_body(const SpatialBodyDesc& desc);
  std::size_t size() const { return id_.size(); }

  // Advance by dt [s] and report the step (dynamics/step_report.h). Throws std::runtime_error naming the pair when
  // neither narrow phase can measure a contact.
  const StepReport& step(double dt);
  // The last step's report, as step() returned it; its motion summary anew after a change from outside (add_body,
  // restore). Its overlap limit is kOverlapLimit x the smaller equivalent radius of a pair.
  const StepReport& report() const;
  static constexpr double kOverlapLimit = 0.25;
  void compute_forces(double dt);

  // Worker threads of step() (OpenMP; 1 = serial, the default). The result does not depend on it, bitwise: the
  // per-body stages write only their own body, and every candidate pair is evaluated apart, its forces then added
  // in the broad phase's order on one thread. Without OpenMP in the build it is ignored.
  void set_threads(int threads) { threads_ = threads < 1 ? 1 : threads; }
  int threads() const { return threads_; }

  // The state a checkpoint needs, and its restoration into a SpatialWorld built from the same scene. restore()
  // throws std::invalid_argument naming the first mismatch (other bodies, an array of the wrong size, a
  // non-finite value, a quaternion that is not of unit length, a spring of a pair that does not exist), leaving
  // this world unchanged.
  SpatialWorldState state() const;
  void restore(const SpatialWorldState& s);
  const StepProfile& profile() const { return profile_; }

  double time() const { return time_; }  // [s]
  std::uint64_t step_count() const { return steps_; }

  BodyId id(int i) const { return id_[i]; }
  // The bodies' indices in increasing id (the run guard's and the checkpoint signature's order, as the planar World's).
  std::span<const int> id_order() const;
  const geometry::ConvexPolyhedron& shape(int i) const { return *shape_[i]; }
  Motion motion(int i) const { return motion_[i]; }
  double mass(int i) const { return mass_[i]; }                       // [kg]
  const Mat3& body_inertia(int i) const { return inertia_body_[i]; }  // [kg m^2], body frame
  const Vec3& position(int i) const { return pos_[i]; }               // [m]
  const Quat& orientation(int i) const { return q_[i]; }
  const Vec3& velocity(int i) const { return vel_[i]; }   // [m/s]
  Vec3 angular_velocity(int i) const;                     // world frame [rad/s]
  const Vec3& force(int i) const { return force_[i]; }    // [N]
  const Vec3& torque(int i) const { return torque_[i]; }  // [N m]
  std::span<const Vec3> world_vertices(int i) const {
    return {world_.data() + vert_off_[i], static_cast<std::size_t>(vert_off_[i + 1] - vert_off_[i])};
  }
  const std::vector<SpatialContact>& contacts() const { return contacts_; }
  const NarrowPhaseStats& narrow_phase_stats() const { return stats_; }

  // --- diagnostics (dynamic bodies) ---
  double kinetic_energy() const;  // translation + rotation [J]
  double contact_energy() const;  // elastic energy stored in the active contacts [J]
  Vec3 linear_momentum() const;   // [kg m/s]
  Vec3 angular_momentum() const;  // about the origin [kg m^2/s]
  // Shortest undamped Hertz impact among the bodies present at `speed` [m/s]: each dynamic body striking its like
  // and a fixed body, at its least effective mass (a corner impact: 1 / (1/m + r_c^2 / I_min)) and with a full
  // manifold's stiffness (kMaxManifoldPoints x k_n) [s].
  double shortest_contact_duration(double speed) const;

  const SpatialSettings& settings() const { return settings_; }

 private:
  // The members SpatialWorldState holds as plain copies, each with its field (state_fields.h copy_members_*).
  template <class Self, class F>
  static void state_members(Self& w, F&& f) {
    f(&SpatialWorldState::time, w.time_);
    f(&SpatialWorldState::steps, w.steps_);
    f(&SpatialWorldState::forces_ready, w.forces_ready_);
    f(&SpatialWorldState::position, w.pos_);
    f(&SpatialWorldState::velocity, w.vel_);
    f(&SpatialWorldState::orientation, w.q_);
    f(&SpatialWorldState::angular_momentum, w.ang_mom_);
    f(&SpatialWorldState::force, w.force_);
    f(&SpatialWorldState::torque, w.torque_);
    f(&SpatialWorldState::narrow_phase_queries, w.stats_.queries);
    f(&SpatialWorldState::narrow_phase_failures, w.stats_.primary_failures);
  }
  void kick(double half_dt);
  void drift(double dt);
  void update_world_vertices(int i);
  Mat3 world_inverse_inertia(int i) const;
  // compute_forces' parts: gravity and buoyancy, the narrow phase of a pair, its manifold, its forces, its friction.
  void body_loads();
  // What the evaluation of one candidate pair gives (written by one thread, summed in pair order by another).
  struct PairResult {
    bool measured = false;  // the boxes overlap in z: a narrow-phase query
    bool failure = false;   // the chosen libccd method failed and sat answered (NarrowPhaseStats)
    bool contact = false;   // a contact with forces (k, torques, spring below)
    bool spring = false;    // a tangential spring to keep (friction)
    SpatialContact k;
    Vec3 torque_a, torque_b;   // [N m]
    Vec3 tangential_spring;    // [m]
    std::exception_ptr error;  // a contact that could not be measured or gave a non-finite force
  };
  void evaluate_pair(const contact::CandidatePair& p, double dt, std::size_t& hint, PairResult& r) const;
  contact::SatContact measure(int a, int b, const Mat3& rot_a, const Mat3& rot_b, bool& failure) const;
  contact::ContactManifold manifold(int a, int b, const Mat3& rot_a, const Mat3& rot_b, const contact::SatContact& c,
                                    SpatialContact& k) const;
  bool apply_contact(const contact::ContactManifold& m, double dt, std::size_t& hint, PairResult& r) const;
  Vec3 friction(const PairResult& r, const contact::PairCoefficients& coef, double normal_total, const Vec3& vrel,
                double dt, std::size_t& hint, Vec3& spring) const;
  void add_pair(PairResult& r);
  // The report's deepest overlap and shortest contact, from contacts_ (in pair order: the first of equals).
  void report_contacts();
  // The threads of a loop of `items` items of about `ns_per_item` each: one below kParallelWork, where starting the
  // threads (a few microseconds) would cost more than they save; the result is the same either way.
  static constexpr double kParallelWork = 2e4;  // [ns]
  int threads_for(std::size_t items, double ns_per_item) const {
    return static_cast<double>(items) * ns_per_item >= kParallelWork ? threads_ : 1;
  }

  SpatialSettings settings_;
  contact::ContactLaw law_;
  contact::GridBroadPhase broad_;
  double time_ = 0.0;
  std::uint64_t steps_ = 0;
  bool forces_ready_ = false;
  int threads_ = 1;
  StepProfile profile_;
  // hot state
  std::vector<Vec3> pos_, vel_, ang_mom_, force_, torque_;
  std::vector<Quat> q_;
  std::vector<double> inv_mass_;
  // cold data
  std::vector<BodyId> id_;
  mutable std::vector<int> by_id_;  // id_order(), listed when first asked for after add_body
  std::unordered_map<BodyId, int> index_;
  std::vector<std::shared_ptr<const geometry::ConvexPolyhedron>> shape_;
  std::vector<double> mass_, radius_;
  std::vector<Mat3> inertia_body_, inv_inertia_body_;
  std::vector<Motion> motion_;
  std::vector<std::uint8_t> is_dynamic_;
  std::vector<Vec3> omega_kinematic_;  // prescribed angular velocity of kinematic bodies [rad/s]
  // world-frame vertices and boxes
  std::vector<int> vert_off_{0};
  std::vector<Vec3> world_;
  std::vector<geometry::Aabb> boxes_;
  std::vector<double> z_lo_, z_hi_;
  // contacts
  std::vector<contact::CandidatePair> pairs_;
  std::vector<PairResult> results_;  // per candidate pair
  std::vector<std::size_t> hints_;   // per thread: where its last history lookup was found
  std::vector<SpatialContact> contacts_;
  contact::HistoryStore<Vec3> springs_;  // the tangential spring of each touching pair with friction [m]
  NarrowPhaseStats stats_;
  mutable StepReport report_;  // see report()
  mutable bool motion_ready_ = false;
};

}  // namespace polyfloe::dynamics
