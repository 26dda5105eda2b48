#include "scene/schema.h"

#include <cctype>
#include <charconv>
#include <cmath>

#include "contact/narrow_phase_planar.h"
#include "geometry/polygon.h"

namespace polyfloe::scene::detail {

// What a node is, for "expected X, got Y".
std::string excerpt(const std::string& text) {
  constexpr std::size_t kShown = 60;
  if (text.size() <= kShown) return text;
  std::size_t cut = 40;
  while (cut > 0 && (static_cast<unsigned char>(text[cut]) & 0xC0) == 0x80) --cut;  // not inside a UTF-8 character
  return text.substr(0, cut) + "... (" + std::to_string(text.size()) + " characters)";
}

std::string describe(const YAML::Node& n) {
  if (!n.IsDefined() || n.IsNull()) return "nothing";
  if (n.IsMap()) return "a map";
  if (n.IsSequence()) return "a list of " + std::to_string(n.size()) + " items";
  if (n.Tag() == "!") return "the quoted string '" + excerpt(n.Scalar()) + "'";
  return "'" + excerpt(n.Scalar()) + "'";
}

// ---------------------------------------------------------------------------------------------------------------
// Typed values

bool non_finite_spelling(const std::string& s) {
  std::string t = s;
  if (!t.empty() && (t[0] == '+' || t[0] == '-')) t.erase(0, 1);
  std::transform(t.begin(), t.end(), t.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return t == ".nan" || t == ".inf" || t == "nan" || t == "inf" || t == "infinity";
}

// Reads a plain YAML scalar as a double: decimal or exponent notation, optional sign; .nan/.inf are non-finite.
NumberText parse_double(const std::string& s, double& x) {
  if (non_finite_spelling(s)) return NumberText::non_finite;
  const char* begin = s.data() + (!s.empty() && s[0] == '+' ? 1 : 0);
  const char* end = s.data() + s.size();
  const auto res = std::from_chars(begin, end, x);
  if (res.ec == std::errc::result_out_of_range) return NumberText::non_finite;
  if (res.ec != std::errc() || res.ptr != end || begin == end) return NumberText::not_a_number;
  return std::isfinite(x) ? NumberText::ok : NumberText::non_finite;
}

double to_number(const Context& ctx, const Field& f, const Range& r, const char* alternative) {
  double x = 0.0;
  const NumberText t = plain_scalar(f.value) ? parse_double(f.value.Scalar(), x) : NumberText::not_a_number;
  if (t == NumberText::not_a_number)
    ctx.fail(f, "expected a number [" + std::string(r.unit) + "]" + alternative + ", got " + describe(f.value));
  if (t == NumberText::non_finite) ctx.fail(f, f.value.Scalar() + " is not a finite number");
  if (!r.contains(x)) ctx.fail(f, excerpt(f.value.Scalar()) + " is outside the allowed range " + r.text());
  return x;
}

long long to_integer(const Context& ctx, const Field& f, long long lo, long long hi) {
  const std::string range = "[" + std::to_string(lo) + ", " + std::to_string(hi) + "]";
  if (!plain_scalar(f.value)) ctx.fail(f, "expected an integer in " + range + ", got " + describe(f.value));
  const std::string& s = f.value.Scalar();
  const char* begin = s.data() + (!s.empty() && s[0] == '+' ? 1 : 0);
  const char* end = s.data() + s.size();
  long long x = 0;
  const auto res = std::from_chars(begin, end, x);
  if (res.ec != std::errc() || res.ptr != end || begin == end)
    ctx.fail(f, "expected an integer in " + range + ", got " + describe(f.value));
  if (x < lo || x > hi) ctx.fail(f, s + " is outside the allowed range " + range);
  return x;
}

std::uint64_t to_unsigned64(const Context& ctx, const Field& f) {
  const char* what = "expected a non-negative integer in [0, 2^64 - 1], got ";
  if (!plain_scalar(f.value)) ctx.fail(f, what + describe(f.value));
  const std::string& s = f.value.Scalar();
  const char* begin = s.data() + (!s.empty() && s[0] == '+' ? 1 : 0);
  const char* end = s.data() + s.size();
  std::uint64_t x = 0;
  const auto res = std::from_chars(begin, end, x);
  if (res.ec != std::errc() || res.ptr != end || begin == end) ctx.fail(f, what + describe(f.value));
  return x;
}

bool to_bool(const Context& ctx, const Field& f) {
  bool b = false;
  if (!plain_scalar(f.value) || !YAML::convert<bool>::decode(f.value, b))
    ctx.fail(f, "expected true or false, got " + describe(f.value));
  return b;
}

// The items of a list, as Fields named PATH.0, PATH.1, ...
std::vector<Field> list_items(const Context& ctx, const Field& f, const std::string& what) {
  if (!f.value.IsSequence()) ctx.fail(f, "expected " + what + ", got " + describe(f.value));
  std::vector<Field> items;
  for (std::size_t i = 0; i < f.value.size(); ++i)
    items.push_back({f.value[i], YAML::Node(), join(f.path, std::to_string(i))});
  return items;
}

Vec2 to_vec2(const Context& ctx, const Field& f, const Range& r) {
  const std::string what = "a list of 2 numbers [x, y] [" + std::string(r.unit) + "]";
  const std::vector<Field> items = list_items(ctx, f, what);
  if (items.size() != 2) ctx.fail(f, "expected " + what + ", got " + describe(f.value));
  return {to_number(ctx, items[0], r), to_number(ctx, items[1], r)};
}

std::vector<Vec2> to_polygon(const Context& ctx, const Field& f) {
  const std::string what = "a list of at least 3 points [[x, y], ...] [m]";
  std::vector<Vec2> v;
  for (const Field& item : list_items(ctx, f, what)) v.push_back(to_vec2(ctx, item, any("m")));
  if (v.size() < 3) ctx.fail(f, "expected " + what + ", got " + describe(f.value));
  if (v.size() > static_cast<std::size_t>(contact::kMaxPolygonVertices))
    ctx.fail(f, "a polygon may have at most " + std::to_string(contact::kMaxPolygonVertices) + " vertices, got " +
                    std::to_string(v.size()));
  if (const std::string err = geometry::convexity_error(v); !err.empty()) ctx.fail(f, err);
  return v;
}

}  // namespace polyfloe::scene::detail
