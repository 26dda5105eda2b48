// The scene's settings, declared once (internal to dem/scene): each block lists its keys in order, each with the
// member it sets, its unit and allowed range, and the comment the resolved scene gives it (the default is the
// member's initial value in scene.h). Several visitors walk the same declaration:
//   - MapReader (schema.h) reads and checks the YAML tree (its after() hooks check across keys once a block is read);
//   - SettingsWriter (resolved_yaml.cpp) writes the resolved scene, one key per line with its comment;
//   - KeyLister (scene_keys.cpp) lists every key with its unit and choices, for `docs/scene-reference.md`'s check
//     and the tests' comparator.
// A visitor provides number, number_or_auto, zero_is_auto, integer, unsigned64, boolean, name, vec2, vec3, choice,
// block, flow (a block the resolved scene writes on one line), optional_block, custom (a key with its own reader
// and writer: lists, boxes, fields) and after. The writer visits the resolved Scene through these same non-const
// references and never changes it.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <ostream>
#include <optional>
#include <string>
#include <vector>

#include "scene/channel.h"
#include "scene/schema.h"
#include "scene/yaml_format.h"

namespace polyfloe::scene::detail {

// The keys with readers and writers of their own (defined beside the other readers, and in resolved_yaml.cpp); a
// writer writes the key's lines, the one-line ones with the comment the declaration gives.
void read_region(MapReader& m, const char* key, std::optional<std::array<double, 4>>& region);  // box or 'auto'
void write_region(std::ostream& o, const std::string& indent, const char* key, const char* comment,
                  const std::optional<std::array<double, 4>>& region);
struct Box {  // a rectangle given as two corners [m]
  Vec2& min;
  Vec2& max;
};
void read_box(MapReader& m, const char* key, Box& box);
void write_box(std::ostream& o, const std::string& indent, const char* key, const char* comment, const Box& box);
void read_corners(MapReader& m, const char* key, FloeFieldSpec& f);
void write_corners(std::ostream& o, const std::string& indent, const char* key, const char* comment,
                   const FloeFieldSpec& f);
void read_floes(MapReader& m, const char* key, std::vector<BodySpec>& bodies);
void write_floes(std::ostream& o, const std::string& indent, const char* key, const char* comment,
                 const std::vector<BodySpec>& bodies);
void read_spatial_bodies(MapReader& m, const char* key, std::vector<SpatialBodySpec>& bodies);
void write_spatial_bodies(std::ostream& o, const std::string& indent, const char* key, const char* comment,
                          const std::vector<SpatialBodySpec>& bodies);
// 'current' / 'wind' (a uniform velocity, `shorthand`) or 'field' (a field block of any kind), not both.
struct Velocity {
  const char* shorthand;
  forcing::FieldSpec& spec;
};
void read_velocity(MapReader& m, const char* key, Velocity& v);
void write_velocity(std::ostream& o, const std::string& indent, const char* key, const char* comment,
                    const Velocity& v);

template <class V>
void run_keys(V& v, TimeSettings& t) {
  v.number("duration", t.duration, positive("s"), "simulated time");
  v.number_or_auto("dt", t.dt, positive("s"), "time step; auto = shortest contact duration / steps_per_contact");
  v.number("steps_per_contact", t.steps_per_contact, at_least(dynamics::kMinStepsPerContact, "-"), "");
  v.number_or_auto("steps_per_flat_contact", t.steps_per_flat_contact, at_least(dynamics::kMinStepsPerContact, "-"),
                   "foundation model: time steps per flat face's contact; auto = steps_per_contact");
  v.number_or_auto("reference_speed", t.reference_speed, positive("m/s"),
                   "impact speed; auto = max(1 m/s, free-drift speed)");
}

template <class V>
void velocity_grid_keys(V& v, VelocityGridSettings& g) {
  v.boolean("enabled", g.enabled, "");
  v.number("cell", g.cell, positive("m"), "");
  v.custom("region", g.region, "[m] xmin, ymin, xmax, ymax", read_region, write_region);
  v.integer("samples_per_frame", g.samples_per_frame, 1, 1000, "");
  v.after([&g](MapReader& m) {
    if (!g.region) return;  // the automatic region is checked when the world is built
    const auto& r = *g.region;
    const double cells = std::ceil((r[2] - r[0]) / g.cell) * std::ceil((r[3] - r[1]) / g.cell);
    if (cells > VelocityGridSettings::kMaxCells) {
      const auto f = m.take("cell");
      m.context().fail(f ? *f : m.self(), "the velocity grid would have " + fmt(cells) + " cells (at most " +
                                              fmt(VelocityGridSettings::kMaxCells) +
                                              "): raise output.velocity_grid.cell or shrink its region");
    }
  });
}

template <class V>
void output_keys(V& v, OutputSettings& o) {
  v.number("interval", o.interval, positive("s"), "simulated time between frames");
  v.boolean("vtk", o.vtk, "");
  v.boolean("contacts", o.contacts, "");
  v.boolean("vtk_pieces", o.vtk_pieces, "one piece per MPI rank");
  v.boolean("hdf5", o.hdf5, "");
  v.block("velocity_grid", [&](V& g) { velocity_grid_keys(g, o.velocity_grid); });
  v.block("checkpoint", [&](V& c) {
    c.integer("every", o.checkpoint.every, 0, 100000, "[frames] 0 = no checkpoints");
    c.integer("keep", o.checkpoint.keep, 1, 1000, "newest checkpoints kept");
  });
  v.after([&o](MapReader& m) {  // pieces of frames that are not written: refused, not ignored
    if (!o.vtk_pieces || o.vtk) return;
    const auto f = m.take("vtk_pieces");
    m.context().fail(f ? *f : m.self(),
                     "output.vtk_pieces is true but output.vtk is false: no VTK frames are written to cut into "
                     "pieces; set output.vtk: true, or remove output.vtk_pieces");
  });
}

template <class V>
void ice_keys(V& v, Scene& s) {
  // Bounds that keep every derived quantity (contact stiffness, duration, the automatic step) a normal double.
  v.number("density", s.ice_density, closed(1.0, 1e5, "kg/m^3"), "");
  v.number("youngs_modulus", s.world.contact.youngs_modulus, closed(1e3, 1e13, "Pa"), "");
  v.number("poisson_ratio", s.world.contact.poisson_ratio, Range{0.0, 0.5, false, true, "-"}, "");
}

// `level_floes`: the planar world's keys (narrow_phase, force_model); a spatial scene has neither (the reader refuses
// them there; a spatial scene's resolved text leaves them out).
template <class V>
void contact_keys(V& v, dynamics::WorldSettings& w, bool level_floes) {
  v.number("restitution", w.contact.restitution, Range{0.0, 1.0, true, false, "-"}, "");
  v.number("friction", w.contact.friction, closed(0.0, 10.0, "-"), "Coulomb coefficient");
  v.choice("damping_model", w.contact.damping,
           {{"speed_independent", contact::DampingModel::speed_independent}, {"paper", contact::DampingModel::paper}},
           "");
  if (level_floes) {
    v.choice("narrow_phase", w.narrow_phase,
             {{"exact", dynamics::PlanarNarrowPhase::exact}, {"gjk_epa", dynamics::PlanarNarrowPhase::gjk_epa}},
             "level floes: exact overlap polygon, or the paper's GJK-EPA (comparison)");
    v.choice("force_model", w.contact.force_model,
             {{"centroid", contact::ForceModel::centroid},
              {"gradient", contact::ForceModel::gradient},
              {"foundation", contact::ForceModel::foundation}},
             "");
  }
  v.zero_is_auto("broad_phase_cell", w.broad_phase_cell, positive("m"), "");
  v.zero_is_auto("broad_phase_skin", w.broad_phase_skin, positive("m"),
                 "speed only: the contacts are the same for any value");
  v.after([&w](MapReader& m) {
    if (w.contact.force_model == contact::ForceModel::foundation &&
        w.narrow_phase == dynamics::PlanarNarrowPhase::gjk_epa) {
      const auto f = m.take("narrow_phase");
      m.context().fail(f ? *f : m.self(),
                       "force_model 'foundation' integrates over the overlap polygon, which only "
                       "the 'exact' narrow phase finds: set narrow_phase: exact, or another force_model");
    }
  });
}

// A drag term: {enabled, coefficient}.
template <class V>
void term_keys(V& v, const char* key, bool& enabled, double& coefficient, const Range& range, const char* doc) {
  v.flow(key, doc, [&](V& t) {
    t.boolean("enabled", enabled, "");
    t.number("coefficient", coefficient, range, "");
  });
}

template <class V>
void forcing_keys(V& v, Scene& s) {
  forcing::DriftSettings& d = s.world.drift;
  v.choice(
      "treatment", d.treatment,
      {{"semi_implicit", forcing::DriftTreatment::semi_implicit}, {"explicit", forcing::DriftTreatment::explicit_step}},
      "drag and Coriolis in the step");
  v.choice("quadrature", d.quadrature,
           {{"centroid", forcing::Quadrature::centroid},
            {"degree1", forcing::Quadrature::degree1},
            {"degree2", forcing::Quadrature::degree2},
            {"degree4", forcing::Quadrature::degree4},
            {"degree5", forcing::Quadrature::degree5}},
           "bottom and top drag integrals");
  v.integer("update_every", d.update_every, 1, 1000, "[-] steps per full drift evaluation (between: its linear model)");
  v.block("ocean", [&](V& o) {
    o.number("density", d.water_density, positive("kg/m^3"), "");
    Velocity current{"current", s.ocean_field};
    o.custom("field", current, "[m], [m/s], [1/s], [s]", read_velocity, write_velocity);
    term_keys(o, "form_drag", d.form_drag, d.form_drag_coefficient, closed(0.0, 10.0, "-"), "C_d^F [-]");
    term_keys(o, "moment_drag", d.moment_drag, d.moment_drag_coefficient, closed(0.0, 10.0, "-"), "C_d^M [-]");
    term_keys(o, "skin_drag", d.skin_drag, d.skin_drag_coefficient, closed(0.0, 1.0, "-"), "c_w [-]");
  });
  v.block("air", [&](V& a) {
    a.number("density", d.air_density, positive("kg/m^3"), "");
    Velocity wind{"wind", s.wind_field};
    a.custom("field", wind, "", read_velocity, write_velocity);
    term_keys(a, "drag", d.air_drag, d.air_drag_coefficient, closed(0.0, 1.0, "-"), "c_a [-]");
  });
  v.flow("coriolis", "[deg], [m]", [&](V& c) {
    c.boolean("enabled", d.coriolis, "");
    c.number("latitude", d.latitude, closed(-90.0, 90.0, "deg"), "");
    c.boolean("beta_plane", d.beta_plane, "");
    c.number("reference_y", d.reference_y, any("m"), "");
  });
  v.after([&s, &d](MapReader& m) {
    if (d.update_every > 1 && d.treatment != forcing::DriftTreatment::semi_implicit)
      m.context().fail(*m.take("update_every"),
                       "update_every = " + std::to_string(d.update_every) +
                           " needs forcing.treatment: semi_implicit (the steps between full evaluations use its "
                           "linear model); use 1 with treatment: explicit");
    d.ocean = forcing::make_field(s.ocean_field);
    d.wind = forcing::make_field(s.wind_field);
  });
}

template <class V>
void floe_field_keys(V& v, FloeFieldSpec& s) {
  Box region{s.region_min, s.region_max};
  v.custom("region", region, "[m] xmin, ymin, xmax, ymax", read_box, write_box);
  v.number("concentration", s.concentration, Range{0.0, 0.7, true, false, "-"}, "ice area / region area");
  v.flow("size", "[m], [m], [-]; size = diameter of the area-equivalent circle", [&](V& z) {
    // From a centimetre to 100 km: beyond, areas under- or overflow and no contact resolves.
    z.number("min", s.size_min, closed(FloeFieldSpec::kMinSize, FloeFieldSpec::kMaxSize, "m"), "");
    z.number("max", s.size_max, closed(FloeFieldSpec::kMinSize, FloeFieldSpec::kMaxSize, "m"), "");
    z.number("exponent", s.exponent, closed(0.0, 10.0, "-"), "");
    z.after([&s](MapReader& m) {
      if (s.size_max < s.size_min) {
        const auto f = m.take("max");
        m.context().fail(f ? *f : *m.take("min"),
                         "size.max = " + fmt(s.size_max) + " m must be >= size.min = " + fmt(s.size_min) + " m");
      }
    });
  });
  v.custom("corners", s, "[-]", read_corners, write_corners);
  v.choice("shape", s.shape, {{"ellipse", FloeShape::ellipse}, {"voronoi", FloeShape::voronoi}}, "");
  v.number("aspect_max", s.aspect_max, closed(1.0, 10.0, "-"), "ellipse shapes: axis ratio uniform in [1, aspect_max]");
  v.number("thickness", s.thickness, positive("m"), "");
  v.vec2("velocity", s.velocity, "m/s", "");
  v.unsigned64("seed", s.seed, "");
  v.integer("max_attempts", s.max_attempts, 1, 1000000000, "[-] placement tries per floe");
  v.after([&s](MapReader& m) { s.source.where = m.context().where(m.self()); });
}

template <class V>
void bond_keys(V& v, SheetBondSpec& b) {
  v.number("tensile_strength", b.tensile_strength, positive("Pa"), "");
  v.number("shear_strength", b.shear_strength, positive("Pa"), "Mohr-Coulomb cohesion");
  v.number("friction_angle", b.friction_angle, Range{0.0, 0.5 * std::numbers::pi, false, true, "rad"}, "");
  v.integer("points_per_face", b.points_per_face, 2, 64, "");
  v.number("damping_ratio", b.damping_ratio, closed(0.0, 10.0, "-"), "");
}

template <class V>
void ice_sheet_keys(V& v, IceSheetSpec& s) {
  Box region{s.region_min, s.region_max};
  v.custom("region", region, "[m] xmin, ymin, xmax, ymax", read_box, write_box);
  v.number("cell_size", s.cell_size, positive("m"), "diameter of the circle of the mean cell area");
  v.integer("relaxation", s.relaxation, 0, 1000, "[-] Lloyd iterations");
  v.number("thickness", s.thickness, positive("m"), "");
  v.vec2("velocity", s.velocity, "m/s", "");
  v.unsigned64("seed", s.seed, "");
  v.choice("elements", s.elements, {{"cells", SheetElements::cells}, {"triangles", SheetElements::triangles}}, "");
  v.optional_block("bonds", s.bonds, [](V& b, SheetBondSpec& bond) { bond_keys(b, bond); });
  v.after([&s](MapReader& m) {
    s.source.where = m.context().where(m.self());
    const double cells = (s.region_max - s.region_min).prod() / (0.25 * std::numbers::pi * s.cell_size * s.cell_size);
    if (cells > IceSheetSpec::kMaxCells) {
      const auto f = m.take("cell_size");
      m.context().fail(f ? *f : m.self(), "the region holds " + fmt(std::round(cells)) +
                                              " cells of this size (at most " + fmt(IceSheetSpec::kMaxCells) +
                                              "): raise ice_sheet.cell_size or shrink its region");
    }
  });
}

template <class V>
void channel_keys(V& v, ChannelSpec& c) {
  v.number("basin_x_min", c.basin_x_min, any("m"), "");
  v.number("basin_x_max", c.basin_x_max, any("m"), "");
  v.number("basin_y_min", c.basin_y_min, any("m"), "");
  v.number("basin_y_max", c.basin_y_max, any("m"), "");
  v.number("funnel_length", c.funnel_length, positive("m"), "");
  v.number("opening", c.opening, positive("m"), "");
  v.number("strait_length", c.strait_length, positive("m"), "");
  v.number("wall_thickness", c.wall_thickness, positive("m"), "");
  v.number("jam_window", c.jam_window, positive("s"), "jammed: no ice through the strait entrance this long");
  v.number("jam_speed", c.jam_speed, positive("m/s"), "... with the funnel's ice slower than this");
  v.after([&c](MapReader& m) {
    c.source.where = m.context().where(m.self());
    if (const std::optional<SpecIssue> issue = channel_issue(c)) {
      const auto f = m.take(issue->key.c_str());
      m.context().fail(f ? *f : Field{m.self().value, m.self().key, join(m.self().path, issue->key)}, issue->message);
    }
  });
}

template <class V>
void spatial_keys(V& v, SpatialSpec& s) {
  v.vec3("gravity", s.gravity, "m/s^2", "");
  v.boolean("buoyancy", s.buoyancy, "");
  v.number("water_level", s.water_level, any("m"), "");
  v.number("water_density", s.water_density, closed(1.0, 1e5, "kg/m^3"), "");
  v.choice("narrow_phase", s.narrow_phase,
           {{"sat", dynamics::SpatialNarrowPhase::sat},
            {"gjk_epa_tiebreak", dynamics::SpatialNarrowPhase::gjk_epa_tiebreak},
            {"gjk_epa", dynamics::SpatialNarrowPhase::gjk_epa},
            {"mpr", dynamics::SpatialNarrowPhase::mpr}},
           "");
  v.choice("contact_point", s.contact_point,
           {{"witness", dynamics::ContactPointModel::witness}, {"manifold", dynamics::ContactPointModel::manifold}},
           "");
  v.custom("bodies", s.bodies, "", read_spatial_bodies, write_spatial_bodies);
  v.after([&s](MapReader& m) {
    s.source.where = m.context().where(m.self());
    if (s.buoyancy && !(s.gravity.norm() > 0.0))
      m.context().fail(*m.take("buoyancy"),
                       "buoyancy needs gravity (Archimedes' force is the weight of the displaced water): "
                       "give spatial.gravity, for example [0, 0, -9.81]");
    if (std::none_of(s.bodies.begin(), s.bodies.end(),
                     [](const SpatialBodySpec& b) { return b.motion == dynamics::Motion::dynamic; }))
      m.context().fail(m.self(), "a spatial scene needs at least one body with motion: dynamic under 'spatial.bodies'");
  });
}

// The whole scene. A spatial scene has neither forcing nor floes: the reader meets 'spatial' last (it refuses
// both afterwards), the resolved scene leaves them out.
template <class V>
void scene_keys(V& v, Scene& s) {
  v.name("name", s.name, "");
  v.block("run", [&](V& b) { run_keys(b, s.time); });
  v.block("output", [&](V& b) { output_keys(b, s.output); });
  v.block("ice", [&](V& b) { ice_keys(b, s); });
  v.block("contact", [&](V& b) { contact_keys(b, s.world, !s.spatial); });
  if (!s.spatial) {
    v.block("forcing", [&](V& b) { forcing_keys(b, s); });
    v.custom("floes", s.bodies, "", read_floes, write_floes);
  }
  v.optional_block("floe_field", s.floe_field, [](V& b, FloeFieldSpec& f) { floe_field_keys(b, f); });
  v.optional_block("ice_sheet", s.ice_sheet, [](V& b, IceSheetSpec& i) { ice_sheet_keys(b, i); });
  v.optional_block("channel", s.channel, [](V& b, ChannelSpec& c) { channel_keys(b, c); });
  v.optional_block("spatial", s.spatial, [](V& b, SpatialSpec& p) { spatial_keys(b, p); });
}

}  // namespace polyfloe::scene::detail
