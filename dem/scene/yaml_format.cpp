#include "scene/yaml_format.h"

#include <charconv>
#include <cmath>
#include <cstdio>

namespace polyfloe::scene::detail {

using geometry::Vec2;

// Shortest text that reads back to the same double.
std::string fmt(double x) {
  if (std::isnan(x)) return ".nan";
  if (std::isinf(x)) return x > 0 ? "inf" : "-inf";
  char buf[64];
  const auto r = std::to_chars(buf, buf + sizeof buf, x);
  std::string t(buf, r.ptr);
  // 1e+09 -> 1e9, 3.3e-05 -> 3.3e-5
  if (const std::size_t e = t.find('e'); e != std::string::npos) {
    std::size_t d = e + 1;
    if (t[d] == '+')
      t.erase(d, 1);
    else if (t[d] == '-')
      ++d;
    while (d + 1 < t.size() && t[d] == '0') t.erase(d, 1);
  }
  return t;
}

std::string fmt(const Vec2& v) { return "[" + fmt(v.x()) + ", " + fmt(v.y()) + "]"; }

std::string quoted(const std::string& s) {
  std::string out = "\"";
  for (char c : s) {
    switch (c) {
      case '"': out += "\\\""; break;
      case '\\': out += "\\\\"; break;
      case '\n': out += "\\n"; break;
      case '\t': out += "\\t"; break;
      default:
        if (static_cast<unsigned char>(c) < 0x20) {
          char buf[8];
          std::snprintf(buf, sizeof buf, "\\x%02x", static_cast<unsigned>(static_cast<unsigned char>(c)));
          out += buf;
        } else {
          out += c;
        }
    }
  }
  return out + "\"";
}

}  // namespace polyfloe::scene::detail
