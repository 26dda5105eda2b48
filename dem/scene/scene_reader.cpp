// The scene schema, one read_*() function per block, on the schema walker of schema.h; --set overrides.
#include "scene/scene_reader.h"

#include <yaml-cpp/depthguard.h>
#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cerrno>
#include <charconv>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <limits>
#include <map>
#include <optional>
#include <numbers>
#include <iomanip>
#include <sstream>
#include <utility>

#include "contact/narrow_phase_planar.h"
#include "geometry/polygon.h"
#include "scene/channel.h"
#include "scene/forcing_reader.h"
#include "scene/yaml_format.h"
#include "scene/yaml_limits.h"

namespace polyfloe::scene {

using detail::fmt;
using detail::quoted;

namespace {

using namespace detail;


// ---------------------------------------------------------------------------------------------------------------
// The schema, one block per function

void read_run(MapReader m, TimeSettings& t) {
  m.number("duration", t.duration, positive("s"));
  m.number_or_auto("dt", t.dt, positive("s"));
  m.number("steps_per_contact", t.steps_per_contact, at_least(dynamics::kMinStepsPerContact, "-"));
  m.number_or_auto("reference_speed", t.reference_speed, positive("m/s"));
  m.finish();
}

// A rectangle [xmin, ymin, xmax, ymax] [m] with xmax > xmin and ymax > ymin.
std::array<double, 4> to_box(const Context& ctx, const Field& f) {
  const std::string what = "a list of 4 numbers [xmin, ymin, xmax, ymax] [m]";
  const std::vector<Field> items = list_items(ctx, f, what);
  if (items.size() != 4) ctx.fail(f, "expected " + what + ", got " + describe(f.value));
  std::array<double, 4> r{};
  for (std::size_t i = 0; i < 4; ++i) r[i] = to_number(ctx, items[i], any("m"));
  if (!(r[2] > r[0])) ctx.fail(items[2], "xmax = " + fmt(r[2]) + " must be > xmin = " + fmt(r[0]) + " [m]");
  if (!(r[3] > r[1])) ctx.fail(items[3], "ymax = " + fmt(r[3]) + " must be > ymin = " + fmt(r[1]) + " [m]");
  return r;
}

void read_velocity_grid(MapReader m, VelocityGridSettings& g) {
  const Context& ctx = m.context();
  m.boolean("enabled", g.enabled);
  m.number("cell", g.cell, positive("m"));
  if (auto f = m.take("region")) {
    if (is_word(f->value, "auto")) g.region.reset();
    else g.region = to_box(ctx, *f);
  }
  m.integer("samples_per_frame", g.samples_per_frame, 1, 1000);
  if (g.region) {  // the automatic region is checked when the world is built
    const double cells = std::ceil(((*g.region)[2] - (*g.region)[0]) / g.cell) *
                         std::ceil(((*g.region)[3] - (*g.region)[1]) / g.cell);
    if (cells > VelocityGridSettings::kMaxCells) {
      const auto f = m.take("cell");
      ctx.fail(f ? *f : m.self(), "the velocity grid would have " + fmt(cells) + " cells (at most " +
                                      fmt(VelocityGridSettings::kMaxCells) + "): raise output.velocity_grid.cell or shrink its region");
    }
  }
  m.finish();
}

void read_output(MapReader m, OutputSettings& o) {
  m.number("interval", o.interval, positive("s"));
  m.boolean("vtk", o.vtk);
  m.boolean("contacts", o.contacts);
  m.boolean("hdf5", o.hdf5);
  read_velocity_grid(m.block("velocity_grid"), o.velocity_grid);
  {
    MapReader c = m.block("checkpoint");
    c.integer("every", o.checkpoint.every, 0, 100000);
    c.integer("keep", o.checkpoint.keep, 1, 1000);
    c.finish();
  }
  m.finish();
}

void read_ice(MapReader m, Scene& s) {
  // Bounds that keep every derived quantity (contact stiffness, duration, the automatic step) a normal double.
  m.number("density", s.ice_density, closed(1.0, 1e5, "kg/m^3"));
  m.number("youngs_modulus", s.world.contact.youngs_modulus, closed(1e3, 1e13, "Pa"));
  m.number("poisson_ratio", s.world.contact.poisson_ratio, Range{0.0, 0.5, false, true, "-"});
  m.finish();
}

void read_contact(MapReader m, dynamics::WorldSettings& w) {
  m.number("restitution", w.contact.restitution, Range{0.0, 1.0, true, false, "-"});
  m.number("friction", w.contact.friction, closed(0.0, 10.0, "-"));
  m.choice("damping_model", w.contact.damping,
           {{"speed_independent", contact::DampingModel::speed_independent},
            {"paper", contact::DampingModel::paper}});
  m.choice("narrow_phase", w.narrow_phase,
           {{"exact", dynamics::PlanarNarrowPhase::exact}, {"gjk_epa", dynamics::PlanarNarrowPhase::gjk_epa}});
  m.choice("force_model", w.contact.force_model,
           {{"centroid", contact::ForceModel::centroid}, {"gradient", contact::ForceModel::gradient}});
  std::optional<double> cell;
  if (w.broad_phase_cell > 0.0) cell = w.broad_phase_cell;
  m.number_or_auto("broad_phase_cell", cell, positive("m"));
  w.broad_phase_cell = cell.value_or(0.0);
  std::optional<double> skin;
  if (w.broad_phase_skin > 0.0) skin = w.broad_phase_skin;
  m.number_or_auto("broad_phase_skin", skin, positive("m"));
  w.broad_phase_skin = skin.value_or(0.0);
  m.finish();
}

// One explicit body: exactly one of polygon / regular / rectangle.
BodySpec read_body(MapReader m) {
  const Context& ctx = m.context();
  BodySpec b;
  b.source.where = ctx.where(m.self());
  const int shapes = int(m.has("polygon")) + int(m.has("regular")) + int(m.has("rectangle"));
  if (shapes != 1)
    ctx.fail(m.self(), shapes == 0 ? "missing the shape: give one of 'polygon', 'regular' or 'rectangle'"
                                   : "give only one of 'polygon', 'regular' or 'rectangle'");
  const bool given_polygon = m.has("polygon");
  if (auto f = m.take("polygon")) b.polygon = to_polygon(ctx, *f);
  {
    MapReader r = m.block("regular");
    if (m.has("regular")) {
      const auto fs = r.take("sides");
      const auto fr = r.take("radius");
      if (!fs || !fr) ctx.fail(r.self(), std::string("missing required key '") + (fs ? "radius" : "sides") + "'");
      const int sides = static_cast<int>(to_integer(ctx, *fs, 3, contact::kMaxPolygonVertices));
      const double radius = to_number(ctx, *fr, positive("m"));  // circumradius [m]
      for (int i = 0; i < sides; ++i) {
        const double a = 2.0 * std::numbers::pi * i / sides;
        b.polygon.emplace_back(radius * std::cos(a), radius * std::sin(a));
      }
      if (const std::string err = geometry::convexity_error(b.polygon); !err.empty())
        ctx.fail(r.self(), "the regular polygon's outline is unusable: " + err);
    }
    r.finish();
  }
  {
    MapReader r = m.block("rectangle");
    if (m.has("rectangle")) {
      const auto fw = r.take("width");
      const auto fh = r.take("height");
      if (!fw || !fh) ctx.fail(r.self(), std::string("missing required key '") + (fw ? "height" : "width") + "'");
      const double hx = 0.5 * to_number(ctx, *fw, positive("m")), hy = 0.5 * to_number(ctx, *fh, positive("m"));
      b.polygon = {{-hx, -hy}, {hx, -hy}, {hx, hy}, {-hx, hy}};
      // The same check as a polygon's (an outline that would not read back, or build, is refused here).
      if (const std::string err = geometry::convexity_error(b.polygon); !err.empty())
        ctx.fail(r.self(), "the rectangle's outline is unusable: " + err +
                               " (width and height must be within a factor 1e9 of each other, each in [1e-60, 1e60] m)");
    }
    r.finish();
  }
  // coordinates: world keeps a polygon where its vertices are in the scene (a coastline or a CFD wall copied as
  // it is): the body goes where the polygon's centroid is, unrotated.
  bool world_frame = false;
  if (const auto fc = m.take("coordinates")) {
    const std::string c = fc->value.IsScalar() ? fc->value.Scalar() : std::string();
    if (c != "body" && c != "world") ctx.fail(*fc, "expected body or world, got " + describe(fc->value));
    world_frame = c == "world";
    if (world_frame && !given_polygon)
      ctx.fail(*fc, "coordinates: world places a 'polygon' given in scene coordinates; 'regular' and 'rectangle' "
                    "are centred shapes: give their 'position'");
    for (const char* k : {"position", "yaw", "yaw_deg"})
      if (world_frame && m.has(k))
        ctx.fail(*fc, std::string("coordinates: world takes the body's place from its polygon: remove '") + k + "'");
  }
  if (world_frame) {
    Vec2 centre{0.0, 0.0};
    (void)geometry::ConvexPolygon::from_vertices(b.polygon, &centre);
    b.position = centre;
  }
  m.vec2("position", b.position, "m");
  if (m.has("yaw") && m.has("yaw_deg")) ctx.fail(m.self(), "give only one of 'yaw' [rad] and 'yaw_deg' [deg]");
  m.number("yaw", b.yaw, any("rad"));
  double yaw_deg = 0.0;
  if (m.number("yaw_deg", yaw_deg, any("deg"))) b.yaw = yaw_deg * std::numbers::pi / 180.0;
  m.vec2("velocity", b.velocity, "m/s");
  m.number("angular_velocity", b.angular_velocity, any("rad/s"));
  m.number("thickness", b.thickness, positive("m"));
  m.choice("motion", b.motion,
           {{"dynamic", dynamics::Motion::dynamic},
            {"fixed", dynamics::Motion::fixed},
            {"kinematic", dynamics::Motion::kinematic}});
  m.optional_unsigned64("id", b.id);
  m.vec2("external_force", b.external_force, "N");
  m.number("external_torque", b.external_torque, any("N m"));
  m.finish();
  return b;
}

void read_floes(const Context& ctx, const Field& f, std::vector<BodySpec>& bodies) {
  if (!f.value.IsDefined() || f.value.IsNull()) return;
  std::map<std::uint64_t, std::size_t> first_with_id;  // id -> the floe that gave it first
  for (const Field& item : list_items(ctx, f, "a list of floes (each a block of keys)")) {
    bodies.push_back(read_body(MapReader(ctx, item)));
    if (const auto id = bodies.back().id) {
      const auto [it, fresh] = first_with_id.emplace(*id, bodies.size() - 1);
      if (!fresh)
        ctx.fail({static_cast<const YAML::Node&>(item.value)["id"], YAML::Node(), join(item.path, "id")},
                 "id " + std::to_string(*id) + " is already used by " + f.path + "." + std::to_string(it->second) +
                     " (" + bodies[it->second].source.where + ")");
    }
  }
}

FloeFieldSpec read_floe_field(MapReader m) {
  const Context& ctx = m.context();
  FloeFieldSpec s;
  s.source.where = ctx.where(m.self());
  if (auto f = m.take("region")) {
    const std::array<double, 4> r = to_box(ctx, *f);
    s.region_min = {r[0], r[1]};
    s.region_max = {r[2], r[3]};
  }
  m.number("concentration", s.concentration, Range{0.0, 0.7, true, false, "-"});
  {
    MapReader size = m.block("size");
    // From a centimetre to 100 km: beyond, areas under- or overflow and no contact resolves.
    size.number("min", s.size_min, closed(FloeFieldSpec::kMinSize, FloeFieldSpec::kMaxSize, "m"));
    size.number("max", s.size_max, closed(FloeFieldSpec::kMinSize, FloeFieldSpec::kMaxSize, "m"));
    size.number("exponent", s.exponent, closed(0.0, 10.0, "-"));
    if (s.size_max < s.size_min) {
      const auto f = size.take("max");
      ctx.fail(f ? *f : *size.take("min"),
               "size.max = " + fmt(s.size_max) + " m must be >= size.min = " + fmt(s.size_min) + " m");
    }
    size.finish();
  }
  if (auto f = m.take("corners")) {
    const int hi = contact::kMaxPolygonVertices;
    if (f->value.IsSequence()) {
      const std::vector<Field> items = list_items(ctx, *f, "[min, max]");
      if (items.size() != 2) ctx.fail(*f, "expected a list [min, max] of corner counts, got " + describe(f->value));
      s.corners_min = static_cast<int>(to_integer(ctx, items[0], 3, hi));
      s.corners_max = static_cast<int>(to_integer(ctx, items[1], 3, hi));
      if (s.corners_max < s.corners_min)
        ctx.fail(items[1], "max = " + std::to_string(s.corners_max) + " must be >= min = " +
                               std::to_string(s.corners_min));
    } else {
      s.corners_min = s.corners_max = static_cast<int>(to_integer(ctx, *f, 3, hi));
    }
  }
  m.choice("shape", s.shape, {{"ellipse", FloeShape::ellipse}, {"voronoi", FloeShape::voronoi}});
  m.number("aspect_max", s.aspect_max, closed(1.0, 10.0, "-"));
  m.number("thickness", s.thickness, positive("m"));
  m.vec2("velocity", s.velocity, "m/s");
  m.unsigned64("seed", s.seed);
  m.integer("max_attempts", s.max_attempts, 1, 1000000000);
  m.finish();
  return s;
}

ChannelSpec read_channel(MapReader m) {
  const Context& ctx = m.context();
  ChannelSpec c;
  c.source.where = ctx.where(m.self());
  m.number("basin_x_min", c.basin_x_min, any("m"));
  m.number("basin_x_max", c.basin_x_max, any("m"));
  m.number("basin_y_min", c.basin_y_min, any("m"));
  m.number("basin_y_max", c.basin_y_max, any("m"));
  m.number("funnel_length", c.funnel_length, positive("m"));
  m.number("opening", c.opening, positive("m"));
  m.number("strait_length", c.strait_length, positive("m"));
  m.number("wall_thickness", c.wall_thickness, positive("m"));
  m.number("jam_window", c.jam_window, positive("s"));
  m.number("jam_speed", c.jam_speed, positive("m/s"));
  m.finish();
  if (const std::optional<SpecIssue> issue = channel_issue(c)) {
    const auto f = m.take(issue->key.c_str());
    ctx.fail(f ? *f : Field{m.self().value, m.self().key, join(m.self().path, issue->key)}, issue->message);
  }
  return c;
}

IceSheetSpec read_ice_sheet(MapReader m) {
  const Context& ctx = m.context();
  IceSheetSpec s;
  s.source.where = ctx.where(m.self());
  if (auto f = m.take("region")) {
    const std::array<double, 4> r = to_box(ctx, *f);
    s.region_min = {r[0], r[1]};
    s.region_max = {r[2], r[3]};
  }
  m.number("cell_size", s.cell_size, positive("m"));
  m.integer("relaxation", s.relaxation, 0, 1000);
  m.number("thickness", s.thickness, positive("m"));
  m.vec2("velocity", s.velocity, "m/s");
  m.unsigned64("seed", s.seed);
  m.choice("elements", s.elements, {{"cells", SheetElements::cells}, {"triangles", SheetElements::triangles}});
  if (auto b = m.optional_block("bonds")) {
    SheetBondSpec bond;
    b->number("tensile_strength", bond.tensile_strength, positive("Pa"));
    b->number("shear_strength", bond.shear_strength, positive("Pa"));
    b->number("friction_angle", bond.friction_angle, Range{0.0, 0.5 * std::numbers::pi, false, true, "rad"});
    b->integer("points_per_face", bond.points_per_face, 2, 64);
    b->number("damping_ratio", bond.damping_ratio, closed(0.0, 10.0, "-"));
    b->finish();
    s.bonds = bond;
  }
  const double cells = (s.region_max - s.region_min).prod() / (0.25 * std::numbers::pi * s.cell_size * s.cell_size);
  if (cells > IceSheetSpec::kMaxCells) {
    const auto f = m.take("cell_size");
    ctx.fail(f ? *f : m.self(), "the region holds " + fmt(std::round(cells)) + " cells of this size (at most " +
                                    fmt(IceSheetSpec::kMaxCells) + "): raise ice_sheet.cell_size or shrink its region");
  }
  m.finish();
  return s;
}

geometry::Vec3 to_vec3(const Context& ctx, const Field& f, const Range& r) {
  const std::string what = "a list of 3 numbers [x, y, z] [" + std::string(r.unit) + "]";
  const std::vector<Field> items = list_items(ctx, f, what);
  if (items.size() != 3) ctx.fail(f, "expected " + what + ", got " + describe(f.value));
  return {to_number(ctx, items[0], r), to_number(ctx, items[1], r), to_number(ctx, items[2], r)};
}

// One spatial body: exactly one of box / polygon (+ thickness).
SpatialBodySpec read_spatial_body(MapReader m) {
  const Context& ctx = m.context();
  SpatialBodySpec b;
  b.source.where = ctx.where(m.self());
  if (m.has("box") == m.has("polygon"))
    ctx.fail(m.self(), m.has("box") ? "give only one of 'box' and 'polygon'"
                                    : "missing the shape: give 'box: [lx, ly, lz]' or 'polygon' (with 'thickness')");
  if (auto f = m.take("box")) {
    b.box = to_vec3(ctx, *f, positive("m"));
    const double lo = b.box->minCoeff(), hi = b.box->maxCoeff();
    if (!(hi <= 1e9 * lo) || lo < geometry::kMinPolygonSize || hi > 1e30)
      ctx.fail(*f, "box edge lengths must lie in [1e-60, 1e30] m and within a factor 1e9 of each other");
  }
  if (auto f = m.take("polygon")) b.polygon = to_polygon(ctx, *f);
  m.number("thickness", b.thickness, positive("m"));
  if (auto f = m.take("position")) b.position = to_vec3(ctx, *f, any("m"));
  if (auto r = m.optional_block("rotation")) {
    const Context& c = r->context();
    if (auto f = r->take("axis")) b.rotation_axis = to_vec3(c, *f, any("-"));
    if (!(b.rotation_axis.norm() > 0.0) || !std::isfinite(b.rotation_axis.norm()))
      c.fail(r->self(), "rotation.axis must be a finite, non-zero vector");
    if (r->has("angle") && r->has("angle_deg")) c.fail(r->self(), "give only one of 'angle' [rad] and 'angle_deg' [deg]");
    r->number("angle", b.rotation_angle, any("rad"));
    double deg = 0.0;
    if (r->number("angle_deg", deg, any("deg"))) b.rotation_angle = deg * std::numbers::pi / 180.0;
    if (r->has("axis") && !r->has("angle") && !r->has("angle_deg"))
      c.fail(*r->take("axis"), "a rotation about this axis needs its angle: give rotation.angle [rad] or "
                               "rotation.angle_deg [deg]");
    r->finish();
  }
  if (auto f = m.take("velocity")) b.velocity = to_vec3(ctx, *f, any("m/s"));
  if (auto f = m.take("angular_velocity")) b.angular_velocity = to_vec3(ctx, *f, any("rad/s"));
  double density = 0.0;
  if (m.number("density", density, positive("kg/m^3"))) b.density = density;
  m.choice("motion", b.motion,
           {{"dynamic", dynamics::Motion::dynamic},
            {"fixed", dynamics::Motion::fixed},
            {"kinematic", dynamics::Motion::kinematic}});
  m.optional_unsigned64("id", b.id);
  m.finish();
  return b;
}

SpatialSpec read_spatial(MapReader m) {
  const Context& ctx = m.context();
  SpatialSpec s;
  s.source.where = ctx.where(m.self());
  if (auto f = m.take("gravity")) s.gravity = to_vec3(ctx, *f, any("m/s^2"));
  if (m.boolean("buoyancy", s.buoyancy) && s.buoyancy && !(s.gravity.norm() > 0.0))
    ctx.fail(*m.take("buoyancy"), "buoyancy needs gravity (Archimedes' force is the weight of the displaced water): "
                                  "give spatial.gravity, for example [0, 0, -9.81]");
  m.number("water_level", s.water_level, any("m"));
  m.number("water_density", s.water_density, closed(1.0, 1e5, "kg/m^3"));
  m.choice("narrow_phase", s.narrow_phase,
           {{"sat", dynamics::SpatialNarrowPhase::sat},
            {"gjk_epa_tiebreak", dynamics::SpatialNarrowPhase::gjk_epa_tiebreak},
            {"gjk_epa", dynamics::SpatialNarrowPhase::gjk_epa},
            {"mpr", dynamics::SpatialNarrowPhase::mpr}});
  m.choice("contact_point", s.contact_point,
           {{"witness", dynamics::ContactPointModel::witness},
            {"manifold", dynamics::ContactPointModel::manifold}});
  if (auto f = m.take("bodies")) {
    if (!f->value.IsNull()) {
      for (const Field& item : list_items(ctx, *f, "a list of bodies (each a block of keys)")) {
        s.bodies.push_back(read_spatial_body(MapReader(ctx, item)));
        for (std::size_t j = 0; j + 1 < s.bodies.size(); ++j) {
          if (s.bodies.back().id && s.bodies[j].id == s.bodies.back().id)
            ctx.fail({static_cast<const YAML::Node&>(item.value)["id"], YAML::Node(), join(item.path, "id")},
                     "id " + std::to_string(*s.bodies.back().id) + " is already used by " + f->path + "." +
                         std::to_string(j) + " (" + s.bodies[j].source.where + ")");
        }
      }
    }
  }
  m.finish();
  if (std::none_of(s.bodies.begin(), s.bodies.end(),
                   [](const SpatialBodySpec& b) { return b.motion == dynamics::Motion::dynamic; }))
    ctx.fail(m.self(), "a spatial scene needs at least one body with motion: dynamic under 'spatial.bodies'");
  return s;
}

void read_scene_tree(const Context& ctx, const YAML::Node& root, Scene& s) {
  MapReader top(ctx, {root, YAML::Node(), ""});
  top.file_name("name", s.name);
  read_run(top.block("run"), s.time);
  read_output(top.block("output"), s.output);
  read_ice(top.block("ice"), s);
  read_contact(top.block("contact"), s.world);
  read_forcing(top.block("forcing"), s);
  if (auto f = top.take("floes")) read_floes(ctx, *f, s.bodies);
  if (auto m = top.optional_block("floe_field")) s.floe_field = read_floe_field(*m);
  if (auto m = top.optional_block("ice_sheet")) s.ice_sheet = read_ice_sheet(*m);
  if (auto m = top.optional_block("channel")) s.channel = read_channel(*m);
  const bool has_forcing = top.has("forcing");
  if (auto m = top.optional_block("spatial")) s.spatial = read_spatial(*m);
  top.finish();
  if (s.spatial) {
    // Spatial scenes have polyhedra, gravity and buoyancy; level-floe content would be silently ignored.
    const char* planar_only = !s.bodies.empty() ? "floes" : s.floe_field ? "floe_field" : s.ice_sheet ? "ice_sheet"
                              : s.channel ? "channel" : has_forcing ? "forcing" : nullptr;
    if (planar_only)
      throw SceneError(s.spatial->source.where + ": a spatial scene takes its bodies from 'spatial.bodies' and has "
                       "no drift forcing: remove '" + planar_only + "' (or remove 'spatial' for a planar scene)");
    return;
  }
  check_forcing(ctx, top.self(), s);

  const bool dynamic_body = std::any_of(s.bodies.begin(), s.bodies.end(),
                                        [](const BodySpec& b) { return b.motion == dynamics::Motion::dynamic; });
  if (!dynamic_body && !s.floe_field && !s.ice_sheet) {
    throw SceneError(ctx.file() + ":1:1: the scene has no dynamic body: list floes under 'floes' (motion: dynamic) "
                                  "or generate them with 'floe_field' or 'ice_sheet'");
  }
}

// ---------------------------------------------------------------------------------------------------------------
// Overrides

bool is_index(const std::string& s) {
  return !s.empty() && s.size() < 10 && std::all_of(s.begin(), s.end(), [](unsigned char c) { return std::isdigit(c); });
}

// Sets the value at keys[i..] below `node` (whose path is `path`), creating missing blocks.
void set_path(Context& ctx, YAML::Node node, const std::vector<std::string>& keys, std::size_t i,
              const std::string& path, const YAML::Node& value, const std::string& key) {
  const std::string& k = keys[i];
  const std::string child_path = join(path, k);
  const bool last = i + 1 == keys.size();
  const std::string where = "--set " + key + ": ";
  if (node.IsSequence()) {
    if (!is_index(k) || std::stoul(k) >= node.size())
      throw SceneError(where + "'" + path + "' is a list of " + std::to_string(node.size()) + " items; '" + k +
                       "' is not one of its indices 0.." + std::to_string(node.size()) + "-1");
    const std::size_t idx = std::stoul(k);
    if (last) {
      node[idx] = value;
      ctx.set_origin(child_path, key);
      return;
    }
    YAML::Node child = node[idx];
    set_path(ctx, child, keys, i + 1, child_path, value, key);
    return;
  }
  if (!node.IsMap())
    throw SceneError(where + "'" + path + "' is a single value, not a block of keys, so '" + child_path +
                     "' cannot be set");
  if (last) {
    node[k] = value;
    ctx.set_origin(child_path, key);
    return;
  }
  YAML::Node child;
  for (auto it = node.begin(); it != node.end(); ++it)
    if (it->first.IsScalar() && it->first.Scalar() == k) child.reset(it->second);
  if (!child.IsDefined() || child.IsNull()) {
    if (is_index(keys[i + 1]))
      throw SceneError(where + "there is no list '" + child_path + "' to take item " + keys[i + 1] + " from");
    node[k] = YAML::Node(YAML::NodeType::Map);
    child.reset(node[k]);
    ctx.set_origin(child_path, key);
  }
  set_path(ctx, child, keys, i + 1, child_path, value, key);
}

void apply_override(Context& ctx, YAML::Node& root, const std::string& arg) {
  const std::size_t eq = arg.find('=');
  if (eq == std::string::npos || eq == 0)
    throw SceneError("--set '" + arg + "': expected key.path=value (for example --set run.duration=60)");
  const std::string key = arg.substr(0, eq);
  const std::string text = arg.substr(eq + 1);
  std::vector<std::string> keys;
  for (std::size_t start = 0;;) {
    const std::size_t dot = key.find('.', start);
    keys.push_back(key.substr(start, dot == std::string::npos ? std::string::npos : dot - start));
    if (keys.back().empty()) throw SceneError("--set " + key + ": empty name in the key path");
    if (dot == std::string::npos) break;
    start = dot + 1;
  }
  YAML::Node value;
  try {
    value = YAML::Load(text);
  } catch (const YAML::Exception& e) {
    throw SceneError("--set " + key + ": cannot read the value '" + text + "' as YAML: " + e.msg);
  }
  check_tree_limits(value, "--set " + key);
  if (!root.IsMap()) root.reset(YAML::Node(YAML::NodeType::Map));
  set_path(ctx, root, keys, 0, "", value, key);
}

// yaml-cpp 0.7 accepts a quoted scalar left open at the end of the text (it folds the rest of the file into it):
// where the first quote that is never closed starts, if any.
std::optional<YAML::Mark> unclosed_quote(const std::string& text, const YAML::Node& n) {
  if (!n.IsDefined()) return std::nullopt;
  if (n.IsScalar()) {
    const int pos = n.Mark().pos;
    if (n.Mark().is_null() || pos < 0 || static_cast<std::size_t>(pos) >= text.size()) return std::nullopt;
    const char q = text[static_cast<std::size_t>(pos)];
    if (q != '"' && q != '\'') return std::nullopt;
    for (std::size_t i = static_cast<std::size_t>(pos) + 1; i < text.size(); ++i) {
      if (q == '"' && text[i] == '\\') ++i;                       // an escape: skip the escaped character
      else if (q == '\'' && text.compare(i, 2, "''") == 0) ++i;  // '' is a quote inside a single-quoted string
      else if (text[i] == q) return std::nullopt;
    }
    return n.Mark();
  }
  for (auto it = n.begin(); it != n.end(); ++it) {
    const bool map = n.IsMap();
    for (const YAML::Node& child : map ? std::vector<YAML::Node>{it->first, it->second} : std::vector<YAML::Node>{*it})
      if (auto m = unclosed_quote(text, child)) return m;
  }
  return std::nullopt;
}

}  // namespace

// ---------------------------------------------------------------------------------------------------------------

Scene parse_scene(const std::string& text, const std::string& display_name, const std::vector<std::string>& overrides) {
  Context ctx(display_name);
  // A binary file (or one in UTF-16) would otherwise meet the YAML parser's escape or indentation errors.
  for (std::size_t i = 0, line = 1, column = 1; i < text.size(); ++i, ++column) {
    const auto c = static_cast<unsigned char>(text[i]);
    if (c == '\n') {
      ++line;
      column = 0;
    } else if ((c < 0x20 && c != '\t' && c != '\r') || c == 0x7f) {
      std::ostringstream msg;
      msg << display_name << ":" << line << ":" << column << ": not a text file: control byte 0x" << std::hex
          << std::setw(2) << std::setfill('0') << static_cast<int>(c) << " (a scene is YAML text, UTF-8)";
      throw SceneError(msg.str());
    }
  }
  YAML::Node root;
  try {
    root = YAML::Load(text);
  } catch (const YAML::DeepRecursion& e) {
    throw SceneError(display_name + ":" + std::to_string(e.mark.line + 1) + ":" + std::to_string(e.mark.column + 1) +
                     ": blocks nested more than " + std::to_string(e.depth()) + " levels deep (a scene nests some 5)");
  } catch (const YAML::ParserException& e) {
    throw SceneError(display_name + ":" + std::to_string(e.mark.line + 1) + ":" + std::to_string(e.mark.column + 1) +
                     ": YAML syntax error: " + e.msg);
  } catch (const YAML::Exception& e) {
    throw SceneError(display_name + ": cannot read YAML: " + e.msg);
  }
  check_tree_limits(root, display_name);  // before any other walk of the tree
  if (const auto open = unclosed_quote(text, root))
    throw SceneError(display_name + ":" + std::to_string(open->line + 1) + ":" + std::to_string(open->column + 1) +
                     ": YAML syntax error: the quoted string that starts here is never closed");
  if (root.IsDefined() && !root.IsNull() && !root.IsMap())
    throw SceneError(ctx.where({root, YAML::Node(), ""}) + ": a scene is a block of keys (name, run, ...), got " +
                     describe(root));
  for (const std::string& o : overrides) apply_override(ctx, root, o);
  if (!overrides.empty()) check_tree_limits(root, display_name);  // an override may use a block twice

  Scene s;
  // The default name is the file's stem, under the rule 'name:' follows (results/<name> must be a folder below
  // results/): a stem such as '..' (from '...yaml') or '.' falls back to "scene".
  s.name = std::filesystem::path(display_name).stem().string();
  if (s.name.empty() || s.name == "." || s.name == ".." || s.name.size() > 200) s.name = "scene";
  s.source_path = display_name;
  s.source_text = text;
  s.overrides = overrides;
  try {
    read_scene_tree(ctx, root, s);
  } catch (const YAML::Exception& e) {  // should not happen: every access above is checked
    throw SceneError(display_name + ": " + e.what());
  }
  return s;
}

Scene read_scene(const std::filesystem::path& file, const std::vector<std::string>& overrides) {
  return parse_scene(read_text_file(file, kMaxSceneBytes, "scene file"), file.string(), overrides);
}

}  // namespace polyfloe::scene
