// Text formatting shared by the scene reader's messages and resolved_yaml(): numbers that read back exactly,
// quoted strings.
#pragma once

#include <string>

#include "geometry/vec2.h"

namespace polyfloe::scene::detail {

std::string fmt(double x);                 // shortest text that reads back to the same double
std::string fmt(const geometry::Vec2& v);  // "[x, y]"
std::string quoted(const std::string& s);  // a YAML double-quoted string

}  // namespace polyfloe::scene::detail
