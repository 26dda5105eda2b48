#include "scene/forcing_reader.h"
#include "scene/settings_schema.h"

#include <filesystem>

#include "forcing/analytic_fields.h"
#include "forcing/gridded_field.h"
#include "formats/field_file.h"

namespace polyfloe::scene::detail {

namespace {

Eigen::Matrix2d to_matrix2(const Context& ctx, const Field& f, const char* unit) {
  const std::string what = "a list of 2 rows [[du/dx, du/dy], [dv/dx, dv/dy]] [" + std::string(unit) + "]";
  const std::vector<Field> rows = list_items(ctx, f, what);
  if (rows.size() != 2) ctx.fail(f, "expected " + what + ", got " + describe(f.value));
  Eigen::Matrix2d g;
  for (int r = 0; r < 2; ++r) g.row(r) = to_vec2(ctx, rows[static_cast<std::size_t>(r)], any(unit)).transpose();
  return g;
}

void read_time_boundary(MapReader& m, forcing::FieldSpec& s) {
  m.choice("outside", s.outside,
           {{"clamp", forcing::TimeBoundary::clamp},
            {"cyclic", forcing::TimeBoundary::cyclic},
            {"error", forcing::TimeBoundary::error}});
}

// A field file (HDF5, `polyfloe field import`): the path is relative to the scene file's folder; the file is read
// and checked here, so a bad file fails like a bad key, before any output is written.
void read_file_field(MapReader& m, forcing::FieldSpec& s) {
  namespace fs = std::filesystem;
  const Context& ctx = m.context();
  const auto fp = m.take("path");
  if (!fp) ctx.fail(m.self(), "missing required key 'path' (an ocean field file written by `polyfloe field import`)");
  std::string given;
  m.text("path", given);
  if (given.empty()) ctx.fail(*fp, "expected a file name, got an empty text");
  fs::path path(given);
  if (path.is_relative()) path = fs::path(ctx.file()).parent_path() / path;
  // One spelling per file (links and '..' resolved), so that a restart compares the same resolved scene.
  std::error_code ec;
  const fs::path spelled = fs::absolute(path, ec).lexically_normal();
  const fs::path canonical = fs::weakly_canonical(spelled, ec);
  path = ec ? spelled : canonical;
  s.path = path.string();
  try {
    s.grid = std::make_shared<forcing::GridData>(io::read_field_file(path).grid);
  } catch (const std::exception& e) {
    ctx.fail(*fp, e.what());
  }
  const bool has_time = m.has("outside");
  read_time_boundary(m, s);
  if (s.grid->t.size() > 1 && !has_time)
    ctx.fail(m.self(), "the field file has " + std::to_string(s.grid->t.size()) + " snapshots (" +
                           fmt(s.grid->t.front()) + " to " + fmt(s.grid->t.back()) +
                           " s): say what the field does beyond them with 'outside' (clamp, cyclic or error)");
  m.choice("no_water", s.no_water,
           {{"error", forcing::OutsideWater::error}, {"velocity", forcing::OutsideWater::velocity}});
  const bool has_velocity = m.vec2("no_water_velocity", s.no_water_velocity, "m/s");
  if (s.no_water == forcing::OutsideWater::velocity && !has_velocity)
    ctx.fail(m.self(), "no_water: velocity needs no_water_velocity: [u, v] [m/s]");
  m.vec2("offset", s.offset, "m");                   // where the file's (0, 0) lies in the scene
  m.number("time_offset", s.time_offset, any("s"));  // scene time 0 is the file's time_offset
  m.choice("land", s.land_walls, {{"none", false}, {"walls", true}});
}

// One field block: 'type' picks the kind and with it the keys that may follow.
forcing::FieldSpec read_field(MapReader m) {
  using forcing::FieldKind;
  const Context& ctx = m.context();
  forcing::FieldSpec s;
  if (!m.has("type"))
    ctx.fail(m.self(), "missing required key 'type' (uniform, linear, solid_body, rankine, tidal, time_series, file)");
  m.choice("type", s.kind,
           {{"uniform", FieldKind::uniform},
            {"linear", FieldKind::linear},
            {"solid_body", FieldKind::solid_body},
            {"rankine", FieldKind::rankine},
            {"tidal", FieldKind::tidal},
            {"time_series", FieldKind::time_series},
            {"file", FieldKind::file}});
  switch (s.kind) {
    case FieldKind::uniform: m.vec2("velocity", s.velocity, "m/s"); break;
    case FieldKind::linear:
      m.vec2("velocity", s.velocity, "m/s");
      m.vec2("origin", s.origin, "m");
      if (auto f = m.take("gradient")) s.gradient = to_matrix2(ctx, *f, "1/s");
      m.vec2("depth_gradient", s.depth_gradient, "1/s");
      break;
    case FieldKind::solid_body:
      m.vec2("centre", s.origin, "m");
      m.number("angular_velocity", s.angular_velocity, any("rad/s"));
      m.vec2("velocity", s.velocity, "m/s");
      break;
    case FieldKind::rankine: {
      m.vec2("centre", s.origin, "m");
      const auto fr = m.take("core_radius");
      const auto fv = m.take("max_speed");
      if (!fr || !fv)
        ctx.fail(m.self(), std::string("missing required key '") + (fr ? "max_speed" : "core_radius") + "'");
      s.core_radius = to_number(ctx, *fr, positive("m"));
      s.max_speed = to_number(ctx, *fv, any("m/s"));
      m.vec2("velocity", s.velocity, "m/s");
      break;
    }
    case FieldKind::tidal: {
      m.vec2("velocity", s.velocity, "m/s");
      m.vec2("amplitude", s.amplitude, "m/s");
      const auto fp = m.take("period");
      if (!fp) ctx.fail(m.self(), "missing required key 'period' [s]");
      s.period = to_number(ctx, *fp, closed(1.0, 1e12, "s"));  // a second to 30,000 years
      m.number("phase", s.phase, any("rad"));
      break;
    }
    case FieldKind::time_series: {
      const auto ft = m.take("times");
      const auto fv = m.take("velocities");
      if (!ft || !fv) ctx.fail(m.self(), std::string("missing required key '") + (ft ? "velocities" : "times") + "'");
      const std::vector<Field> times = list_items(ctx, *ft, "a list of times [s]");
      const std::vector<Field> values = list_items(ctx, *fv, "a list of velocities [[u, v], ...] [m/s]");
      if (times.size() < 2) ctx.fail(*ft, "expected at least 2 times, got " + describe(ft->value));
      if (values.size() != times.size())
        ctx.fail(*fv, "expected one velocity per time (" + std::to_string(times.size()) + "), got " +
                          std::to_string(values.size()));
      for (std::size_t i = 0; i < times.size(); ++i) {
        s.times.push_back(to_number(ctx, times[i], any("s")));
        if (i > 0 && !(s.times[i] > s.times[i - 1]))
          ctx.fail(times[i], fmt(s.times[i]) + " s must be after the previous time " + fmt(s.times[i - 1]) + " s");
        s.values.push_back(to_vec2(ctx, values[i], any("m/s")));
      }
      read_time_boundary(m, s);
      break;
    }
    case FieldKind::file: read_file_field(m, s); break;
  }
  m.finish();
  if (const std::string err = forcing::field_spec_error(s); !err.empty()) ctx.fail(m.self(), err);
  return s;
}

}  // namespace

void read_velocity(MapReader& m, const char* key, Velocity& v) {
  if (m.has(v.shorthand) && m.has(key))
    m.context().fail(m.self(), std::string("give only one of '") + v.shorthand + "' (uniform) and '" + key + "'");
  Vec2 u = v.spec.velocity;
  if (m.vec2(v.shorthand, u, "m/s")) v.spec = forcing::FieldSpec::uniform(u);
  if (auto f = m.optional_block(key)) v.spec = read_field(*f);
}

void check_forcing(const Context& ctx, const Field& root, const Scene& s) {
  const forcing::DriftSettings& d = s.world.drift;
  if (!(s.ice_density < d.water_density)) {
    // Point at whichever of the two densities the scene gave (ice.density first); const lookups never throw.
    const YAML::Node& tree = root.value;
    Field where{YAML::Node(), YAML::Node(), "ice.density"};
    for (const auto& [block, sub, path] :
         {std::tuple{"ice", "", "ice.density"}, {"forcing", "ocean", "forcing.ocean.density"}}) {
      // (a missing key yields an invalid node: only IsDefined() may be asked of it)
      auto child = [](const YAML::Node& m, const char* key) {
        return m.IsDefined() && m.IsMap() ? m[key] : YAML::Node();  // (a default Node is defined and null)
      };
      // (YAML::Node's operator= writes into the node it refers to: build each step as a new node)
      const YAML::Node b = child(tree, block);
      const YAML::Node m = *sub ? child(b, sub) : b;
      const YAML::Node n = child(m, "density");
      if (n.IsDefined() && !n.IsNull()) {
        where = {n, YAML::Node(), path};
        break;
      }
    }
    ctx.fail(where, "ice density " + fmt(s.ice_density) +
                        " kg/m^3 must be below the water density forcing.ocean.density = " + fmt(d.water_density) +
                        " kg/m^3, or the floes would sink");
  }
  const std::pair<const forcing::FieldSpec*, const char*> fields[] = {{&s.ocean_field, "forcing.ocean.field"},
                                                                      {&s.wind_field, "forcing.air.field"}};
  for (const auto& [f, path] : fields) {
    if (f->outside != forcing::TimeBoundary::error) continue;
    const bool series = f->kind == forcing::FieldKind::time_series;
    const bool file = f->kind == forcing::FieldKind::file && f->grid && f->grid->t.size() > 1;
    if (!series && !file) continue;
    const std::vector<double>& t = series ? f->times : f->grid->t;
    const double shift = series ? 0.0 : f->time_offset;  // the run's [0, duration] is the file's [shift, ...]
    if (t.front() > shift || t.back() < s.time.duration + shift)
      throw SceneError(ctx.file() + ": key '" + std::string(path) +
                       (series ? ".times': the series" : ".path': the file's snapshots") + " cover" +
                       (series ? "s" : "") + " [" + fmt(t.front()) + ", " + fmt(t.back()) + "] s but the run spans [" +
                       fmt(shift) + ", " + fmt(s.time.duration + shift) + "] s" +
                       (shift != 0.0 ? " of the file's time (time_offset " + fmt(shift) + " s)" : "") +
                       " with outside: error; " + (series ? "extend the series" : "import more snapshots") +
                       " or choose clamp or cyclic");
  }
}

}  // namespace polyfloe::scene::detail
