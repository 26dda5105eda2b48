// resolved_yaml(): every resolved setting of a Scene as YAML, with units as comments (printed by `polyfloe check`,
// written next to the results, and read back by parse_scene to the same settings): the settings' declaration
// (settings_schema.h) walked by a writer, and the writers of the keys that write themselves.
#include <filesystem>
#include <sstream>
#include <system_error>

#include "scene/scene_reader.h"
#include "scene/settings_schema.h"
#include "scene/yaml_format.h"

namespace polyfloe::scene {

using detail::fmt;
using detail::quoted;

namespace detail {

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

std::string vec3(const geometry::Vec3& v) { return "[" + fmt(v.x()) + ", " + fmt(v.y()) + ", " + fmt(v.z()) + "]"; }

// One line "key: value  # comment" (no comment when it is empty).
void line(std::ostream& o, const std::string& indent, const char* key, const std::string& value,
          const std::string& comment) {
  o << indent << key << ": " << value << (comment.empty() ? "" : "  # " + comment) << "\n";
}

std::string with_unit(const char* unit, const char* comment) {
  return "[" + std::string(unit) + "]" + (*comment ? " " + std::string(comment) : std::string());
}

// The visitor of settings_schema.h that writes the resolved scene: one key per line with its unit and comment; a
// flow block on one line ({a: 1, b: 2}) with the block's comment.
class SettingsWriter {
 public:
  explicit SettingsWriter(std::ostream& o) : o_(o) {}

  void number(const char* key, double x, const Range& r, const char* comment) {
    put(key, fmt(x), with_unit(r.unit, comment));
  }
  void number_or_auto(const char* key, const std::optional<double>& x, const Range& r, const char* comment) {
    put(key, x ? fmt(*x) : std::string("auto"), with_unit(r.unit, comment));
  }
  void zero_is_auto(const char* key, double x, const Range& r, const char* comment) {
    put(key, x > 0.0 ? fmt(x) : std::string("auto"), with_unit(r.unit, comment));
  }
  void integer(const char* key, int x, int, int, const char* comment) { put(key, std::to_string(x), comment); }
  void unsigned64(const char* key, std::uint64_t x, const char* comment) { put(key, std::to_string(x), comment); }
  void boolean(const char* key, bool x, const char* comment) { put(key, x ? "true" : "false", comment); }
  void name(const char* key, const std::string& x, const char* comment) { put(key, quoted(x), comment); }
  void vec2(const char* key, const Vec2& x, const char* unit, const char* comment) {
    put(key, fmt(x), with_unit(unit, comment));
  }
  void vec3(const char* key, const geometry::Vec3& x, const char* unit, const char* comment) {
    put(key, detail::vec3(x), with_unit(unit, comment));
  }
  template <class E>
  void choice(const char* key, E x, std::initializer_list<std::pair<const char*, E>> options, const char* comment) {
    for (const auto& [word, value] : options)
      if (value == x) put(key, word, comment);
  }
  template <class F>
  void block(const char* key, F&& fn) {
    o_ << indent_ << key << ":\n";
    indent_ += "  ";
    fn(*this);
    indent_.resize(indent_.size() - 2);
  }
  template <class F>
  void flow(const char* key, const char* comment, F&& fn) {
    flow_ = true;
    fn(*this);
    flow_ = false;
    put(key, "{" + items_ + "}", comment);
    items_.clear();
  }
  template <class T, class F>
  void optional_block(const char* key, std::optional<T>& x, F&& fn) {
    if (x) block(key, [&](SettingsWriter& w) { fn(w, *x); });
  }
  template <class T, class R>
  void custom(const char* key, T& x, const char* comment, R,
              void (*write)(std::ostream&, const std::string&, const char*, const char*, const T&)) {
    write(o_, indent_, key, comment, x);
  }
  template <class F>
  void after(F&&) {}

 private:
  void put(const char* key, const std::string& value, const std::string& comment) {
    if (flow_)
      items_ += (items_.empty() ? "" : ", ") + std::string(key) + ": " + value;
    else
      line(o_, indent_, key, value, comment);
  }
  std::ostream& o_;
  std::string indent_;
  bool flow_ = false;
  std::string items_;  // of the flow block being written
};

// A list: "key: []", or "key:" and its items.
template <class T, class F>
void write_list(std::ostream& o, const std::string& indent, const char* key, const std::vector<T>& items, F&& item) {
  o << indent << key << (items.empty() ? ": []\n" : ":\n");
  for (const T& x : items) item(x, indent + "  - ", indent + "    ");
}

std::string polygon_text(const std::vector<Vec2>& polygon) {
  std::string t = "[";
  for (std::size_t i = 0; i < polygon.size(); ++i) t += (i ? ", " : "") + fmt(polygon[i]);
  return t + "]";
}

std::string from(const SourceRef& source) { return source.where.empty() ? "" : ", from " + source.where; }

}  // namespace

void write_region(std::ostream& o, const std::string& indent, const char* key, const char* comment,
                  const std::optional<std::array<double, 4>>& r) {
  line(o, indent, key,
       r ? "[" + fmt((*r)[0]) + ", " + fmt((*r)[1]) + ", " + fmt((*r)[2]) + ", " + fmt((*r)[3]) + "]"
         : std::string("auto"),
       comment);
}

void write_box(std::ostream& o, const std::string& indent, const char* key, const char* comment, const Box& b) {
  write_region(o, indent, key, comment, std::array<double, 4>{b.min.x(), b.min.y(), b.max.x(), b.max.y()});
}

void write_corners(std::ostream& o, const std::string& indent, const char* key, const char* comment,
                   const FloeFieldSpec& f) {
  line(o, indent, key, "[" + std::to_string(f.corners_min) + ", " + std::to_string(f.corners_max) + "]", comment);
}

void write_velocity(std::ostream& o, const std::string& indent, const char* key, const char* comment,
                    const Velocity& v) {
  line(o, indent, key, field_yaml(v.spec), comment);
}

void write_floes(std::ostream& o, const std::string& indent, const char* key, const char*,
                 const std::vector<BodySpec>& bodies) {
  write_list(o, indent, key, bodies, [&](const BodySpec& b, const std::string& first, const std::string& in) {
    o << first << "polygon: " << polygon_text(b.polygon) << "  # [m] body frame" << from(b.source) << "\n";
    line(o, in, "position", fmt(b.position), "[m] centroid");
    line(o, in, "yaw", fmt(b.yaw), "[rad]");
    line(o, in, "velocity", fmt(b.velocity), "[m/s]");
    line(o, in, "angular_velocity", fmt(b.angular_velocity), "[rad/s]");
    line(o, in, "thickness", fmt(b.thickness), "[m]");
    line(o, in, "motion", std::string(dynamics::to_string(b.motion)), "");
    if (b.id) line(o, in, "id", std::to_string(*b.id), "");
    line(o, in, "external_force", fmt(b.external_force), "[N]");
    line(o, in, "external_torque", fmt(b.external_torque), "[N m]");
  });
}

void write_spatial_bodies(std::ostream& o, const std::string& indent, const char* key, const char*,
                          const std::vector<SpatialBodySpec>& bodies) {
  write_list(o, indent, key, bodies, [&](const SpatialBodySpec& b, const std::string& first, const std::string& in) {
    if (b.box)
      o << first << "box: " << vec3(*b.box) << "  # [m] edge lengths" << from(b.source) << "\n";
    else
      o << first << "polygon: " << polygon_text(b.polygon) << "  # [m] body frame" << from(b.source) << "\n";
    line(o, in, "thickness", fmt(b.thickness), "[m] (polygon prisms)");
    line(o, in, "position", vec3(b.position), "[m] centroid");
    line(o, in, "rotation", "{axis: " + vec3(b.rotation_axis) + ", angle: " + fmt(b.rotation_angle) + "}", "[rad]");
    line(o, in, "velocity", vec3(b.velocity), "[m/s]");
    line(o, in, "angular_velocity", vec3(b.angular_velocity), "[rad/s]");
    if (b.density) line(o, in, "density", fmt(*b.density), "[kg/m^3]");
    line(o, in, "motion", std::string(dynamics::to_string(b.motion)), "");
    if (b.id) line(o, in, "id", std::to_string(*b.id), "");
  });
}

}  // namespace detail

namespace {

// The comment lines: the scene, its file (one spelling) and the --set overrides.
void put_header(std::ostream& o, const Scene& s) {
  o << "# Scene '" << s.name << "', every setting resolved (units in the comments).\n";
  if (!s.source_path.empty()) {  // one spelling of the file (links and '..' resolved): restarts compare this text
    std::error_code ec;
    const std::filesystem::path p = std::filesystem::weakly_canonical(s.source_path, ec);
    o << "# from: " << (ec ? s.source_path : p.string()) << "\n";
  }
  for (const std::string& ov : s.overrides) o << "# --set " << ov << "\n";
}

}  // namespace

std::string resolved_yaml(const Scene& s) {
  std::ostringstream o;
  put_header(o, s);
  detail::SettingsWriter w(o);
  detail::scene_keys(w, const_cast<Scene&>(s));  // the writer only reads
  return o.str();
}

}  // namespace polyfloe::scene
