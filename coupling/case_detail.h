// Pieces the files of the OpenFOAM case reader share (internal to coupling/).
#pragma once

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <sstream>
#include <string>
#include <vector>

#include "openfoam_case.h"

namespace polyfloe::coupling::detail {

[[noreturn]] inline void fail(const std::filesystem::path& dir, const std::string& what) {
  throw CouplingError(dir.string() + ": " + what);
}

// "t1, t2, ..." as the times print in messages.
inline std::string times_text(const std::vector<double>& t) {
  std::ostringstream os;
  for (std::size_t i = 0; i < t.size(); ++i) os << (i ? ", " : "") << t[i];
  return os.str();
}

// Two times of a case are the same time (time folder names and the reader's values round differently).
inline bool same_time(double a, double b) { return std::abs(a - b) <= 1e-6 * std::max(1.0, std::abs(a)); }

}  // namespace polyfloe::coupling::detail
