// schema_keys(): the settings' declaration (settings_schema.h) walked by a visitor that lists each key with its
// kind, unit, choices, value and comment.
#include <sstream>
#include <type_traits>

#include "scene/scene_reader.h"
#include "scene/settings_schema.h"
#include "scene/yaml_format.h"

namespace polyfloe::scene {

namespace detail {

namespace {

class KeyLister {
 public:
  explicit KeyLister(bool with_absent) : with_absent_(with_absent) {}
  std::vector<SchemaKey> keys;

  void number(const char* key, double x, const Range& r, const char* c) { add(key, "number", r.unit, fmt(x), c); }
  void number_or_auto(const char* key, const std::optional<double>& x, const Range& r, const char* c) {
    add(key, "number", r.unit, x ? fmt(*x) : "auto", c);
  }
  void zero_is_auto(const char* key, double x, const Range& r, const char* c) {
    add(key, "number", r.unit, x > 0.0 ? fmt(x) : "auto", c);
  }
  void integer(const char* key, int x, int, int, const char* c) { add(key, "integer", "", std::to_string(x), c); }
  void unsigned64(const char* key, std::uint64_t x, const char* c) { add(key, "integer", "", std::to_string(x), c); }
  void boolean(const char* key, bool x, const char* c) { add(key, "boolean", "", x ? "true" : "false", c); }
  void name(const char* key, const std::string& x, const char* c) { add(key, "text", "", x, c); }
  void vec2(const char* key, const Vec2& x, const char* unit, const char* c) { add(key, "vec2", unit, fmt(x), c); }
  void vec3(const char* key, const geometry::Vec3& x, const char* unit, const char* c) {
    add(key, "vec3", unit, "[" + fmt(x.x()) + ", " + fmt(x.y()) + ", " + fmt(x.z()) + "]", c);
  }
  template <class E>
  void choice(const char* key, E x, std::initializer_list<std::pair<const char*, E>> options, const char* c) {
    add(key, "choice", "", "", c);
    for (const auto& [word, value] : options) {
      keys.back().choices.emplace_back(word);
      if (value == x) keys.back().value = word;
    }
  }
  template <class F>
  void block(const char* key, F&& fn) {
    nest(key, "block", "", fn);
  }
  template <class F>
  void flow(const char* key, const char* comment, F&& fn) {
    nest(key, "flow", comment, fn);
  }
  template <class T, class F>
  void optional_block(const char* key, std::optional<T>& x, F&& fn) {
    if (x) {
      block(key, [&](KeyLister& v) { fn(v, *x); });
    } else if (with_absent_) {
      T defaults;
      block(key, [&](KeyLister& v) { fn(v, defaults); });
    }
  }
  template <class T, class R>
  void custom(const char* key, T& x, const char* comment, R,
              void (*write)(std::ostream&, const std::string&, const char*, const char*, const T&)) {
    std::ostringstream text;
    write(text, "", key, "", x);
    add(key, "custom", "", text.str(), comment);
    if constexpr (std::is_same_v<T, Velocity>) add(x.shorthand, "vec2", "m/s", "", "a uniform velocity");
  }
  template <class F>
  void after(F&&) {}

 private:
  void add(const char* key, const char* kind, const char* unit, const std::string& value, const char* comment) {
    keys.push_back({join(prefix_, key), kind, unit, {}, value, comment});
  }
  template <class F>
  void nest(const char* key, const char* kind, const char* comment, F& fn) {
    add(key, kind, "", "", comment);
    const std::string outer = prefix_;
    prefix_ = join(prefix_, key);
    fn(*this);
    prefix_ = outer;
  }
  bool with_absent_;
  std::string prefix_;
};

}  // namespace

}  // namespace detail

std::vector<SchemaKey> schema_keys(const Scene& scene, bool with_absent) {
  detail::KeyLister lister(with_absent);
  detail::scene_keys(lister, const_cast<Scene&>(scene));  // the lister only reads
  return std::move(lister.keys);
}

}  // namespace polyfloe::scene
