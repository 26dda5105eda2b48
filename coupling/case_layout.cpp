// Where an OpenFOAM case keeps its solution and which times it has: reconstructed or decomposed (processor*/),
// steady or transient, and the times an import reads (case_layout, case_is_steady, choose_times of
// openfoam_case.h). Reads folder names and a few files only; the mesh and fields are read in openfoam_case.cpp.
#include "openfoam_case.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "case_detail.h"

namespace polyfloe::coupling {

namespace fs = std::filesystem;
using detail::fail;
using detail::same_time;
using detail::times_text;

namespace {

void check_case(const fs::path& dir) {
  std::error_code ec;
  if (!fs::is_directory(dir, ec)) fail(dir, "no such folder (expected an OpenFOAM case)");
  if (!fs::is_regular_file(dir / "system" / "controlDict", ec))
    fail(dir, "not an OpenFOAM case (no system/controlDict)");
  if (!fs::is_directory(dir / "constant" / "polyMesh", ec))
    fail(dir, "no mesh (constant/polyMesh is missing): run the case's Allrun, or blockMesh, first");
}

struct TimeDir {
  double t;
  std::string name;
};

// The time directories of `dir` (a case or one of its processor*/ folders) that hold U, increasing.
std::vector<TimeDir> times_with_u(const fs::path& dir) {
  std::vector<TimeDir> times;
  std::error_code ec;
  for (const fs::directory_entry& e : fs::directory_iterator(dir, ec)) {
    if (!e.is_directory(ec)) continue;
    const std::string name = e.path().filename().string();
    double t = 0.0;
    const auto [end, err] = std::from_chars(name.data(), name.data() + name.size(), t);
    if (err != std::errc() || end != name.data() + name.size() || !std::isfinite(t)) continue;
    if (fs::is_regular_file(e.path() / "U", ec) || fs::is_regular_file(e.path() / "U.gz", ec))
      times.push_back({t, name});
  }
  std::sort(times.begin(), times.end(), [](const TimeDir& a, const TimeDir& b) { return a.t < b.t; });
  return times;
}

// processor0 ... processorN-1 (decomposePar's folders), checked to be numbered without a gap.
int count_processors(const fs::path& dir) {
  std::vector<int> ids;
  std::error_code ec;
  for (const fs::directory_entry& e : fs::directory_iterator(dir, ec)) {
    const std::string name = e.path().filename().string();
    if (name.rfind("processor", 0) != 0 || !e.is_directory(ec)) continue;
    const std::string digits = name.substr(9);
    int id = -1;
    const auto [end, err] = std::from_chars(digits.data(), digits.data() + digits.size(), id);
    if (err == std::errc() && end == digits.data() + digits.size() && !digits.empty()) {
      ids.push_back(id);
    } else if (name.rfind("processors", 0) == 0) {
      fail(dir, "a decomposed case written with OpenFOAM's collated file handler (" + name +
                    "/), which VTK's "
                    "reader cannot read: reconstruct it with `reconstructPar -case " +
                    dir.string() + "`, or run the solver with -fileHandler uncollated");
    }
  }
  std::sort(ids.begin(), ids.end());
  for (std::size_t k = 0; k < ids.size(); ++k)
    if (ids[k] != static_cast<int>(k))
      fail(dir, "a decomposed case whose processor folders are not processor0 to processor" +
                    std::to_string(ids.size() - 1) + " (processor" + std::to_string(k) + " is missing)");
  return static_cast<int>(ids.size());
}

}  // namespace

CaseLayout case_layout(const fs::path& dir) {
  check_case(dir);
  std::vector<TimeDir> times = times_with_u(dir);
  CaseLayout layout;
  std::error_code ec;
  const int processors = count_processors(dir);
  if (processors > 0) {
    std::vector<TimeDir> decomposed = times_with_u(dir / "processor0");
    if (!decomposed.empty() && (times.empty() || decomposed.back().t > times.back().t)) {
      // Every processor must hold every time: a run stopped while writing leaves one behind.
      for (int p = 1; p < processors; ++p) {
        const std::vector<TimeDir> other = times_with_u(dir / ("processor" + std::to_string(p)));
        for (const TimeDir& d : decomposed)
          if (std::none_of(other.begin(), other.end(), [&](const TimeDir& o) { return same_time(o.t, d.t); }))
            fail(dir, "a decomposed case whose processor" + std::to_string(p) + "/ has no U at t = " + d.name +
                          " (processor0/ has it): the run did not finish writing that time; choose the times every "
                          "processor holds with --times");
      }
      layout.decomposed = true;
      layout.processors = processors;
      times = std::move(decomposed);
    }
  }
  if (times.empty()) fail(dir, "no time directory holds a velocity field U");
  for (const TimeDir& d : times) {
    layout.times.push_back(d.t);
    layout.names.push_back(d.name);
  }
  return layout;
}

std::vector<double> case_times(const fs::path& dir) { return case_layout(dir).times; }

bool case_is_steady(const fs::path& dir) {
  std::ifstream in(dir / "system" / "fvSchemes");
  std::stringstream ss;
  ss << in.rdbuf();
  // ddtSchemes { ... default steadyState; ... } (a plain scan: GCC 12 warns inside <regex> under the sanitizers)
  const std::string text = ss.str();
  const std::size_t key = text.find("ddtSchemes");
  if (key == std::string::npos) return false;
  const std::size_t open = text.find('{', key), close = text.find('}', key);
  if (open == std::string::npos || close == std::string::npos || close < open) return false;
  std::istringstream block(text.substr(open + 1, close - open - 1));
  std::string word, previous;
  while (block >> word) {
    if (previous == "default" && word.rfind("steadyState", 0) == 0) return true;
    previous = word;
  }
  return false;
}

std::vector<double> choose_times(const fs::path& dir, const CaseLayout& layout, const TimeSelection& which,
                                 bool steady) {
  const std::vector<double>& available = layout.times;
  using Kind = TimeSelection::Kind;
  switch (which.kind) {
    case Kind::automatic:
      if (steady) return {available.back()};
      // A transient case's t = 0 is its initial condition, not a solution: left out when later times exist.
      if (available.size() > 1 && same_time(available.front(), 0.0))
        return std::vector<double>(available.begin() + 1, available.end());
      return available;
    case Kind::all: return available;
    case Kind::latest: return {available.back()};
    case Kind::listed: {
      if (which.times.empty()) fail(dir, "no time chosen");
      std::vector<double> chosen;
      for (const double t : which.times) {
        const auto it = std::find_if(available.begin(), available.end(), [t](double a) { return same_time(a, t); });
        if (it == available.end())
          fail(dir, "no time directory " + times_text({t}) + " with U (the case has " + times_text(available) + ")");
        chosen.push_back(*it);
      }
      std::sort(chosen.begin(), chosen.end());
      chosen.erase(std::unique(chosen.begin(), chosen.end()), chosen.end());
      return chosen;
    }
    case Kind::range: {
      if (which.times.size() != 2) fail(dir, "a time range needs its two ends");
      const double lo = which.times[0], hi = which.times[1];  // an open end is infinite
      std::vector<double> chosen;
      for (const double a : available)
        if (a >= lo - 1e-6 * std::max(1.0, std::abs(a)) && a <= hi + 1e-6 * std::max(1.0, std::abs(a)))
          chosen.push_back(a);
      if (chosen.empty())
        fail(dir, "no time directory with U in " + times_text({lo}) + ":" + times_text({hi}) + " (the case has " +
                      times_text(available) + ")");
      return chosen;
    }
  }
  return available;
}

}  // namespace polyfloe::coupling
