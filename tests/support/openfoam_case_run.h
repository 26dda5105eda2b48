// A copy of one of of_cases/ run with `Allrun --quick` in a scratch folder, for the OpenFOAM end-to-end tests
// (each suite runs its case once, in SetUpTestSuite). Needs POLYFLOE_SOURCE_DIR and POLYFLOE_BINARY (the tests'
// compile definitions).
#pragma once

#include <gtest/gtest.h>
#include <stdlib.h>

#include <cstdlib>
#include <filesystem>
#include <string>

#include "text_file.h"

namespace polyfloe::tsupport {

// A copy of of_cases/<name> (and common/) run once with `Allrun --quick` for every test of a suite.
struct CaseRun {
  std::filesystem::path root, dir;
  int status = -1;
  void run(const char* name) {
    std::string tmpl = (std::filesystem::temp_directory_path() / "polyfloe_test_of_case.XXXXXX").string();
    ASSERT_NE(mkdtemp(tmpl.data()), nullptr);
    root = tmpl;
    std::filesystem::create_directories(root / "of_cases");
    const std::filesystem::path kSource = POLYFLOE_SOURCE_DIR;
    const std::filesystem::path kBuild = std::filesystem::path(POLYFLOE_BINARY).parent_path();
    std::filesystem::copy(kSource / "of_cases" / "common", root / "of_cases" / "common",
                          std::filesystem::copy_options::recursive);
    // tidal links some files to strait's
    std::filesystem::copy(kSource / "of_cases" / "strait", root / "of_cases" / "strait",
                          std::filesystem::copy_options::recursive);
    if (std::string(name) != "strait")
      std::filesystem::copy(kSource / "of_cases" / name, root / "of_cases" / name,
                            std::filesystem::copy_options::recursive | std::filesystem::copy_options::copy_symlinks);
    dir = root / "of_cases" / name;
    // A copy of the source tree may hold a previous run's outputs: start clean.
    const std::string clean = "bash " + (dir / "Allclean").string();
    ASSERT_EQ(std::system(clean.c_str()), 0);
    const std::string cmd = "POLYFLOE_ROOT=" + kSource.string() + " POLYFLOE_BUILD_DIR=" + kBuild.string() + " bash " +
                            (dir / "Allrun").string() + " --quick > " + (root / "allrun.log").string() + " 2>&1";
    status = std::system(cmd.c_str());
  }
  void check() const {
    ASSERT_EQ(status, 0) << dir.filename().string()
                         << "/Allrun --quick failed (is OpenFOAM installed? bash scripts/setup.sh):\n"
                         << tsupport::slurp(root / "allrun.log");
  }
  ~CaseRun() {
    std::error_code ec;
    if (!root.empty()) std::filesystem::remove_all(root, ec);
  }
};

}  // namespace polyfloe::tsupport
