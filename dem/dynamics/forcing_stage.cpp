// Stage: drift forces on every dynamic body - form drag on the submerged side faces, the drag moment, skin drag
// on the bottom, air drag on the top, Coriolis - with the damping matrix the final half kick uses to treat them
// semi-implicitly. Spatially uniform fields (and still water, calm air) are sampled once per step.
#include "dynamics/forcing_stage.h"

#include <sstream>

#include "dynamics/parallel.h"

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

// What every body of one drift evaluation shares.
struct DriftStage {
  const forcing::DriftSettings& s;
  const DriftBodies& b;
  double t;  // [s]
  FieldNow ocean, wind;
  bool sides, surfaces;
};

// Form drag on body i's submerged side faces and the drag moment, into `load`.
void add_side_drift(std::size_t i, const DriftStage& stage, const forcing::FloeMotion& m,
                    DriftForcing::Scratch& scratch, forcing::DriftLoad& load) {
  const forcing::DriftSettings& s = stage.s;
  const DriftBodies& b = stage.b;
  const std::span<const Vec2> verts{b.world_xy.data() + b.vert_begin[i],
                                    static_cast<std::size_t>(b.vert_off[i + 1] - b.vert_off[i])};
  const double draft = b.draft[i];
  const std::size_t nv = verts.size();
  double omega_water = 0.0;  // [rad/s]
  if (stage.ocean.uniform) {
    if (s.form_drag)
      forcing::add_form_drag(load, s.form_drag_coefficient, s.water_density, draft, m, verts, stage.ocean.value);
  } else {
    const std::span<forcing::Vec3> pts{scratch.side_points.data(), nv};
    const std::span<Vec2> water{scratch.side_water.data(), nv};
    forcing::side_sample_points(verts, draft, pts);
    stage.ocean.field->sample(stage.t, pts, water);
    if (s.form_drag) forcing::add_form_drag(load, s.form_drag_coefficient, s.water_density, draft, m, verts, water);
    omega_water = forcing::water_rotation_rate(verts, water, b.plan_area[i]);
  }
  if (s.moment_drag)
    forcing::add_moment_drag(load, s.moment_drag_coefficient, s.water_density, b.side_area[i], b.equivalent_radius[i],
                             m.omega - omega_water);
}

// Skin drag on body i's bottom and air drag on its top, at its quadrature points, into `load`.
void add_surface_drift(std::size_t i, const DriftStage& stage, const forcing::FloeMotion& m,
                       DriftForcing::Scratch& scratch, forcing::DriftLoad& load) {
  const forcing::DriftSettings& s = stage.s;
  const DriftBodies& b = stage.b;
  // Quadrature points: body-frame levers turned into the world frame.
  const int q0 = b.quad_off[i];
  const std::size_t nq = static_cast<std::size_t>(b.quad_off[i + 1] - q0);
  const double c = b.rotation[i].x(), sn = b.rotation[i].y();
  const double* lx = b.quad_lx.data() + q0;
  const double* ly = b.quad_ly.data() + q0;
  double* rx = scratch.quad_rx.data();
  double* ry = scratch.quad_ry.data();
  for (std::size_t q = 0; q < nq; ++q) {
    rx[q] = c * lx[q] - sn * ly[q];
    ry[q] = sn * lx[q] + c * ly[q];
  }
  const forcing::SurfaceSamples samples{{rx, nq}, {ry, nq}, {b.quad_weight.data() + q0, nq}};
  const Vec2 p = b.position[i];
  auto surface = [&](const FieldNow& fluid, double z, double coefficient, double rho) {
    if (fluid.uniform) {
      forcing::add_surface_drag(load, coefficient, rho, m, samples, fluid.value);
      return;
    }
    const std::span<forcing::Vec3> pts{scratch.quad_points.data(), nq};
    const std::span<Vec2> u{scratch.quad_fluid.data(), nq};
    for (std::size_t q = 0; q < nq; ++q) pts[q] = {p.x() + rx[q], p.y() + ry[q], z};
    fluid.field->sample(stage.t, pts, u);
    for (std::size_t q = 0; q < nq; ++q) {
      scratch.quad_fx[q] = u[q].x();
      scratch.quad_fy[q] = u[q].y();
    }
    forcing::add_surface_drag(load, coefficient, rho, m, samples, {scratch.quad_fx.data(), nq},
                              {scratch.quad_fy.data(), nq});
  };
  if (s.skin_drag) surface(stage.ocean, -b.draft[i], s.skin_drag_coefficient, s.water_density);
  if (s.air_drag) surface(stage.wind, b.thickness[i] - b.draft[i], s.air_drag_coefficient, s.air_density);
}

}  // namespace

// Each thread's scratch sized for the largest body (no allocation in the loop).
void DriftForcing::prepare(const DriftBodies& b, int threads) {
  if (scratch_.size() < static_cast<std::size_t>(threads)) scratch_.resize(static_cast<std::size_t>(threads));
  for (Scratch& d : scratch_) {
    d.error_body = -1;
    if (d.quad_rx.size() < b.max_quad_points) {
      d.quad_points.resize(b.max_quad_points);
      d.quad_fluid.resize(b.max_quad_points);
      d.quad_rx.resize(b.max_quad_points);
      d.quad_ry.resize(b.max_quad_points);
      d.quad_fx.resize(b.max_quad_points);
      d.quad_fy.resize(b.max_quad_points);
    }
    if (d.side_points.size() < b.max_vertices) {
      d.side_points.resize(b.max_vertices);
      d.side_water.resize(b.max_vertices);
    }
  }
}

void DriftForcing::apply(const forcing::DriftSettings& s, const DriftBodies& b, double t, int threads,
                         DriftModel& model, std::span<Vec2> force, std::span<double> torque) {
  const std::size_t n = b.id.size();
  // New drag matrices: compute_forces keeps their inverses anew. Every body's load is written in the loop below
  // (not zeroed here first: a pass of its own).
  model.resize(n, !s.any());
  if (!s.any()) return;
  const DriftStage stage{s,
                         b,
                         t,
                         FieldNow(s.ocean.get(), t),
                         FieldNow(s.wind.get(), t),
                         s.form_drag || s.moment_drag,
                         s.skin_drag || s.air_drag};
  const bool semi_implicit = s.treatment == forcing::DriftTreatment::semi_implicit;
  prepare(b, threads);  // per thread (each body's samples are independent of every other's)

  const int n_int = static_cast<int>(n);
  POLYFLOE_OMP_FOR(threads)
  for (int ii = 0; ii < n_int; ++ii) {
    const std::size_t i = static_cast<std::size_t>(ii);
    // The world-frame vertices are stored in slot order (world.h): fetch a later body's ahead of use.
    if (ii + 8 < n_int) {
      const Vec2* ahead = b.world_xy.data() + b.vert_begin[i + 8];
      __builtin_prefetch(ahead);
      __builtin_prefetch(ahead + 4);
      __builtin_prefetch(ahead + 8);
    }
    if (!b.dynamic[i]) {
      model.load(i) = forcing::DriftLoad{};
      continue;
    }
    Scratch& scratch = scratch_[static_cast<std::size_t>(polyfloe_thread_index())];
    // A field that has no water at a sample throws; no exception may leave an OpenMP loop, so the lowest failing
    // body's message is kept (the same for any thread count) and thrown after the loop.
    try {
      const forcing::FloeMotion m{b.position[i], b.velocity[i], b.omega[i]};
      forcing::DriftLoad load;
      if (stage.sides) add_side_drift(i, stage, m, scratch, load);
      if (stage.surfaces) add_surface_drift(i, stage, m, scratch, load);
      if (s.coriolis) forcing::add_coriolis(load, b.mass[i], s.coriolis_parameter(m.centre.y()), m.velocity);
      force[i] += load.force;
      torque[i] += load.torque;
      model.load(i) = semi_implicit ? load : forcing::DriftLoad{};
    } catch (const forcing::FieldError& e) {
      model.load(i) = forcing::DriftLoad{};
      if (scratch.error_body < 0) {  // each thread meets its bodies in increasing order
        scratch.error_body = ii;
        scratch.error_text = e.what();
      }
    }
  }
  const Scratch* failed = nullptr;
  for (const Scratch& d : scratch_)
    if (d.error_body >= 0 && (!failed || d.error_body < failed->error_body)) failed = &d;
  if (failed) {
    const std::size_t i = static_cast<std::size_t>(failed->error_body);
    std::ostringstream os;
    os << "body " << b.id[i] << " at (" << b.position[i].x() << ", " << b.position[i].y() << ") m, t = " << t
       << " s: " << failed->error_text;
    throw forcing::FieldError(os.str());
  }
}

}  // namespace polyfloe::dynamics
