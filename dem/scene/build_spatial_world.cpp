// Scene -> SpatialWorld: the polyhedra of spatial.bodies, with their given ids or the next free ones in order.
#include <algorithm>
#include <cmath>
#include <sstream>

#include "scene/body_ids.h"
#include "scene/scene.h"

namespace polyfloe::scene {

namespace {

std::string body_where(const SpatialBodySpec& b, std::size_t i) {
  const std::string name = "spatial.bodies." + std::to_string(i);
  return b.source.where.empty() ? name : b.source.where + " (" + name + ")";
}

}  // namespace

dynamics::SpatialWorld build_spatial_world(const Scene& scene) {
  if (!scene.spatial) throw SceneError(scene.source_path + ": not a spatial scene (no 'spatial' block)");
  const SpatialSpec& sp = *scene.spatial;
  dynamics::SpatialSettings settings;
  settings.contact = scene.world.contact;
  settings.contact.reference_speed = reference_speed(scene);
  settings.narrow_phase = sp.narrow_phase;
  settings.contact_point = sp.contact_point;
  settings.gravity = sp.gravity;
  settings.buoyancy = sp.buoyancy;
  settings.water_density = sp.water_density;
  settings.water_level = sp.water_level;
  dynamics::SpatialWorld world(settings);

  std::vector<std::optional<std::uint64_t>> given;
  for (const SpatialBodySpec& b : sp.bodies) given.push_back(b.id);
  const std::vector<dynamics::BodyId> ids =
      detail::assign_ids(given, [&](std::size_t i) { return body_where(sp.bodies[i], i); });
  for (std::size_t i = 0; i < sp.bodies.size(); ++i) {
    const SpatialBodySpec& b = sp.bodies[i];
    dynamics::SpatialBodyDesc d;
    d.id = ids[i];
    try {
      d.shape = std::make_shared<geometry::ConvexPolyhedron>(
          b.box ? geometry::ConvexPolyhedron::box(*b.box)
                : geometry::ConvexPolyhedron::prism(geometry::ConvexPolygon::from_vertices(b.polygon), b.thickness));
    } catch (const geometry::GeometryError& e) {
      throw SceneError(body_where(b, i) + ": " + e.what());
    }
    d.density = b.density.value_or(scene.ice_density);
    d.position = b.position;
    d.orientation = dynamics::Quat(Eigen::AngleAxisd(b.rotation_angle, b.rotation_axis.normalized()));
    d.velocity = b.velocity;
    d.angular_velocity = b.angular_velocity;
    d.motion = b.motion;
    try {
      world.add_body(d);
    } catch (const std::invalid_argument& e) {
      throw SceneError(body_where(b, i) + ": " + e.what());
    }
  }
  // Bodies must start apart: an initial overlap is an explosion at the first step.
  for (int i = 0; i < static_cast<int>(world.size()); ++i) {
    for (int j = i + 1; j < static_cast<int>(world.size()); ++j) {
      if (world.motion(i) != dynamics::Motion::dynamic && world.motion(j) != dynamics::Motion::dynamic) continue;
      const auto c = contact::sat_penetration(
          world.shape(i), world.orientation(i).toRotationMatrix(), world.world_vertices(i), world.position(i),
          world.shape(j), world.orientation(j).toRotationMatrix(), world.world_vertices(j), world.position(j));
      if (c.hit) {
        std::ostringstream msg;
        msg << body_where(sp.bodies[static_cast<std::size_t>(i)], static_cast<std::size_t>(i)) << " and "
            << body_where(sp.bodies[static_cast<std::size_t>(j)], static_cast<std::size_t>(j)) << " overlap by "
            << c.depth << " m at the start: move them apart";
        throw SceneError(msg.str());
      }
    }
  }
  return world;
}

double time_step(const Scene& scene, const dynamics::SpatialWorld& world) {
  double dt = 0.0;
  if (scene.time.dt) {
    dt = *scene.time.dt;
  } else {
    const double duration = world.shortest_contact_duration(reference_speed(scene));
    if (!(duration > 0.0) || !std::isfinite(duration))
      throw SceneError(scene.source_path + ": cannot choose an automatic time step (shortest contact duration " +
                       std::to_string(duration) + " s); set run.dt");
    dt = duration / scene.time.steps_per_contact;
  }
  check_run_length(scene, dt);
  return dt;
}

}  // namespace polyfloe::scene
