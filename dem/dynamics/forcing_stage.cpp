// Stage: drift forces on every dynamic body - form drag on the submerged side faces, the drag moment, skin drag
// on the bottom, air drag on the top, Coriolis - with the damping matrix the final half kick uses to treat them
// semi-implicitly. Spatially uniform fields (and still water, calm air) are sampled once per step.
#include <sstream>

#include "dynamics/parallel.h"
#include "dynamics/world.h"

namespace polyfloe::dynamics {

namespace {

// A field as the stage sees it: null, or uniform this step (value), or sampled at points.
struct FieldNow {
  const forcing::VelocityField* field = nullptr;
  bool uniform = true;
  Vec2 value{0.0, 0.0};
  FieldNow(const forcing::VelocityField* f, double t) : field(f), uniform(!f || f->uniform_in_space()) {
    if (f && uniform) value = f->at({0.0, 0.0, 0.0}, t);
  }
};

}  // namespace

// What every body of one drift evaluation shares.
struct World::DriftStage {
  const forcing::DriftSettings& s;
  double t;  // [s]
  FieldNow ocean, wind;
  bool sides, surfaces;
};

// Each thread's scratch sized for the largest body (no allocation in the loop).
void World::prepare_drift_scratch() {
  if (drift_scratch_.size() < static_cast<std::size_t>(threads_))
    drift_scratch_.resize(static_cast<std::size_t>(threads_));
  for (DriftScratch& d : drift_scratch_) {
    d.error_body = -1;
    if (d.quad_rx.size() < max_quad_points_) {
      d.quad_points.resize(max_quad_points_);
      d.quad_fluid.resize(max_quad_points_);
      d.quad_rx.resize(max_quad_points_);
      d.quad_ry.resize(max_quad_points_);
      d.quad_fx.resize(max_quad_points_);
      d.quad_fy.resize(max_quad_points_);
    }
    if (d.side_points.size() < max_vertices_) {
      d.side_points.resize(max_vertices_);
      d.side_water.resize(max_vertices_);
    }
  }
}

// Form drag on body i's submerged side faces and the drag moment, into `load`.
void World::add_side_drift(std::size_t i, const DriftStage& stage, const forcing::FloeMotion& m, DriftScratch& scratch,
                           forcing::DriftLoad& load) const {
  const forcing::DriftSettings& s = stage.s;
  const std::span<const Vec2> verts = world_vertices(static_cast<int>(i));
  const std::size_t nv = verts.size();
  double omega_water = 0.0;  // [rad/s]
  if (stage.ocean.uniform) {
    if (s.form_drag)
      forcing::add_form_drag(load, s.form_drag_coefficient, s.water_density, draft_[i], m, verts, stage.ocean.value);
  } else {
    const std::span<forcing::Vec3> pts{scratch.side_points.data(), nv};
    const std::span<Vec2> water{scratch.side_water.data(), nv};
    forcing::side_sample_points(verts, draft_[i], pts);
    stage.ocean.field->sample(stage.t, pts, water);
    if (s.form_drag) forcing::add_form_drag(load, s.form_drag_coefficient, s.water_density, draft_[i], m, verts, water);
    omega_water = forcing::water_rotation_rate(verts, water, plan_area_[i]);
  }
  if (s.moment_drag)
    forcing::add_moment_drag(load, s.moment_drag_coefficient, s.water_density, side_area_[i], equivalent_radius_[i],
                             m.omega - omega_water);
}

// Skin drag on body i's bottom and air drag on its top, at its quadrature points, into `load`.
void World::add_surface_drift(std::size_t i, const DriftStage& stage, const forcing::FloeMotion& m,
                              DriftScratch& scratch, forcing::DriftLoad& load) const {
  const forcing::DriftSettings& s = stage.s;
  // Quadrature points: body-frame levers turned into the world frame.
  const int q0 = quad_off_[i];
  const std::size_t nq = static_cast<std::size_t>(quad_off_[i + 1] - q0);
  const double c = rotation_[i].x(), sn = rotation_[i].y();
  const double* lx = quad_lx_.data() + q0;
  const double* ly = quad_ly_.data() + q0;
  double* rx = scratch.quad_rx.data();
  double* ry = scratch.quad_ry.data();
  for (std::size_t q = 0; q < nq; ++q) {
    rx[q] = c * lx[q] - sn * ly[q];
    ry[q] = sn * lx[q] + c * ly[q];
  }
  const forcing::SurfaceSamples samples{{rx, nq}, {ry, nq}, {quad_weight_.data() + q0, nq}};
  auto surface = [&](const FieldNow& fluid, double z, double coefficient, double rho) {
    if (fluid.uniform) {
      forcing::add_surface_drag(load, coefficient, rho, m, samples, fluid.value);
      return;
    }
    const std::span<forcing::Vec3> pts{scratch.quad_points.data(), nq};
    const std::span<Vec2> u{scratch.quad_fluid.data(), nq};
    for (std::size_t q = 0; q < nq; ++q) pts[q] = {pos_[i].x() + rx[q], pos_[i].y() + ry[q], z};
    fluid.field->sample(stage.t, pts, u);
    for (std::size_t q = 0; q < nq; ++q) {
      scratch.quad_fx[q] = u[q].x();
      scratch.quad_fy[q] = u[q].y();
    }
    forcing::add_surface_drag(load, coefficient, rho, m, samples, {scratch.quad_fx.data(), nq},
                              {scratch.quad_fy.data(), nq});
  };
  if (s.skin_drag) surface(stage.ocean, -draft_[i], s.skin_drag_coefficient, s.water_density);
  if (s.air_drag) surface(stage.wind, thickness_[i] - draft_[i], s.air_drag_coefficient, s.air_density);
}

void World::drift_forces(double t) {
  const forcing::DriftSettings& s = settings_.drift;
  const std::size_t n = size();
  // New drag matrices: compute_forces keeps their inverses anew. Every body's load is written in the loop below
  // (not zeroed here first: a pass of its own).
  drift_.resize(n, !s.any());
  if (!s.any()) return;
  const DriftStage stage{s,
                         t,
                         FieldNow(s.ocean.get(), t),
                         FieldNow(s.wind.get(), t),
                         s.form_drag || s.moment_drag,
                         s.skin_drag || s.air_drag};
  const bool semi_implicit = s.treatment == forcing::DriftTreatment::semi_implicit;
  prepare_drift_scratch();  // per thread (each body's samples are independent of every other's)

  const int n_int = static_cast<int>(n);
  POLYFLOE_OMP_FOR(threads_)
  for (int ii = 0; ii < n_int; ++ii) {
    const std::size_t i = static_cast<std::size_t>(ii);
    // The world-frame vertices are stored in slot order (world.h): fetch a later body's ahead of use.
    if (ii + 8 < n_int) {
      const Vec2* ahead = world_xy_.data() + vert_begin_[i + 8];
      __builtin_prefetch(ahead);
      __builtin_prefetch(ahead + 4);
      __builtin_prefetch(ahead + 8);
    }
    if (!is_dynamic_[i]) {
      drift_.load(i) = forcing::DriftLoad{};
      continue;
    }
    DriftScratch& scratch = drift_scratch_[static_cast<std::size_t>(polyfloe_thread_index())];
    // A field that has no water at a sample throws; no exception may leave an OpenMP loop, so the lowest failing
    // body's message is kept (the same for any thread count) and thrown after the loop.
    try {
      const forcing::FloeMotion m{pos_[i], vel_eval_[i], omega_eval_[i]};
      forcing::DriftLoad load;
      if (stage.sides) add_side_drift(i, stage, m, scratch, load);
      if (stage.surfaces) add_surface_drift(i, stage, m, scratch, load);
      if (s.coriolis) forcing::add_coriolis(load, mass_[i], s.coriolis_parameter(pos_[i].y()), m.velocity);
      force_[i] += load.force;
      torque_[i] += load.torque;
      drift_.load(i) = semi_implicit ? load : forcing::DriftLoad{};
    } catch (const forcing::FieldError& e) {
      drift_.load(i) = forcing::DriftLoad{};
      if (scratch.error_body < 0) {  // each thread meets its bodies in increasing order
        scratch.error_body = ii;
        scratch.error_text = e.what();
      }
    }
  }
  const DriftScratch* failed = nullptr;
  for (const DriftScratch& d : drift_scratch_)
    if (d.error_body >= 0 && (!failed || d.error_body < failed->error_body)) failed = &d;
  if (failed) {
    const std::size_t i = static_cast<std::size_t>(failed->error_body);
    std::ostringstream os;
    os << "body " << id_[i] << " at (" << pos_[i].x() << ", " << pos_[i].y() << ") m, t = " << t
       << " s: " << failed->error_text;
    throw forcing::FieldError(os.str());
  }
}

}  // namespace polyfloe::dynamics
