// The study drivers' JSON (tests/bench): nlohmann::ordered_json (keys in the order written) and one writer.
#pragma once

#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

namespace polyfloe::tsupport {

using Json = nlohmann::ordered_json;

// A measurement that may have no value (NaN, inf): -1 in the JSON, which the plotting scripts read as "none".
inline double or_none(double x) { return std::isfinite(x) ? x : -1.0; }
inline Json or_none(const std::vector<double>& v) {
  Json a = Json::array();
  for (double x : v) a.push_back(or_none(x));
  return a;
}

// Writes `j` (indented by 2) to `file`, creating its folder; false, with a message on stderr, if it cannot.
inline bool write_json(const std::string& file, const Json& j) {
  if (const std::filesystem::path parent = std::filesystem::path(file).parent_path(); !parent.empty()) {
    std::error_code ec;
    std::filesystem::create_directories(parent, ec);  // -o results/x.json on a fresh checkout
  }
  std::ofstream out(file);
  out << j.dump(2) << "\n";
  out.close();
  if (!out) {
    std::fprintf(stderr, "cannot write %s\n", file.c_str());
    return false;
  }
  return true;
}

}  // namespace polyfloe::tsupport
