#include "dynamics/bodies.h"
#include "dynamics/rows.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "contact/contact_law.h"
#include "contact/narrow_phase_planar.h"

namespace polyfloe::dynamics {

int Bodies::add(const BodyDesc& d, double water_density, forcing::Quadrature rule) {
  if (!d.shape) throw std::invalid_argument("body " + std::to_string(d.id) + " has no shape");
  if (index.count(d.id)) throw std::invalid_argument("duplicate body id " + std::to_string(d.id));
  if (d.shape->size() > contact::kMaxPolygonVertices)
    throw std::invalid_argument("body " + std::to_string(d.id) + " has " + std::to_string(d.shape->size()) +
                                " vertices; at most " + std::to_string(contact::kMaxPolygonVertices) + " are allowed");
  if (!(d.thickness > 0.0) || !std::isfinite(d.thickness))
    throw std::invalid_argument("body " + std::to_string(d.id) + ": thickness must be positive");
  if (!(d.density > 0.0) || !std::isfinite(d.density))
    throw std::invalid_argument("body " + std::to_string(d.id) + ": density must be positive");
  const int i = static_cast<int>(id.size());
  const geometry::PrismMass pm = geometry::prism_mass(*d.shape, d.thickness, d.density);
  const bool dyn = d.motion == Motion::dynamic;
  id.push_back(d.id);
  index[d.id] = i;
  shape.push_back(d.shape);
  thickness.push_back(d.thickness);
  mass.push_back(pm.mass);
  inertia.push_back(pm.inertia_z);
  plan_area.push_back(d.shape->area());
  // Floating at equilibrium; a body denser than water rests fully submerged (draft = thickness).
  const double h = std::min(d.thickness, geometry::floating_draft(d.thickness, d.density, water_density));
  draft.push_back(h);
  side_area.push_back(d.shape->perimeter() * h);
  equivalent_radius.push_back(d.shape->equivalent_radius());
  {
    std::vector<forcing::QuadraturePoint> q;
    forcing::polygon_quadrature(d.shape->vertices(), rule, q);
    for (const forcing::QuadraturePoint& p : q) {
      quad_lx.push_back(p.point.x());
      quad_ly.push_back(p.point.y());
      quad_weight.push_back(p.weight);
    }
    quad_off.push_back(quad_off.back() + static_cast<int>(q.size()));
    max_quad_points = std::max(max_quad_points, q.size());
    max_vertices = std::max(max_vertices, static_cast<std::size_t>(d.shape->size()));
  }
  // Walls and plates are flat and immovable for the contact law: infinite radius and mass.
  radius.push_back(dyn ? d.shape->equivalent_radius() : contact::kInfinite);
  motion.push_back(d.motion);
  is_dynamic.push_back(dyn ? 1 : 0);
  ghost.push_back(0);
  if (dyn) dynamic_mass += mass.back();
  pos.push_back(d.position);
  yaw.push_back(d.yaw);
  vel.push_back(d.motion == Motion::fixed ? Vec2{0.0, 0.0} : d.velocity);
  omega.push_back(d.motion == Motion::fixed ? 0.0 : d.angular_velocity);
  force.emplace_back(0.0, 0.0);
  torque.push_back(0.0);
  ext_force.push_back(d.external_force);
  ext_torque.push_back(d.external_torque);
  inv_mass.push_back(dyn ? 1.0 / pm.mass : 0.0);
  inv_inertia.push_back(dyn ? 1.0 / pm.inertia_z : 0.0);
  vert_off.push_back(vert_off.back() + static_cast<int>(d.shape->size()));
  local_xy.insert(local_xy.end(), d.shape->vertices().begin(), d.shape->vertices().end());
  reach.push_back(d.shape->circumradius());
  if (dyn) {
    dynamic_radius_sum += d.shape->equivalent_radius();
    ++dynamic_count;
  }
  return i;
}

void Bodies::permute(std::span<const int> from) {
  for_each_array(
      *this, [&](auto& rows) { gather_rows(rows, from); },
      [&](std::vector<int>& off, auto&... values) { gather_ranges(off, from, values...); });
  for (std::size_t k = 0; k < id.size(); ++k) index[id[k]] = static_cast<int>(k);
}

}  // namespace polyfloe::dynamics
