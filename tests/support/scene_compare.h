// Scenes compared setting by setting, and the resolved-YAML round trip (scene reader and field-file tests).
#pragma once

#include <gtest/gtest.h>

#include <string>

#include "scene/scene_reader.h"

namespace polyfloe::scene {

// Every setting of two scenes, compared field by field.

inline void expect_same_field(const forcing::FieldSpec& a, const forcing::FieldSpec& b) {
  EXPECT_EQ(a.kind, b.kind);
  EXPECT_EQ(a.velocity, b.velocity);
  EXPECT_EQ(a.origin, b.origin);
  EXPECT_EQ(a.gradient, b.gradient);
  EXPECT_EQ(a.depth_gradient, b.depth_gradient);
  EXPECT_EQ(a.angular_velocity, b.angular_velocity);
  EXPECT_EQ(a.core_radius, b.core_radius);
  EXPECT_EQ(a.max_speed, b.max_speed);
  EXPECT_EQ(a.amplitude, b.amplitude);
  EXPECT_EQ(a.period, b.period);
  EXPECT_EQ(a.phase, b.phase);
  EXPECT_EQ(a.times, b.times);
  EXPECT_EQ(a.values, b.values);
  EXPECT_EQ(a.outside, b.outside);
  EXPECT_EQ(a.path, b.path);
  EXPECT_EQ(a.no_water, b.no_water);
  EXPECT_EQ(a.no_water_velocity, b.no_water_velocity);
  EXPECT_EQ(a.offset, b.offset);
  EXPECT_EQ(a.time_offset, b.time_offset);
  EXPECT_EQ(a.land_walls, b.land_walls);
  EXPECT_EQ(a.grid != nullptr, b.grid != nullptr);
}

inline void expect_same_settings(const Scene& a, const Scene& b) {
  EXPECT_EQ(a.name, b.name);
  EXPECT_EQ(a.time.duration, b.time.duration);
  EXPECT_EQ(a.time.dt, b.time.dt);
  EXPECT_EQ(a.time.steps_per_contact, b.time.steps_per_contact);
  EXPECT_EQ(a.time.reference_speed, b.time.reference_speed);
  EXPECT_EQ(a.output.interval, b.output.interval);
  EXPECT_EQ(a.output.vtk, b.output.vtk);
  EXPECT_EQ(a.output.contacts, b.output.contacts);
  EXPECT_EQ(a.output.hdf5, b.output.hdf5);
  EXPECT_EQ(a.output.velocity_grid.enabled, b.output.velocity_grid.enabled);
  EXPECT_EQ(a.output.velocity_grid.cell, b.output.velocity_grid.cell);
  EXPECT_EQ(a.output.velocity_grid.region, b.output.velocity_grid.region);
  EXPECT_EQ(a.output.velocity_grid.samples_per_frame, b.output.velocity_grid.samples_per_frame);
  EXPECT_EQ(a.ice_density, b.ice_density);
  const auto &ca = a.world.contact, &cb = b.world.contact;
  EXPECT_EQ(ca.youngs_modulus, cb.youngs_modulus);
  EXPECT_EQ(ca.poisson_ratio, cb.poisson_ratio);
  EXPECT_EQ(ca.restitution, cb.restitution);
  EXPECT_EQ(ca.friction, cb.friction);
  EXPECT_EQ(ca.damping, cb.damping);
  EXPECT_EQ(a.world.broad_phase_cell, b.world.broad_phase_cell);
  EXPECT_EQ(a.world.broad_phase_skin, b.world.broad_phase_skin);
  EXPECT_EQ(a.world.narrow_phase, b.world.narrow_phase);
  ASSERT_EQ(a.spatial.has_value(), b.spatial.has_value());
  if (a.spatial) {
    const auto &x = *a.spatial, &y = *b.spatial;
    EXPECT_EQ(x.gravity, y.gravity);
    EXPECT_EQ(x.buoyancy, y.buoyancy);
    EXPECT_EQ(x.water_level, y.water_level);
    EXPECT_EQ(x.water_density, y.water_density);
    EXPECT_EQ(x.narrow_phase, y.narrow_phase);
    EXPECT_EQ(x.contact_point, y.contact_point);
    ASSERT_EQ(x.bodies.size(), y.bodies.size());
    for (std::size_t i = 0; i < x.bodies.size(); ++i) {
      const auto &p = x.bodies[i], &q = y.bodies[i];
      EXPECT_EQ(p.box, q.box);
      EXPECT_EQ(p.polygon, q.polygon);
      EXPECT_EQ(p.thickness, q.thickness);
      EXPECT_EQ(p.position, q.position);
      EXPECT_EQ(p.rotation_axis, q.rotation_axis);
      EXPECT_EQ(p.rotation_angle, q.rotation_angle);
      EXPECT_EQ(p.velocity, q.velocity);
      EXPECT_EQ(p.angular_velocity, q.angular_velocity);
      EXPECT_EQ(p.density, q.density);
      EXPECT_EQ(p.motion, q.motion);
      EXPECT_EQ(p.id, q.id);
    }
  }
  const auto &da = a.world.drift, &db = b.world.drift;
  EXPECT_EQ(da.water_density, db.water_density);
  EXPECT_EQ(da.form_drag, db.form_drag);
  EXPECT_EQ(da.form_drag_coefficient, db.form_drag_coefficient);
  EXPECT_EQ(da.moment_drag, db.moment_drag);
  EXPECT_EQ(da.moment_drag_coefficient, db.moment_drag_coefficient);
  EXPECT_EQ(da.skin_drag, db.skin_drag);
  EXPECT_EQ(da.skin_drag_coefficient, db.skin_drag_coefficient);
  EXPECT_EQ(da.air_density, db.air_density);
  EXPECT_EQ(da.air_drag, db.air_drag);
  EXPECT_EQ(da.air_drag_coefficient, db.air_drag_coefficient);
  EXPECT_EQ(da.quadrature, db.quadrature);
  EXPECT_EQ(da.treatment, db.treatment);
  EXPECT_EQ(da.update_every, db.update_every);
  EXPECT_EQ(da.coriolis, db.coriolis);
  EXPECT_EQ(da.latitude, db.latitude);
  EXPECT_EQ(da.beta_plane, db.beta_plane);
  EXPECT_EQ(da.reference_y, db.reference_y);
  expect_same_field(a.ocean_field, b.ocean_field);
  expect_same_field(a.wind_field, b.wind_field);
  ASSERT_EQ(a.bodies.size(), b.bodies.size());
  for (std::size_t i = 0; i < a.bodies.size(); ++i) {
    const BodySpec &x = a.bodies[i], &y = b.bodies[i];
    EXPECT_EQ(x.polygon, y.polygon) << i;
    EXPECT_EQ(x.position, y.position) << i;
    EXPECT_EQ(x.yaw, y.yaw) << i;
    EXPECT_EQ(x.velocity, y.velocity) << i;
    EXPECT_EQ(x.angular_velocity, y.angular_velocity) << i;
    EXPECT_EQ(x.thickness, y.thickness) << i;
    EXPECT_EQ(x.motion, y.motion) << i;
    EXPECT_EQ(x.id, y.id) << i;
    EXPECT_EQ(x.external_force, y.external_force) << i;
    EXPECT_EQ(x.external_torque, y.external_torque) << i;
  }
  ASSERT_EQ(a.floe_field.has_value(), b.floe_field.has_value());
  if (a.floe_field) {
    const FloeFieldSpec &x = *a.floe_field, &y = *b.floe_field;
    EXPECT_EQ(x.region_min, y.region_min);
    EXPECT_EQ(x.region_max, y.region_max);
    EXPECT_EQ(x.concentration, y.concentration);
    EXPECT_EQ(x.size_min, y.size_min);
    EXPECT_EQ(x.size_max, y.size_max);
    EXPECT_EQ(x.exponent, y.exponent);
    EXPECT_EQ(x.corners_min, y.corners_min);
    EXPECT_EQ(x.corners_max, y.corners_max);
    EXPECT_EQ(x.shape, y.shape);
    EXPECT_EQ(x.aspect_max, y.aspect_max);
    EXPECT_EQ(x.thickness, y.thickness);
    EXPECT_EQ(x.velocity, y.velocity);
    EXPECT_EQ(x.seed, y.seed);
    EXPECT_EQ(x.max_attempts, y.max_attempts);
  }
  ASSERT_EQ(a.ice_sheet.has_value(), b.ice_sheet.has_value());
  if (a.ice_sheet) {
    const IceSheetSpec &x = *a.ice_sheet, &y = *b.ice_sheet;
    EXPECT_EQ(x.region_min, y.region_min);
    EXPECT_EQ(x.region_max, y.region_max);
    EXPECT_EQ(x.cell_size, y.cell_size);
    EXPECT_EQ(x.relaxation, y.relaxation);
    EXPECT_EQ(x.thickness, y.thickness);
    EXPECT_EQ(x.velocity, y.velocity);
    EXPECT_EQ(x.seed, y.seed);
    EXPECT_EQ(x.elements, y.elements);
    ASSERT_EQ(x.bonds.has_value(), y.bonds.has_value());
    if (x.bonds) {
      EXPECT_EQ(x.bonds->tensile_strength, y.bonds->tensile_strength);
      EXPECT_EQ(x.bonds->shear_strength, y.bonds->shear_strength);
      EXPECT_EQ(x.bonds->friction_angle, y.bonds->friction_angle);
      EXPECT_EQ(x.bonds->points_per_face, y.bonds->points_per_face);
      EXPECT_EQ(x.bonds->damping_ratio, y.bonds->damping_ratio);
    }
  }
  ASSERT_EQ(a.channel.has_value(), b.channel.has_value());
  if (a.channel) {
    const ChannelSpec &x = *a.channel, &y = *b.channel;
    EXPECT_EQ(x.basin_x_min, y.basin_x_min);
    EXPECT_EQ(x.basin_x_max, y.basin_x_max);
    EXPECT_EQ(x.basin_y_min, y.basin_y_min);
    EXPECT_EQ(x.basin_y_max, y.basin_y_max);
    EXPECT_EQ(x.funnel_length, y.funnel_length);
    EXPECT_EQ(x.opening, y.opening);
    EXPECT_EQ(x.strait_length, y.strait_length);
    EXPECT_EQ(x.wall_thickness, y.wall_thickness);
    EXPECT_EQ(x.jam_window, y.jam_window);
    EXPECT_EQ(x.jam_speed, y.jam_speed);
  }
}

inline void expect_round_trip(const Scene& s) {
  const std::string text = resolved_yaml(s);
  SCOPED_TRACE(text);
  const Scene back = parse_scene(text, "resolved.yaml", {});
  expect_same_settings(s, back);
}

}  // namespace polyfloe::scene
