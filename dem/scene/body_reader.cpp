// The keys of settings_schema.h that read themselves and make bodies or rectangles: the explicit floes (polygon,
// regular, rectangle; world or body coordinates), the spatial bodies, the floe field's corners, the regions.
#include <algorithm>
#include <array>
#include <map>
#include <optional>
#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include "contact/narrow_phase_planar.h"
#include "geometry/polygon.h"
#include "scene/settings_schema.h"
#include "scene/yaml_format.h"

namespace polyfloe::scene::detail {

namespace {

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

void read_floes(MapReader& m, const char* key, std::vector<BodySpec>& bodies) {
  const Context& ctx = m.context();
  const auto f = m.take(key);
  if (!f || f->value.IsNull()) return;
  std::map<std::uint64_t, std::size_t> first_with_id;  // id -> the floe that gave it first
  for (const Field& item : list_items(ctx, *f, "a list of floes (each a block of keys)")) {
    bodies.push_back(read_body(MapReader(ctx, item)));
    if (const auto id = bodies.back().id) {
      const auto [it, fresh] = first_with_id.emplace(*id, bodies.size() - 1);
      if (!fresh)
        ctx.fail({static_cast<const YAML::Node&>(item.value)["id"], YAML::Node(), join(item.path, "id")},
                 "id " + std::to_string(*id) + " is already used by " + f->path + "." + std::to_string(it->second) +
                     " (" + bodies[it->second].source.where + ")");
    }
  }
}

void read_box(MapReader& m, const char* key, Box& box) {
  if (auto f = m.take(key)) {
    const std::array<double, 4> r = to_box(m.context(), *f);
    box.min = {r[0], r[1]};
    box.max = {r[2], r[3]};
  }
}

void read_region(MapReader& m, const char* key, std::optional<std::array<double, 4>>& region) {
  if (auto f = m.take(key)) {
    if (is_word(f->value, "auto"))
      region.reset();
    else
      region = to_box(m.context(), *f);
  }
}

void read_corners(MapReader& m, const char* key, FloeFieldSpec& s) {
  const Context& ctx = m.context();
  if (auto f = m.take(key)) {
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
}

geometry::Vec3 to_vec3(const Context& ctx, const Field& f, const Range& r) {
  const std::string what = "a list of 3 numbers [x, y, z] [" + std::string(r.unit) + "]";
  const std::vector<Field> items = list_items(ctx, f, what);
  if (items.size() != 3) ctx.fail(f, "expected " + what + ", got " + describe(f.value));
  return {to_number(ctx, items[0], r), to_number(ctx, items[1], r), to_number(ctx, items[2], r)};
}

namespace {

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

void read_spatial_bodies(MapReader& m, const char* key, std::vector<SpatialBodySpec>& bodies) {
  const Context& ctx = m.context();
  const auto f = m.take(key);
  if (!f || f->value.IsNull()) return;
  for (const Field& item : list_items(ctx, *f, "a list of bodies (each a block of keys)")) {
    bodies.push_back(read_spatial_body(MapReader(ctx, item)));
    for (std::size_t j = 0; j + 1 < bodies.size(); ++j) {
      if (bodies.back().id && bodies[j].id == bodies.back().id)
        ctx.fail({static_cast<const YAML::Node&>(item.value)["id"], YAML::Node(), join(item.path, "id")},
                 "id " + std::to_string(*bodies.back().id) + " is already used by " + f->path + "." +
                     std::to_string(j) + " (" + bodies[j].source.where + ")");
    }
  }
}

}  // namespace polyfloe::scene::detail
