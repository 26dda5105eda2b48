// `polyfloe field` (coupling/app/field_main.cpp, run through polyfloe's git-style dispatch): bad arguments and
// cases that are not OpenFOAM cases give exit code 2 with the option or folder named and no output file; `info`
// describes a field file; a decomposed case is read from its processor folders, a 3-D case's levels are heights
// below its surface, the case can be scaled, rotated and shifted as it is read, and files VTK's reader cannot parse
// are written out plainly by OpenFOAM. (The import itself is tested end to end in
// tests/validation/test_strait_openfoam.cpp and tests/validation/test_openfoam_tutorials.cpp.)
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
Result field(const std::string& args, const std::string& env = "") {
  return polyfloe::tsupport::run_polyfloe("field " + args, env);
}

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

TEST_F(FieldCli, BadCommandsArgumentsAndOptionsExitTwoWithTheReasonAndWriteNothing) {
  const std::string out = " -o " + (dir_ / "out.h5").string();
  expect_refused("", "polyfloe field: no command given");
  expect_refused("convert x", "unknown command 'convert' (import, info, compare)");
  expect_refused("import", "import takes CASE, got 0 argument(s)");
  expect_refused("import " + dir_.string(), "import needs -o FILE");
  expect_refused("import " + dir_.string() + out + " --cell -5", "--cell: expected one spacing > 0 m");
  expect_refused("import " + dir_.string() + out + " --cell ten",
                 "--cell: expected numbers separated by commas, got 'ten'");
  expect_refused("import " + dir_.string() + out + " --bounds 0,0,10", "--bounds: expected X0,Y0,X1,Y1 [m]");
  expect_refused("import " + dir_.string() + out + " --bounds 0,0,-10,10", "with X1 > X0 and Y1 > Y0");
  expect_refused("import " + dir_.string() + out + " --z -1,nan", "--z: expected numbers separated by commas");
  expect_refused("import " + dir_.string() + out + " --frobnicate", "not expected: --frobnicate");
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

namespace {

// A decomposed case whose solution was never reconstructed: the case's own 0/U is the initial condition. Importing
// it used to give that as the flow, with exit 0; now it is refused, naming reconstructPar.
// Writes a 3-D box case (blockMesh): x, y in [0, 100] m, z in [0, 10] m (the seabed at 0, the surface at 10), 4 x 4
// x 5 cells, and U = (z_c / 10 m) (1, 0, 0) m/s at the cell centres z_c = 1, 3, 5, 7, 9 m. Returns false without
// OpenFOAM's blockMesh.
bool write_box_case(const fs::path& c) {
  if (std::system("command -v blockMesh > /dev/null 2>&1") != 0) return false;
  for (const char* d : {"system", "constant", "0"}) fs::create_directories(c / d);
  const std::string header = "FoamFile { version 2.0; format ascii; class dictionary; object x; }\n";
  std::ofstream(c / "system" / "controlDict")
      << header
      << "application simpleFoam;\nstartFrom startTime;\n"
         "startTime 0;\nstopAt endTime;\nendTime 1;\ndeltaT 1;\nwriteControl timeStep;\nwriteInterval 1;\n";
  std::ofstream(c / "system" / "fvSchemes") << header << "ddtSchemes { default steadyState; }\n";
  std::ofstream(c / "system" / "fvSolution") << header;
  std::ofstream(c / "system" / "blockMeshDict")
      << header
      << "convertToMeters 1;\nvertices ((0 0 0) (100 0 0) (100 100 0) (0 100 0) (0 0 10) (100 0 10) "
         "(100 100 10) (0 100 10));\nblocks (hex (0 1 2 3 4 5 6 7) (4 4 5) simpleGrading (1 1 1));\n"
         "edges ();\nboundary ();\ndefaultPatch { name walls; type patch; }\n";
  std::ofstream u(c / "0" / "U");
  u << "FoamFile { version 2.0; format ascii; class volVectorField; object U; }\ndimensions [0 1 -1 0 0 0 0];\n"
    << "internalField nonuniform List<vector> 80 (\n";
  for (int k = 0; k < 5; ++k)
    for (int n = 0; n < 16; ++n) u << "(" << (2 * k + 1) / 10.0 << " 0 0)\n";
  u << ");\nboundaryField { walls { type zeroGradient; } }\n";
  u.close();
  const std::string mesh = "cd " + c.string() +
                           " && WM_PROJECT_DIR=/usr/share/openfoam FOAM_ETC=/usr/share/openfoam/etc "
                           "blockMesh > log.blockMesh 2>&1";
  return std::system(mesh.c_str()) == 0;
}

// The value of the field file at level index iz, node (ix, iy) of snapshot it, component k (h5py).
double file_u(const fs::path& file, int iz, int ix, int iy, int k = 0, int it = 0) {
  const std::string py = "/usr/bin/python3 -c \"import h5py; f = h5py.File('" + file.string() +
                         "', 'r'); print('%.9f' % f['U'][" + std::to_string(it) + ", " + std::to_string(iz) + ", " +
                         std::to_string(iy) + ", " + std::to_string(ix) + ", " + std::to_string(k) + "])\"";
  FILE* p = popen(py.c_str(), "r");
  double v = -1.0;
  if (p) {
    if (std::fscanf(p, "%lf", &v) != 1) v = -1.0;
    pclose(p);
  }
  return v;
}

// A 3-D case whose water surface is not at z = 0 (the seabed is): levels are heights below the surface (the mesh's
// top unless --surface says otherwise), so -5 m is mid-depth. They used to be clamped into the mesh at z = 0, the
// seabed: a wrong current with exit 0. A level outside the mesh's depth is refused, naming --z and --surface.
TEST_F(FieldCli, LevelsAreHeightsBelowTheSurfaceOfA3dCaseAndNeverClamped) {
  const fs::path c = dir_ / "box";
  if (!write_box_case(c)) GTEST_SKIP() << "OpenFOAM's blockMesh is not installed";
  const fs::path out = dir_ / "out.h5";
  Result r = field("import " + c.string() + " -o " + out.string() + " --cell 25 --z -5,-3 --no-vtk");
  ASSERT_EQ(r.code, 0) << r.output;
  EXPECT_NE(r.output.find("z 0 to 10 m; water surface at z = 10 m (the top of the mesh"), std::string::npos)
      << r.output;
  // Interior node (x = y = 50 m): U at z = 5 m and 7 m, linear between the cell-centre values 0.1 z (VTK's reader
  // holds the values in single precision: 1e-6).
  EXPECT_NEAR(file_u(out, 0, 2, 2), 0.5, 1e-6);
  EXPECT_NEAR(file_u(out, 1, 2, 2), 0.7, 1e-6);
  // compare measures the file against OpenFOAM's own cell values too: the cells whose depth holds the level
  // (16 per level), the grid at their centres within the reader's single precision.
  const Result cmp = field("compare " + c.string() + " " + out.string() + " --points 100");
  ASSERT_EQ(cmp.code, 0) << cmp.output;
  EXPECT_NE(cmp.output.find("t = 0 s, z = -5 m: RMS"), std::string::npos) << cmp.output;
  EXPECT_NE(cmp.output.find("m/s (the cells' speed reaches 0.5 m/s; 16 cells)"), std::string::npos) << cmp.output;
  const std::size_t at = cmp.output.find("Largest difference from the cell values: ");
  ASSERT_NE(at, std::string::npos) << cmp.output;
  EXPECT_LT(std::stod(cmp.output.substr(at + 41)), 1e-6) << cmp.output;
  fs::remove(out);
  r = field("import " + c.string() + " -o " + out.string() + " --cell 25 --z -1 --surface 5 --no-vtk");
  ASSERT_EQ(r.code, 0) << r.output;
  EXPECT_NEAR(file_u(out, 0, 2, 2), 0.4, 1e-6);  // z = 5 - 1 = 4 m
  fs::remove(out);
  // Time ranges as OpenFOAM's tools take them: A:B, an end left open.
  for (const char* t : {"1", "2"}) fs::copy(c / "0", c / t);
  r = field("import " + c.string() + " -o " + out.string() + " --cell 25 --times 1: --no-vtk");
  ASSERT_EQ(r.code, 0) << r.output;
  EXPECT_NE(r.output.find("2 time(s)"), std::string::npos) << r.output;
  fs::remove(out);
  expect_refused("import " + c.string() + " -o " + out.string() + " --times 5:9",
                 "no time directory with U in 5:9 (the case has 0, 1, 2)");
  expect_refused("import " + c.string() + " -o " + out.string() + " --times 2:1", "a range is A:B with A <= B");
  // A spacing that would need 4e8 nodes is refused with the grid's size before anything is allocated.
  expect_refused("import " + c.string() + " -o " + out.string() + " --cell 0.01",
                 "a grid of 10001 x 10001 nodes at 0.01 m spacing, x 4 level(s) x 1 time(s) is 4.0008e+08 nodes");
  expect_refused("import " + c.string() + " -o " + out.string() + " --cell 25 --z -12,0",
                 "level -12 m lies at z = -2 m, outside the mesh's depth [0, 10] m (the water surface taken at z = 10 "
                 "m, the top of the mesh); give levels from -10 to 0 m (--z), or the surface (--surface Z)");
}

// The case named by its case.foam (as ParaView opens it); output names checked before the import; VTK's own error
// lines (colour codes, source lines) turned into one line of the message, with the fix for #includeEtc.
TEST_F(FieldCli, CaseFoamNamesTheCaseAndVtkErrorsBecomeOneClearLine) {
  const fs::path c = dir_ / "box";
  if (!write_box_case(c)) GTEST_SKIP() << "OpenFOAM's blockMesh is not installed";
  std::ofstream(c / "case.foam") << "";
  const fs::path out = dir_ / "out.h5";
  Result r =
      field("import " + (c / "case.foam").string() + " -o " + out.string() + " --cell 25 --bounds -50,0,100,100");
  EXPECT_EQ(r.code, 0) << r.output;
  fs::remove(out);
  // field.pvd blanks land (x < 0 here: outside the mesh) with VTK's ghost array instead of showing still water.
  const std::string py = "/usr/bin/python3 -c \"import vtk; r = vtk.vtkXMLRectilinearGridReader(); r.SetFileName('" +
                         (dir_ / "out" / "out_0000.vtr").string() +
                         "'); r.Update(); g = r.GetOutput().GetPointData().GetArray('vtkGhostType'); "
                         "print(g.GetValue(0), g.GetValue(3))\"";
  FILE* p = popen(py.c_str(), "r");
  ASSERT_NE(p, nullptr);
  int land = -1, water = -1;
  EXPECT_EQ(std::fscanf(p, "%d %d", &land, &water), 2);
  pclose(p);
  EXPECT_EQ(land, 2);   // vtkDataSetAttributes::HIDDENPOINT: x = -50 m
  EXPECT_EQ(water, 0);  // x = 25 m
  fs::remove_all(dir_ / "out");
  fs::remove(dir_ / "out.pvd");
  expect_refused("import " + c.string() + " -o " + (dir_ / "out").string(), "a field file is HDF5, named FILE.h5");
  expect_refused("import " + c.string() + " -o " + (dir_ / "out.vtr").string(), "got the extension '.vtr'");
  expect_refused("import " + c.string() + " -o " + (dir_ / "no" / "out.h5").string(), "does not exist");
  // 0/U as OpenFOAM's tutorials write it: #includeEtc in its boundaryField, which VTK's reader cannot expand.
  std::string text;
  {
    std::ifstream in(c / "0" / "U");
    text.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  }
  text.replace(text.find("boundaryField {"), 15, "boundaryField {\n#includeEtc \"caseDicts/setConstraintTypes\"\n");
  std::ofstream(c / "0" / "U") << text;
  // Without OpenFOAM: refused, VTK's own error turned into one line with the fix.
  r = field("import " + c.string() + " -o " + out.string() + " --cell 25 --no-vtk", "PATH=/nowhere");
  EXPECT_EQ(r.code, 2) << r.output;
  EXPECT_NE(r.output.find("VTK's OpenFOAM reader said: Error reading line"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("Unsupported directive includeEtc"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("install OpenFOAM (bash scripts/setup.sh), or write the field out plainly with "
                          "OpenFOAM's `postProcess -fields '(U)' -func 'writeObjects(U)'`"),
            std::string::npos)
      << r.output;
  EXPECT_EQ(r.output.find("\x1b"), std::string::npos) << r.output;
  EXPECT_EQ(r.output.find("ERR|"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(out));
  // With OpenFOAM: read from a scratch copy OpenFOAM wrote out plainly, the same values, the case untouched.
  r = field("import " + c.string() + " -o " + out.string() + " --cell 25 --z -5 --no-vtk");
  ASSERT_EQ(r.code, 0) << r.output;
  EXPECT_NE(r.output.find("read from a copy OpenFOAM wrote out plainly"), std::string::npos) << r.output;
  EXPECT_NEAR(file_u(out, 0, 2, 2), 0.5, 1e-6);
  std::ifstream again(c / "0" / "U");
  EXPECT_EQ(std::string(std::istreambuf_iterator<char>(again), std::istreambuf_iterator<char>()), text);
}

// Runs OpenFOAM's decomposePar on the box case (2 processors, split in x) and makes the decomposed initial
// condition the processors' solution at t = 10 s: what a solver run with -parallel leaves (the case's own 0/ holds
// the initial condition, here set to rest). Returns false without OpenFOAM.
bool decompose_box_case(const fs::path& c) {
  std::ofstream(c / "system" / "decomposeParDict")
      << "FoamFile { version 2.0; format ascii; class dictionary; object decomposeParDict; }\n"
         "numberOfSubdomains 2;\nmethod simple;\ncoeffs { n (2 1 1); }\nsimpleCoeffs { n (2 1 1); delta 0.001; }\n";
  const std::string cmd = "cd " + c.string() +
                          " && WM_PROJECT_DIR=/usr/share/openfoam FOAM_ETC=/usr/share/openfoam/etc "
                          "decomposePar > log.decomposePar 2>&1";
  if (std::system(cmd.c_str()) != 0) return false;
  for (const char* p : {"processor0", "processor1"}) fs::rename(c / p / "0", c / p / "10");
  std::ofstream(c / "0" / "U") << "FoamFile { version 2.0; format ascii; class volVectorField; object U; }\n"
                                  "dimensions [0 1 -1 0 0 0 0];\ninternalField uniform (0 0 0);\n"
                                  "boundaryField { walls { type zeroGradient; } }\n";
  return true;
}

// A decomposed case (decomposePar, a parallel run, not reconstructed) is read from its processor folders: the
// solution, not the case's own 0/U (the initial condition), which used to be imported with exit 0. A processor that
// lacks a time the others hold, or OpenFOAM's collated processors folder, is refused with the fix.
TEST_F(FieldCli, ADecomposedCaseIsReadFromItsProcessorFolders) {
  const fs::path c = dir_ / "box";
  if (!write_box_case(c) || !decompose_box_case(c)) GTEST_SKIP() << "OpenFOAM is not installed";
  const fs::path out = dir_ / "out.h5";
  Result r = field("import " + c.string() + " -o " + out.string() + " --cell 25 --z -5,-3 --no-vtk");
  ASSERT_EQ(r.code, 0) << r.output;
  EXPECT_NE(r.output.find("decomposed: read from 2 processor folders"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("times read: 10 s of the case's 10 s"), std::string::npos) << r.output;
  // Both halves of the mesh (x = 25 m on processor0, 75 m on processor1) and the node on the cut (50 m).
  for (const int ix : {1, 2, 3}) {
    EXPECT_NEAR(file_u(out, 0, ix, 2), 0.5, 1e-6) << ix;
    EXPECT_NEAR(file_u(out, 1, ix, 2), 0.7, 1e-6) << ix;
  }
  fs::remove(out);
  fs::remove_all(c / "processor1" / "10");
  expect_refused("import " + c.string() + " -o " + out.string(),
                 "a decomposed case whose processor1/ has no U at t = 10 (processor0/ has it)");
  fs::create_directories(c / "processors2");
  expect_refused("import " + c.string() + " -o " + out.string(), "collated file handler (processors2/)");
}

// --scale, --rotate, --translate and --velocity-scale place a case as it is read: the box (x, y in [0, 100] m, z in
// [0, 10] m, U = 0.1 z (1, 0, 0) m/s) scaled by 2, turned 90 degrees and shifted by (10, 0, -20) m lies in x in
// [-190, 10] m, y in [0, 200] m, z in [-20, 0] m, and flows along +y at half the speed.
TEST_F(FieldCli, TransformsPlaceTheCaseAsItIsRead) {
  const fs::path c = dir_ / "box";
  if (!write_box_case(c)) GTEST_SKIP() << "OpenFOAM's blockMesh is not installed";
  const fs::path out = dir_ / "out.h5";
  const Result r = field("import " + c.string() + " -o " + out.string() +
                         " --cell 50 --z -10 --scale 2 --rotate 90 --translate 10,0,-20 --velocity-scale 0.5 --no-vtk");
  ASSERT_EQ(r.code, 0) << r.output;
  EXPECT_NE(r.output.find("mesh: x -190 to 10 m, y 0 to 200 m, z -20 to 0 m"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("x: 5 from -190 to 10 m"), std::string::npos) << r.output;
  // Level -10 m is z = 5 m of the original case: U = 0.5 m/s along x there, now 0.25 m/s along y.
  EXPECT_NEAR(file_u(out, 0, 2, 2, 0), 0.0, 1e-6);
  EXPECT_NEAR(file_u(out, 0, 2, 2, 1), 0.25, 1e-6);
  fs::remove(out);
  for (const char* bad : {"--scale 0", "--scale 1,2", "--rotate 400", "--translate 1,2", "--velocity-scale -1"})
    expect_refused("import " + c.string() + " -o " + out.string() + " " + bad, std::string(bad).substr(0, 7));
}

}  // namespace
