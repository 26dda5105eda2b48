// `polyfloe field` (coupling/app/field_main.cpp, run through polyfloe's git-style dispatch): bad arguments and
// cases that are not OpenFOAM cases give exit code 2 with the option or folder named and no output file; `info`
// describes a field file. (The import itself is tested end to end in tests/validation/test_strait_openfoam.cpp.)
#include <gtest/gtest.h>
#include <stdlib.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>

#include "cli_support.h"

namespace {

namespace fs = std::filesystem;

using Result = polyfloe::tsupport::CommandResult;
Result field(const std::string& args) { return polyfloe::tsupport::run_polyfloe("field " + args); }

class FieldCli : public ::testing::Test {
 protected:
  void SetUp() override {
    std::string tmpl = (fs::temp_directory_path() / "polyfloe_field_cli.XXXXXX").string();
    ASSERT_NE(mkdtemp(tmpl.data()), nullptr);
    dir_ = tmpl;
  }
  void TearDown() override { fs::remove_all(dir_); }
  // Exit code 2, the message, and nothing written into the scratch folder but what the test made.
  void expect_refused(const std::string& args, const std::string& message) {
    const Result r = field(args);
    EXPECT_EQ(r.code, 2) << args << "\n" << r.output;
    EXPECT_NE(r.output.find(message), std::string::npos) << args << "\n" << r.output;
    EXPECT_FALSE(fs::exists(dir_ / "out.h5")) << args;
    EXPECT_FALSE(fs::exists(dir_ / "out.pvd")) << args;
  }
  fs::path dir_;
};

TEST_F(FieldCli, RefusesBadArguments) {
  const std::string out = " -o " + (dir_ / "out.h5").string();
  expect_refused("", "polyfloe field: no command given");
  expect_refused("convert x", "unknown command 'convert' (import, info, compare)");
  expect_refused("import", "import takes CASE, got 0 argument(s)");
  expect_refused("import " + dir_.string(), "import needs -o FILE");
  expect_refused("import " + dir_.string() + out + " --cell -5", "--cell: expected one spacing > 0 m");
  expect_refused("import " + dir_.string() + out + " --cell ten", "--cell: expected numbers separated by commas, got 'ten'");
  expect_refused("import " + dir_.string() + out + " --bounds 0,0,10", "--bounds: expected X0,Y0,X1,Y1 [m]");
  expect_refused("import " + dir_.string() + out + " --bounds 0,0,-10,10", "with X1 > X0 and Y1 > Y0");
  expect_refused("import " + dir_.string() + out + " --z -1,nan", "--z: expected numbers separated by commas");
  expect_refused("import " + dir_.string() + out + " --frobnicate", "unknown option '--frobnicate'");
  expect_refused("compare " + dir_.string(), "compare takes CASE FILE, got 1 argument(s)");
  expect_refused("compare a b --points 0", "--points: expected a whole number in [1, 1e8]");
}

TEST_F(FieldCli, RefusesFoldersThatAreNotReadyOpenFoamCases) {
  const std::string out = " -o " + (dir_ / "out.h5").string();
  expect_refused("import " + (dir_ / "none").string() + out,
                 (dir_ / "none").string() + ": no such folder (expected an OpenFOAM case)");
  fs::create_directories(dir_ / "case" / "system");
  expect_refused("import " + (dir_ / "case").string() + out,
                 (dir_ / "case").string() + ": not an OpenFOAM case (no system/controlDict)");
  std::ofstream(dir_ / "case" / "system" / "controlDict") << "application simpleFoam;\n";
  expect_refused("import " + (dir_ / "case").string() + out,
                 "no mesh (constant/polyMesh is missing): run the case's Allrun, or blockMesh, first");
  fs::create_directories(dir_ / "case" / "constant" / "polyMesh");
  fs::create_directories(dir_ / "case" / "0");
  expect_refused("import " + (dir_ / "case").string() + out, "no time directory holds a velocity field U");
}

TEST_F(FieldCli, InfoDescribesAFieldFileAndRefusesOthers) {
  const fs::path two = fs::path(POLYFLOE_SOURCE_DIR) / "tests" / "bad_input" / "fields" / "two_snapshots.h5";
  const Result r = field("info " + two.string());
  EXPECT_EQ(r.code, 0) << r.output;
  EXPECT_NE(r.output.find("  t: 2 from 0 to 600 s (0, 600)"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("  x: 4 from -100 to 2000 m"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("water: 100 % of the nodes; speed up to 1 m/s"), std::string::npos) << r.output;
  expect_refused("info " + (dir_ / "missing.h5").string(), (dir_ / "missing.h5").string() + ": no such file");
  const fs::path nan = fs::path(POLYFLOE_SOURCE_DIR) / "tests" / "bad_input" / "fields" / "nan.h5";
  expect_refused("info " + nan.string(), "v is not finite at node (t 1, z 0, y 1, x 2)");
  const Result help = field("--help");
  EXPECT_EQ(help.code, 0);
  EXPECT_NE(help.output.find("polyfloe field import CASE -o FILE"), std::string::npos);
}

}  // namespace
