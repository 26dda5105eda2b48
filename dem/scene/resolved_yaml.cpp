// resolved_yaml(): every resolved setting of a Scene as YAML, with units as comments (printed by `polyfloe check`,
// written next to the results, and read back by parse_scene to the same settings).
#include <filesystem>
#include <sstream>
#include <system_error>

#include "scene/scene_reader.h"
#include "scene/yaml_format.h"

namespace polyfloe::scene {

using detail::fmt;
using detail::quoted;

namespace {

// A field as a one-line YAML flow map with the keys of its kind.
std::string field_yaml(const forcing::FieldSpec& f) {
  using forcing::FieldKind;
  std::ostringstream o;
  o << "{type: " << forcing::to_string(f.kind);
  switch (f.kind) {
    case FieldKind::uniform: o << ", velocity: " << fmt(f.velocity); break;
    case FieldKind::linear:
      o << ", velocity: " << fmt(f.velocity) << ", origin: " << fmt(f.origin) << ", gradient: ["
        << fmt(Vec2(f.gradient.row(0).transpose())) << ", " << fmt(Vec2(f.gradient.row(1).transpose()))
        << "], depth_gradient: " << fmt(f.depth_gradient);
      break;
    case FieldKind::solid_body:
      o << ", centre: " << fmt(f.origin) << ", angular_velocity: " << fmt(f.angular_velocity)
        << ", velocity: " << fmt(f.velocity);
      break;
    case FieldKind::rankine:
      o << ", centre: " << fmt(f.origin) << ", core_radius: " << fmt(f.core_radius)
        << ", max_speed: " << fmt(f.max_speed) << ", velocity: " << fmt(f.velocity);
      break;
    case FieldKind::tidal:
      o << ", velocity: " << fmt(f.velocity) << ", amplitude: " << fmt(f.amplitude) << ", period: " << fmt(f.period)
        << ", phase: " << fmt(f.phase);
      break;
    case FieldKind::time_series:
      o << ", times: [";
      for (std::size_t i = 0; i < f.times.size(); ++i) o << (i ? ", " : "") << fmt(f.times[i]);
      o << "], velocities: [";
      for (std::size_t i = 0; i < f.values.size(); ++i) o << (i ? ", " : "") << fmt(f.values[i]);
      o << "], outside: " << forcing::to_string(f.outside);
      break;
    case FieldKind::file:
      o << ", path: " << quoted(f.path) << ", outside: " << forcing::to_string(f.outside)
        << ", no_water: " << forcing::to_string(f.no_water);
      if (f.no_water == forcing::OutsideWater::velocity) o << ", no_water_velocity: " << fmt(f.no_water_velocity);
      o << ", offset: " << fmt(f.offset) << ", time_offset: " << fmt(f.time_offset)
        << ", land: " << (f.land_walls ? "walls" : "none");
      break;
  }
  o << "}";
  return o.str();
}

std::string opt(const std::optional<double>& x) { return x ? fmt(*x) : std::string("auto"); }
const char* on(bool b) { return b ? "true" : "false"; }

// The comment lines: the scene, its file (one spelling) and the --set overrides; its name.
void put_header(std::ostream& o, const Scene& s) {
  o << "# Scene '" << s.name << "', every setting resolved (units in the comments).\n";
  if (!s.source_path.empty()) {  // one spelling of the file (links and '..' resolved): restarts compare this text
    std::error_code ec;
    const std::filesystem::path p = std::filesystem::weakly_canonical(s.source_path, ec);
    o << "# from: " << (ec ? s.source_path : p.string()) << "\n";
  }
  for (const std::string& ov : s.overrides) o << "# --set " << ov << "\n";
  o << "name: " << quoted(s.name) << "\n";
}

// `run` and `output`.
void put_run_and_output(std::ostream& o, const Scene& s) {
  o << "run:\n"
    << "  duration: " << fmt(s.time.duration) << "  # [s] simulated time\n"
    << "  dt: " << opt(s.time.dt) << "  # [s] time step; auto = shortest contact duration / steps_per_contact\n"
    << "  steps_per_contact: " << fmt(s.time.steps_per_contact) << "  # [-]\n"
    << "  reference_speed: " << opt(s.time.reference_speed)
    << "  # [m/s] impact speed; auto = max(1 m/s, free-drift speed)\n";
  o << "output:\n"
    << "  interval: " << fmt(s.output.interval) << "  # [s] simulated time between frames\n"
    << "  vtk: " << on(s.output.vtk) << "\n"
    << "  contacts: " << on(s.output.contacts) << "\n"
    << "  hdf5: " << on(s.output.hdf5) << "\n";
  const VelocityGridSettings& g = s.output.velocity_grid;
  o << "  velocity_grid:\n"
    << "    enabled: " << on(g.enabled) << "\n"
    << "    cell: " << fmt(g.cell) << "  # [m]\n"
    << "    region: "
    << (g.region ? "[" + fmt((*g.region)[0]) + ", " + fmt((*g.region)[1]) + ", " + fmt((*g.region)[2]) + ", " +
                       fmt((*g.region)[3]) + "]"
                 : std::string("auto"))
    << "  # [m] xmin, ymin, xmax, ymax\n"
    << "    samples_per_frame: " << g.samples_per_frame << "\n";
  o << "  checkpoint:\n"
    << "    every: " << s.output.checkpoint.every << "  # [frames] 0 = no checkpoints\n"
    << "    keep: " << s.output.checkpoint.keep << "  # newest checkpoints kept\n";
}

// `ice` and `contact`.
void put_ice_and_contact(std::ostream& o, const Scene& s) {
  const contact::ContactLawSettings& c = s.world.contact;
  o << "ice:\n"
    << "  density: " << fmt(s.ice_density) << "  # [kg/m^3]\n"
    << "  youngs_modulus: " << fmt(c.youngs_modulus) << "  # [Pa]\n"
    << "  poisson_ratio: " << fmt(c.poisson_ratio) << "  # [-]\n";
  o << "contact:\n"
    << "  restitution: " << fmt(c.restitution) << "  # [-]\n"
    << "  friction: " << fmt(c.friction) << "  # [-] Coulomb coefficient\n"
    << "  damping_model: " << (c.damping == contact::DampingModel::paper ? "paper" : "speed_independent") << "\n"
    << "  narrow_phase: " << (s.world.narrow_phase == dynamics::PlanarNarrowPhase::gjk_epa ? "gjk_epa" : "exact")
    << "  # level floes: exact overlap polygon, or the paper's GJK-EPA (comparison)\n"
    << "  force_model: " << contact::force_model_name(c.force_model) << "\n"
    << "  broad_phase_cell: " << (s.world.broad_phase_cell > 0.0 ? fmt(s.world.broad_phase_cell) : std::string("auto"))
    << "  # [m]\n"
    << "  broad_phase_skin: " << (s.world.broad_phase_skin > 0.0 ? fmt(s.world.broad_phase_skin) : std::string("auto"))
    << "  # [m] speed only: the contacts are the same for any value\n";
}

// `forcing` and `floes` (planar scenes).
void put_forcing_and_floes(std::ostream& o, const Scene& s) {
  if (!s.spatial) {  // spatial scenes have neither drift forcing nor floes
    const forcing::DriftSettings& d = s.world.drift;
    auto term = [&](bool enabled, double c) {
      return std::string("{enabled: ") + on(enabled) + ", coefficient: " + fmt(c) + "}";
    };
    o << "forcing:\n"
      << "  treatment: " << forcing::to_string(d.treatment) << "  # drag and Coriolis in the step\n"
      << "  quadrature: " << forcing::to_string(d.quadrature) << "  # bottom and top drag integrals\n"
      << "  update_every: " << d.update_every << "  # [-] steps per full drift evaluation (between: its linear model)\n"
      << "  ocean:\n"
      << "    density: " << fmt(d.water_density) << "  # [kg/m^3]\n"
      << "    field: " << field_yaml(s.ocean_field) << "  # [m], [m/s], [1/s], [s]\n"
      << "    form_drag: " << term(d.form_drag, d.form_drag_coefficient) << "  # C_d^F [-]\n"
      << "    moment_drag: " << term(d.moment_drag, d.moment_drag_coefficient) << "  # C_d^M [-]\n"
      << "    skin_drag: " << term(d.skin_drag, d.skin_drag_coefficient) << "  # c_w [-]\n"
      << "  air:\n"
      << "    density: " << fmt(d.air_density) << "  # [kg/m^3]\n"
      << "    field: " << field_yaml(s.wind_field) << "\n"
      << "    drag: " << term(d.air_drag, d.air_drag_coefficient) << "  # c_a [-]\n"
      << "  coriolis: {enabled: " << on(d.coriolis) << ", latitude: " << fmt(d.latitude)
      << ", beta_plane: " << on(d.beta_plane) << ", reference_y: " << fmt(d.reference_y) << "}  # [deg], [m]\n";
    if (s.bodies.empty())
      o << "floes: []\n";
    else
      o << "floes:\n";
    for (const BodySpec& b : s.bodies) {
      o << "  - polygon: [";
      for (std::size_t i = 0; i < b.polygon.size(); ++i) o << (i ? ", " : "") << fmt(b.polygon[i]);
      o << "]  # [m] body frame" << (b.source.where.empty() ? "" : ", from " + b.source.where) << "\n"
        << "    position: " << fmt(b.position) << "  # [m] centroid\n"
        << "    yaw: " << fmt(b.yaw) << "  # [rad]\n"
        << "    velocity: " << fmt(b.velocity) << "  # [m/s]\n"
        << "    angular_velocity: " << fmt(b.angular_velocity) << "  # [rad/s]\n"
        << "    thickness: " << fmt(b.thickness) << "  # [m]\n"
        << "    motion: " << dynamics::to_string(b.motion) << "\n";
      if (b.id) o << "    id: " << *b.id << "\n";
      o << "    external_force: " << fmt(b.external_force) << "  # [N]\n"
        << "    external_torque: " << fmt(b.external_torque) << "  # [N m]\n";
    }
  }
}

// `floe_field`.
void put_floe_field(std::ostream& o, const Scene& s) {
  if (const auto& f = s.floe_field) {
    o << "floe_field:\n"
      << "  region: [" << fmt(f->region_min.x()) << ", " << fmt(f->region_min.y()) << ", " << fmt(f->region_max.x())
      << ", " << fmt(f->region_max.y()) << "]  # [m] xmin, ymin, xmax, ymax\n"
      << "  concentration: " << fmt(f->concentration) << "  # [-] ice area / region area\n"
      << "  size: {min: " << fmt(f->size_min) << ", max: " << fmt(f->size_max) << ", exponent: " << fmt(f->exponent)
      << "}  # [m], [m], [-]; size = diameter of the area-equivalent circle\n"
      << "  corners: [" << f->corners_min << ", " << f->corners_max << "]  # [-]\n"
      << "  shape: " << (f->shape == FloeShape::voronoi ? "voronoi" : "ellipse") << "\n"
      << "  aspect_max: " << fmt(f->aspect_max) << "  # [-] ellipse shapes: axis ratio uniform in [1, aspect_max]\n"
      << "  thickness: " << fmt(f->thickness) << "  # [m]\n"
      << "  velocity: " << fmt(f->velocity) << "  # [m/s]\n"
      << "  seed: " << f->seed << "\n"
      << "  max_attempts: " << f->max_attempts << "  # [-] placement tries per floe\n";
  }
}

// `ice_sheet`.
void put_ice_sheet(std::ostream& o, const Scene& s) {
  if (const auto& sh = s.ice_sheet) {
    o << "ice_sheet:\n"
      << "  region: [" << fmt(sh->region_min.x()) << ", " << fmt(sh->region_min.y()) << ", " << fmt(sh->region_max.x())
      << ", " << fmt(sh->region_max.y()) << "]  # [m] xmin, ymin, xmax, ymax\n"
      << "  cell_size: " << fmt(sh->cell_size) << "  # [m] diameter of the circle of the mean cell area\n"
      << "  relaxation: " << sh->relaxation << "  # [-] Lloyd iterations\n"
      << "  thickness: " << fmt(sh->thickness) << "  # [m]\n"
      << "  velocity: " << fmt(sh->velocity) << "  # [m/s]\n"
      << "  seed: " << sh->seed << "\n"
      << "  elements: " << (sh->elements == SheetElements::triangles ? "triangles" : "cells") << "\n";
    if (const auto& b = sh->bonds) {
      o << "  bonds:\n"
        << "    tensile_strength: " << fmt(b->tensile_strength) << "  # [Pa]\n"
        << "    shear_strength: " << fmt(b->shear_strength) << "  # [Pa] Mohr-Coulomb cohesion\n"
        << "    friction_angle: " << fmt(b->friction_angle) << "  # [rad]\n"
        << "    points_per_face: " << b->points_per_face << "\n"
        << "    damping_ratio: " << fmt(b->damping_ratio) << "  # [-]\n";
    }
  }
}

// `spatial`.
void put_spatial(std::ostream& o, const Scene& s) {
  if (const auto& sp = s.spatial) {
    auto v3 = [](const geometry::Vec3& v) { return "[" + fmt(v.x()) + ", " + fmt(v.y()) + ", " + fmt(v.z()) + "]"; };
    o << "spatial:\n"
      << "  gravity: " << v3(sp->gravity) << "  # [m/s^2]\n"
      << "  buoyancy: " << on(sp->buoyancy) << "\n"
      << "  water_level: " << fmt(sp->water_level) << "  # [m]\n"
      << "  water_density: " << fmt(sp->water_density) << "  # [kg/m^3]\n"
      << "  narrow_phase: " << dynamics::to_string(sp->narrow_phase) << "\n"
      << "  contact_point: " << (sp->contact_point == dynamics::ContactPointModel::manifold ? "manifold" : "witness")
      << "\n";
    o << (sp->bodies.empty() ? "  bodies: []\n" : "  bodies:\n");
    for (const SpatialBodySpec& b : sp->bodies) {
      if (b.box) {
        o << "    - box: " << v3(*b.box) << "  # [m] edge lengths";
      } else {
        o << "    - polygon: [";
        for (std::size_t i = 0; i < b.polygon.size(); ++i) o << (i ? ", " : "") << fmt(b.polygon[i]);
        o << "]  # [m] body frame";
      }
      o << (b.source.where.empty() ? "" : ", from " + b.source.where) << "\n";
      o << "      thickness: " << fmt(b.thickness) << "  # [m] (polygon prisms)\n"
        << "      position: " << v3(b.position) << "  # [m] centroid\n"
        << "      rotation: {axis: " << v3(b.rotation_axis) << ", angle: " << fmt(b.rotation_angle) << "}  # [rad]\n"
        << "      velocity: " << v3(b.velocity) << "  # [m/s]\n"
        << "      angular_velocity: " << v3(b.angular_velocity) << "  # [rad/s]\n";
      if (b.density) o << "      density: " << fmt(*b.density) << "  # [kg/m^3]\n";
      o << "      motion: " << dynamics::to_string(b.motion) << "\n";
      if (b.id) o << "      id: " << *b.id << "\n";
    }
  }
}

// `channel`.
void put_channel(std::ostream& o, const Scene& s) {
  if (const auto& ch = s.channel) {
    o << "channel:\n"
      << "  basin_x_min: " << fmt(ch->basin_x_min) << "  # [m]\n"
      << "  basin_x_max: " << fmt(ch->basin_x_max) << "  # [m]\n"
      << "  basin_y_min: " << fmt(ch->basin_y_min) << "  # [m]\n"
      << "  basin_y_max: " << fmt(ch->basin_y_max) << "  # [m]\n"
      << "  funnel_length: " << fmt(ch->funnel_length) << "  # [m]\n"
      << "  opening: " << fmt(ch->opening) << "  # [m]\n"
      << "  strait_length: " << fmt(ch->strait_length) << "  # [m]\n"
      << "  wall_thickness: " << fmt(ch->wall_thickness) << "  # [m]\n"
      << "  jam_window: " << fmt(ch->jam_window) << "  # [s] jammed: no ice through the strait entrance this long\n"
      << "  jam_speed: " << fmt(ch->jam_speed) << "  # [m/s] ... with the funnel's ice slower than this\n";
  }
}

}  // namespace

std::string resolved_yaml(const Scene& s) {
  std::ostringstream o;
  for (auto put : {put_header, put_run_and_output, put_ice_and_contact, put_forcing_and_floes, put_floe_field,
                   put_ice_sheet, put_spatial, put_channel})
    put(o, s);
  return o.str();
}

}  // namespace polyfloe::scene
