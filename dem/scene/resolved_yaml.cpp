// resolved_yaml(): every resolved setting of a Scene as YAML, with units as comments (printed by `polyfloe check`,
// written next to the results, and read back by parse_scene to the same settings).
#include <sstream>

#include "scene/scene_reader.h"
#include "scene/yaml_format.h"

namespace polyfloe::scene {

using detail::fmt;
using detail::quoted;

std::string resolved_yaml(const Scene& s) {
  std::ostringstream o;
  auto opt = [](const std::optional<double>& x) { return x ? fmt(*x) : std::string("auto"); };
  auto on = [](bool b) { return b ? "true" : "false"; };
  o << "# Scene '" << s.name << "', every setting resolved (units in the comments).\n";
  if (!s.source_path.empty()) o << "# from: " << s.source_path << "\n";
  for (const std::string& ov : s.overrides) o << "# --set " << ov << "\n";
  o << "name: " << quoted(s.name) << "\n";
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
  const contact::ContactLawSettings& c = s.world.contact;
  o << "ice:\n"
    << "  density: " << fmt(s.ice_density) << "  # [kg/m^3]\n"
    << "  youngs_modulus: " << fmt(c.youngs_modulus) << "  # [Pa]\n"
    << "  poisson_ratio: " << fmt(c.poisson_ratio) << "  # [-]\n";
  o << "contact:\n"
    << "  restitution: " << fmt(c.restitution) << "  # [-]\n"
    << "  friction: " << fmt(c.friction) << "  # [-] Coulomb coefficient\n"
    << "  damping_model: "
    << (c.damping == contact::DampingModel::paper ? "paper" : "speed_independent") << "\n"
    << "  force_model: " << (c.force_model == contact::ForceModel::gradient ? "gradient" : "centroid") << "\n"
    << "  broad_phase_cell: "
    << (s.world.broad_phase_cell > 0.0 ? fmt(s.world.broad_phase_cell) : std::string("auto")) << "  # [m]\n";
  const forcing::DriftSettings& d = s.world.drift;
  o << "forcing:\n"
    << "  ocean:\n"
    << "    density: " << fmt(d.water_density) << "  # [kg/m^3]\n"
    << "    current: " << fmt(d.current) << "  # [m/s]\n"
    << "    skin_drag: {enabled: " << on(d.skin_drag) << ", coefficient: " << fmt(d.skin_drag_coefficient)
    << "}  # c_w [-]\n"
    << "  air:\n"
    << "    density: " << fmt(d.air_density) << "  # [kg/m^3]\n"
    << "    wind: " << fmt(d.wind) << "  # [m/s]\n"
    << "    drag: {enabled: " << on(d.air_drag) << ", coefficient: " << fmt(d.air_drag_coefficient)
    << "}  # c_a [-]\n";
  if (s.bodies.empty()) o << "floes: []\n";
  else o << "floes:\n";
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
  if (const auto& f = s.floe_field) {
    o << "floe_field:\n"
      << "  region: [" << fmt(f->region_min.x()) << ", " << fmt(f->region_min.y()) << ", " << fmt(f->region_max.x())
      << ", " << fmt(f->region_max.y()) << "]  # [m] xmin, ymin, xmax, ymax\n"
      << "  concentration: " << fmt(f->concentration) << "  # [-] ice area / region area\n"
      << "  size: {min: " << fmt(f->size_min) << ", max: " << fmt(f->size_max) << ", exponent: " << fmt(f->exponent)
      << "}  # [m], [m], [-]; size = diameter of the area-equivalent circle\n"
      << "  corners: [" << f->corners_min << ", " << f->corners_max << "]  # [-]\n"
      << "  thickness: " << fmt(f->thickness) << "  # [m]\n"
      << "  velocity: " << fmt(f->velocity) << "  # [m/s]\n"
      << "  seed: " << f->seed << "\n"
      << "  max_attempts: " << f->max_attempts << "  # [-] placement tries per floe\n";
  }
  if (const auto& ch = s.channel) {
    o << "channel:\n"
      << "  basin_x_min: " << fmt(ch->basin_x_min) << "  # [m]\n"
      << "  basin_x_max: " << fmt(ch->basin_x_max) << "  # [m]\n"
      << "  basin_y_min: " << fmt(ch->basin_y_min) << "  # [m]\n"
      << "  basin_y_max: " << fmt(ch->basin_y_max) << "  # [m]\n"
      << "  funnel_length: " << fmt(ch->funnel_length) << "  # [m]\n"
      << "  opening: " << fmt(ch->opening) << "  # [m]\n"
      << "  strait_length: " << fmt(ch->strait_length) << "  # [m]\n"
      << "  wall_thickness: " << fmt(ch->wall_thickness) << "  # [m]\n";
  }
  return o.str();
}

}  // namespace polyfloe::scene
