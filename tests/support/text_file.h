// A whole file as text, for tests that read what a program wrote (logs, .pvd series, scenes).
#pragma once

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace polyfloe::tsupport {

// The file's bytes ("" when it cannot be opened).
inline std::string slurp(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

}  // namespace polyfloe::tsupport
