// polyfloe-field's command line (internal to coupling/app): the arguments of import, info and compare, parsed on
// CLI11 and checked before any (long) work.
#pragma once

#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>

#include "openfoam_case.h"
#include "resample.h"

namespace polyfloe::coupling::app {

// A command line the program cannot take: the message names the option and what it takes.
class UsageError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct Args {
  std::string command;
  std::vector<std::string> positional;
  std::filesystem::path output;
  GridSpec grid;
  TimeSelection times;
  CaseTransform transform;
  bool vtk = true;
  long points = 20000;
  unsigned seed = 1;
};

// The arguments after the program's name; throws UsageError.
Args parse(int argc, char** argv);

}  // namespace polyfloe::coupling::app
