// Reads the (timestep, file) entries of a ParaView .pvd collection (no std::regex: GCC 12 warns inside it under
// the sanitizers).
#pragma once

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

namespace polyfloe::tsupport {

inline std::string attribute(const std::string& tag, const std::string& name) {
  const std::string key = " " + name + "=\"";
  const auto a = tag.find(key);
  if (a == std::string::npos) return {};
  const auto b = tag.find('"', a + key.size());
  return b == std::string::npos ? std::string{} : tag.substr(a + key.size(), b - a - key.size());
}

inline std::vector<std::pair<double, std::string>> read_pvd(const std::filesystem::path& file) {
  std::ifstream in(file);
  std::stringstream ss;
  ss << in.rdbuf();
  const std::string text = ss.str();
  std::vector<std::pair<double, std::string>> out;
  for (auto p = text.find("<DataSet"); p != std::string::npos; p = text.find("<DataSet", p + 1)) {
    const auto end = text.find('>', p);
    if (end == std::string::npos) break;
    const std::string tag = text.substr(p, end - p);
    const std::string t = attribute(tag, "timestep"), f = attribute(tag, "file");
    if (!t.empty() && !f.empty()) out.emplace_back(std::stod(t), f);
  }
  return out;
}

}  // namespace polyfloe::tsupport
