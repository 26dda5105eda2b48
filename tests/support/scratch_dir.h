// A scratch folder for one test: in the system's temporary folder, its name made unique to this process, so that
// two test runs at once (two checkouts, or ctest -j with repeated tests) never write into each other's output.
#pragma once

#include <unistd.h>

#include <filesystem>
#include <string>

namespace polyfloe::tsupport {

inline std::filesystem::path scratch_dir(const std::string& name) {
  return std::filesystem::temp_directory_path() / (name + "_" + std::to_string(::getpid()));
}

}  // namespace polyfloe::tsupport
