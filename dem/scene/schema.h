// The scene schema walker (internal to dem/scene): a MapReader wraps one YAML map, its typed getters read a key
// (leaving the default in place when it is absent) and record it as known, and finish() reports any key nobody
// asked for. The schema itself is declared in settings_schema.h, which a MapReader walks as one of its visitors
// (the getters take the key's comment for the other visitors and ignore it); the explicit bodies, the field blocks
// and the spatial bodies are read by functions of their own (body_reader.cpp, forcing_reader.cpp).
#pragma once

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cstdint>
#include <functional>
#include <limits>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "scene/scene.h"
#include "scene/yaml_format.h"

namespace polyfloe::scene::detail {

constexpr double kInf = std::numeric_limits<double>::infinity();

// An allowed interval of a number, with its unit for messages ("s", "m/s", "-").
struct Range {
  double lo = -kInf, hi = kInf;
  bool lo_open = true, hi_open = true;
  const char* unit = "-";
  bool contains(double x) const { return (lo_open ? x > lo : x >= lo) && (hi_open ? x < hi : x <= hi); }
  std::string text() const {
    return std::string(lo_open ? "(" : "[") + fmt(lo) + ", " + fmt(hi) + (hi_open ? ")" : "]") + " [" + unit + "]";
  }
};
// Any value a physical quantity of the unit can take: speeds (and rates) within 1 km/s (1,000 rad/s, 1,000 m/s^2)
// positions within 10^9 m and angles within 10^6 rad (10^8 deg), so that no product of user numbers in the models
// overflows and a run cannot blow up
// for a reason other than the number given; other units are not bounded.
inline double physical_cap(const char* unit) {
  const std::string_view u(unit);
  return u == "m/s" || u == "rad/s" || u == "m/s^2" ? 1e3 : u == "m" ? 1e9 : u == "rad" ? 1e6 : u == "deg" ? 1e8 : kInf;
}
inline Range any(const char* unit) {
  const double cap = physical_cap(unit);
  return {-cap, cap, cap == kInf, cap == kInf, unit};
}
inline Range positive(const char* unit) { return {0.0, physical_cap(unit), true, physical_cap(unit) == kInf, unit}; }
inline Range at_least(double lo, const char* unit) { return {lo, kInf, false, true, unit}; }
inline Range closed(double lo, double hi, const char* unit) { return {lo, hi, false, false, unit}; }

// ---------------------------------------------------------------------------------------------------------------
// Where things are

// A value in the tree: its node, the node of its key (for marks of empty values), and its dotted path.
struct Field {
  YAML::Node value;
  YAML::Node key;  // undefined for list items and the root
  std::string path;
};

inline std::string join(const std::string& parent, const std::string& key) {
  return parent.empty() ? key : parent + "." + key;
}

class Context {
 public:
  explicit Context(std::string file) : file_(std::move(file)) {}

  const std::string& file() const { return file_; }
  void set_origin(const std::string& path, const std::string& override_key) { origin_[path] = override_key; }

  // "--set KEY" when the value (or a block around it) came from an override, else "FILE:LINE:COL".
  std::string where(const Field& f) const {
    for (std::string p = f.path;; p = p.substr(0, p.rfind('.'))) {
      if (auto it = origin_.find(p); it != origin_.end()) return "--set " + it->second;
      if (p.find('.') == std::string::npos) break;
    }
    // An empty value's mark points past it; its key's mark is where the reader looks.
    const YAML::Node& n = (f.value.IsDefined() && !f.value.IsNull()) || !f.key.IsDefined() ? f.value : f.key;
    if (!n.IsDefined() || n.Mark().is_null()) return file_;
    return file_ + ":" + std::to_string(n.Mark().line + 1) + ":" + std::to_string(n.Mark().column + 1);
  }

  [[noreturn]] void fail(const Field& f, const std::string& message) const {
    throw SceneError(where(f) + ": key '" + f.path + "': " + message);
  }

 private:
  std::string file_;
  std::map<std::string, std::string> origin_;  // tree path -> the --set key that wrote or created it
};

// ---------------------------------------------------------------------------------------------------------------
// Typed values: each reads one node or fails naming where it is and what is allowed.

// What a node is, for "expected X, got Y"; a long value is shown by its start and its length.
std::string describe(const YAML::Node& n);
// `text` as a message quotes it: at most 60 characters (the first 40, then "... (N characters)").
std::string excerpt(const std::string& text);

enum class NumberText { ok, not_a_number, non_finite };
inline bool plain_scalar(const YAML::Node& n) { return n.IsDefined() && n.IsScalar() && n.Tag() != "!"; }
// A word of the schema ('auto', an enumerated value), plain or quoted: JSON, YAML's subset, quotes every word.
// (Numbers are not words: a quoted number is refused as text.)
inline bool is_word(const YAML::Node& n, const char* word) {
  return n.IsDefined() && n.IsScalar() && n.Scalar() == word;
}
bool non_finite_spelling(const std::string& s);
NumberText parse_double(const std::string& s, double& x);
double to_number(const Context& ctx, const Field& f, const Range& r, const char* alternative = "");
long long to_integer(const Context& ctx, const Field& f, long long lo, long long hi);
std::uint64_t to_unsigned64(const Context& ctx, const Field& f);
bool to_bool(const Context& ctx, const Field& f);
std::vector<Field> list_items(const Context& ctx, const Field& f, const std::string& what);
Vec2 to_vec2(const Context& ctx, const Field& f, const Range& r);
geometry::Vec3 to_vec3(const Context& ctx, const Field& f, const Range& r);
std::vector<Vec2> to_polygon(const Context& ctx, const Field& f);

// ---------------------------------------------------------------------------------------------------------------
// The schema walker

class MapReader {
 public:
  // `self` must be a map, or absent / empty (then every key keeps its default).
  MapReader(const Context& ctx, Field self) : ctx_(ctx), self_(std::move(self)) {
    if (!self_.value.IsDefined() || self_.value.IsNull()) return;
    if (!self_.value.IsMap()) ctx_.fail(self_, "expected a block of keys (a map), got " + describe(self_.value));
    for (auto it = self_.value.begin(); it != self_.value.end(); ++it) {
      const YAML::Node key = it->first;
      if (!key.IsScalar()) ctx_.fail({key, key, self_.path}, "keys must be plain names, got " + describe(key));
      for (const Entry& e : entries_) {
        if (e.name == key.Scalar())
          ctx_.fail({key, key, join(self_.path, e.name)},
                    "duplicate key (first given at " + ctx_.where({e.key, e.key, join(self_.path, e.name)}) + ")");
      }
      entries_.push_back({key.Scalar(), key, it->second, false});
    }
  }

  const Field& self() const { return self_; }
  const Context& context() const { return ctx_; }
  bool has(const char* key) const {
    return std::any_of(entries_.begin(), entries_.end(), [&](const Entry& e) { return e.name == key; });
  }

  // Marks `key` as part of the schema and returns its value if given (a null value counts as given).
  std::optional<Field> take(const char* key) {
    if (std::find(known_.begin(), known_.end(), key) == known_.end()) known_.emplace_back(key);
    for (Entry& e : entries_) {
      if (e.name == key) {
        e.used = true;
        return Field{e.value, e.key, join(self_.path, key)};
      }
    }
    return std::nullopt;
  }

  // Typed getters: `out` keeps its default when the key is absent. They return whether the key was given.
  bool number(const char* key, double& out, const Range& r, const char* /*comment*/ = "") {
    const auto f = take(key);
    if (f) out = to_number(ctx_, *f, r);
    return f.has_value();
  }
  // A number, or the word 'auto' (stored as empty).
  bool number_or_auto(const char* key, std::optional<double>& out, const Range& r, const char* /*comment*/ = "") {
    const auto f = take(key);
    if (!f) return false;
    if (is_word(f->value, "auto"))
      out.reset();
    else
      out = to_number(ctx_, *f, r, " or 'auto'");
    return true;
  }
  bool integer(const char* key, int& out, int lo, int hi, const char* /*comment*/ = "") {
    const auto f = take(key);
    if (f) out = static_cast<int>(to_integer(ctx_, *f, lo, hi));
    return f.has_value();
  }
  bool unsigned64(const char* key, std::uint64_t& out, const char* /*comment*/ = "") {
    const auto f = take(key);
    if (f) out = to_unsigned64(ctx_, *f);
    return f.has_value();
  }
  bool optional_unsigned64(const char* key, std::optional<std::uint64_t>& out) {
    std::uint64_t x = 0;
    if (!unsigned64(key, x)) return false;
    out = x;
    return true;
  }
  bool boolean(const char* key, bool& out, const char* /*comment*/ = "") {
    const auto f = take(key);
    if (f) out = to_bool(ctx_, *f);
    return f.has_value();
  }
  bool text(const char* key, std::string& out) {
    const auto f = take(key);
    if (!f) return false;
    if (!f->value.IsScalar()) ctx_.fail(*f, "expected a text, got " + describe(f->value));
    out = f->value.Scalar();
    for (const char c : out)
      if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f)
        ctx_.fail(*f, "expected one line of text without control characters (is a quoted string left open?)");
    return true;
  }
  // A text that names a file or folder (the scene name: results/<name>): not empty, no '/', not . or ..
  bool file_name(const char* key, std::string& out) {
    const auto f = take(key);
    if (!f) return false;
    text(key, out);
    if (out.empty() || out == "." || out == ".." || out.find('/') != std::string::npos || out.size() > 200)
      ctx_.fail(*f,
                "expected a name usable as a folder name (not empty, at most 200 bytes, no '/', not '.' or "
                "'..'), got '" +
                    excerpt(out) + "'");
    return true;
  }
  bool vec2(const char* key, Vec2& out, const char* unit, const char* /*comment*/ = "") {
    const auto f = take(key);
    if (f) out = to_vec2(ctx_, *f, any(unit));
    return f.has_value();
  }
  bool vec3(const char* key, geometry::Vec3& out, const char* unit, const char* /*comment*/ = "") {
    const auto f = take(key);
    if (f) out = to_vec3(ctx_, *f, any(unit));
    return f.has_value();
  }
  // A number, or the word 'auto' (stored as 0).
  bool zero_is_auto(const char* key, double& out, const Range& r, const char* comment = "") {
    std::optional<double> x;
    if (out > 0.0) x = out;
    const bool given = number_or_auto(key, x, r, comment);
    out = x.value_or(0.0);
    return given;
  }
  bool name(const char* key, std::string& out, const char* /*comment*/ = "") { return file_name(key, out); }
  template <class E>
  bool choice(const char* key, E& out, std::initializer_list<std::pair<const char*, E>> options,
              const char* /*comment*/ = "") {
    const auto f = take(key);
    if (!f) return false;
    std::string names;
    for (const auto& [name, value] : options) {
      if (is_word(f->value, name)) {
        out = value;
        return true;
      }
      names += (names.empty() ? "" : ", ") + std::string(name);
    }
    ctx_.fail(*f, "expected one of " + names + ", got " + describe(f->value));
  }
  // A nested block (an empty reader when absent: its keys keep their defaults).
  MapReader block(const char* key) {
    const auto f = take(key);
    return MapReader(ctx_, f ? *f : Field{YAML::Node(), YAML::Node(), join(self_.path, key)});
  }
  // A block that may be left out; absent or null ('key: null', '--set key=~') means none.
  std::optional<MapReader> optional_block(const char* key) {
    const auto f = take(key);
    if (!f || f->value.IsNull()) return std::nullopt;
    return MapReader(ctx_, *f);
  }

  // The settings_schema.h visitor's blocks: each is read by `fn(reader)` and finished.
  template <class F>
  void block(const char* key, F&& fn) {
    MapReader sub = block(key);
    fn(sub);
    sub.finish();
  }
  template <class F>
  void flow(const char* key, const char* /*comment*/, F&& fn) {
    block(key, std::forward<F>(fn));
  }
  template <class T, class F>
  void optional_block(const char* key, std::optional<T>& out, F&& fn) {
    if (auto sub = optional_block(key)) {
      out.emplace();
      fn(*sub, *out);
      sub->finish();
    }
  }
  // A key with a reader of its own (which takes the key; and may take others, as 'current' beside 'field').
  template <class T, class W>
  void custom(const char* key, T& member, const char* /*comment*/, void (*read)(MapReader&, const char*, T&), W) {
    read(*this, key, member);
  }
  // A check across the block's keys, run by finish() once every key is read and none is unknown.
  void after(std::function<void(MapReader&)> check) { after_.push_back(std::move(check)); }

  // Every key given must have been asked for; then the after() checks.
  void finish() {
    for (const Entry& e : entries_) {
      if (e.used || std::find(known_.begin(), known_.end(), e.name) != known_.end()) continue;
      std::string allowed;
      for (const std::string& k : known_) allowed += (allowed.empty() ? "" : ", ") + k;
      const std::string in = self_.path.empty() ? "at the top level" : "in '" + self_.path + "'";
      const Field f{e.key, e.key, join(self_.path, e.name)};
      throw SceneError(ctx_.where(f) + ": unknown key '" + excerpt(f.path) + "'; allowed " + in + ": " + allowed);
    }
    const std::vector<std::function<void(MapReader&)>> checks = std::move(after_);
    after_.clear();
    for (const auto& check : checks) check(*this);
  }

 private:
  struct Entry {
    std::string name;
    YAML::Node key, value;
    bool used = false;
  };
  const Context& ctx_;
  Field self_;
  std::vector<Entry> entries_;
  std::vector<std::string> known_;
  std::vector<std::function<void(MapReader&)>> after_;
};

}  // namespace polyfloe::scene::detail
