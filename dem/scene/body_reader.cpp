// The blocks of a scene that make bodies: explicit floes (polygon, regular, rectangle; world or body coordinates),
// the floe field, the channel, the ice sheet and the spatial bodies. Each reads its block on the schema walker of
// schema.h and checks what one block can check; scene_reader.cpp checks across blocks.
#include "scene/body_reader.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include "contact/narrow_phase_planar.h"
#include "geometry/polygon.h"
#include "scene/channel.h"
#include "scene/yaml_format.h"

namespace polyfloe::scene::detail {

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

namespace {

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
        ctx.fail(r.self(),
                 "the rectangle's outline is unusable: " + err +
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
      ctx.fail(*fc,
               "coordinates: world places a 'polygon' given in scene coordinates; 'regular' and 'rectangle' "
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

}  // namespace

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
        ctx.fail(items[1],
                 "max = " + std::to_string(s.corners_max) + " must be >= min = " + std::to_string(s.corners_min));
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

namespace {

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
    if (r->has("angle") && r->has("angle_deg"))
      c.fail(r->self(), "give only one of 'angle' [rad] and 'angle_deg' [deg]");
    r->number("angle", b.rotation_angle, any("rad"));
    double deg = 0.0;
    if (r->number("angle_deg", deg, any("deg"))) b.rotation_angle = deg * std::numbers::pi / 180.0;
    if (r->has("axis") && !r->has("angle") && !r->has("angle_deg"))
      c.fail(*r->take("axis"),
             "a rotation about this axis needs its angle: give rotation.angle [rad] or "
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

}  // namespace

SpatialSpec read_spatial(MapReader m) {
  const Context& ctx = m.context();
  SpatialSpec s;
  s.source.where = ctx.where(m.self());
  if (auto f = m.take("gravity")) s.gravity = to_vec3(ctx, *f, any("m/s^2"));
  if (m.boolean("buoyancy", s.buoyancy) && s.buoyancy && !(s.gravity.norm() > 0.0))
    ctx.fail(*m.take("buoyancy"),
             "buoyancy needs gravity (Archimedes' force is the weight of the displaced water): "
             "give spatial.gravity, for example [0, 0, -9.81]");
  m.number("water_level", s.water_level, any("m"));
  m.number("water_density", s.water_density, closed(1.0, 1e5, "kg/m^3"));
  m.choice("narrow_phase", s.narrow_phase,
           {{"sat", dynamics::SpatialNarrowPhase::sat},
            {"gjk_epa_tiebreak", dynamics::SpatialNarrowPhase::gjk_epa_tiebreak},
            {"gjk_epa", dynamics::SpatialNarrowPhase::gjk_epa},
            {"mpr", dynamics::SpatialNarrowPhase::mpr}});
  m.choice("contact_point", s.contact_point,
           {{"witness", dynamics::ContactPointModel::witness}, {"manifold", dynamics::ContactPointModel::manifold}});
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

}  // namespace polyfloe::scene::detail
