// Users' own OpenFOAM cases, end to end (of_cases/tutorials/Allrun into a scratch folder: OpenFOAM's tutorials from
// Debian's openfoam-examples, run short): a transient tutorial with #includeEtc, a steady one in millimetres, a
// decomposed run read before reconstructPar, a 3-D case whose surface is 10 m above its seabed. Each imported field
// is checked against OpenFOAM's own probes of U (postProcess -func probes, cellPoint interpolation: computed by
// OpenFOAM, not by VTK's reader or polyfloe) at the same points, transformed as the import transformed the case;
// each drives an ice run that writes its VTK series.
// Needs OpenFOAM and its tutorials (scripts/setup.sh installs both): without them the test fails and says so.
#include <gtest/gtest.h>

#include <stdlib.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "text_file.h"
#include "forcing/gridded_field.h"
#include "formats/field_file.h"

namespace polyfloe {
namespace {

namespace fs = std::filesystem;

const fs::path kSource = POLYFLOE_SOURCE_DIR;
const fs::path kBuild = fs::path(POLYFLOE_BINARY).parent_path();

using tsupport::slurp;

// OpenFOAM's probes file (postProcessing/probes/<start time>/U): the points, then per time one vector per point.
struct Probes {
  std::vector<Eigen::Vector3d> points;
  std::vector<double> times;
  std::vector<std::vector<Eigen::Vector3d>> u;  // [time][point]
};

Probes read_probes(const fs::path& case_dir) {
  Probes p;
  const fs::path root = case_dir / "postProcessing" / "probes";
  fs::path file;
  for (const auto& e : fs::directory_iterator(root)) file = e.path() / "U";
  std::ifstream in(file);
  std::string line;
  while (std::getline(in, line)) {
    for (char& c : line)
      if (c == '(' || c == ')') c = ' ';
    std::istringstream ls(line);
    if (line.rfind("# Probe ", 0) == 0) {
      std::string hash, word;
      int k;
      Eigen::Vector3d x;
      ls >> hash >> word >> k >> x.x() >> x.y() >> x.z();
      p.points.push_back(x);
    } else if (!line.empty() && line[0] != '#') {
      double t;
      ls >> t;
      p.times.push_back(t);
      p.u.emplace_back(p.points.size());
      for (Eigen::Vector3d& v : p.u.back()) ls >> v.x() >> v.y() >> v.z();
    }
  }
  return p;
}

// Every case's Allrun output, made once for the suite.
class Tutorials : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    std::string tmpl = (fs::temp_directory_path() / "polyfloe_test_tutorials.XXXXXX").string();
    ASSERT_NE(mkdtemp(tmpl.data()), nullptr);
    work_ = tmpl;
    const std::string cmd = "POLYFLOE_ROOT=" + kSource.string() + " POLYFLOE_BUILD_DIR=" + kBuild.string() + " bash " +
                            (kSource / "of_cases" / "tutorials" / "Allrun").string() + " --work " + work_.string() +
                            " > " + (work_ / "allrun.log").string() + " 2>&1";
    status_ = std::system(cmd.c_str());
  }
  static void TearDownTestSuite() {
    std::error_code ec;
    fs::remove_all(work_, ec);
  }
  void SetUp() override {
    ASSERT_EQ(status_, 0) << "of_cases/tutorials/Allrun failed (are openfoam and openfoam-examples installed? bash "
                             "scripts/setup.sh):\n"
                          << slurp(work_ / "allrun.log");
  }

  // The imported field against OpenFOAM's probes at every probe point and time: the point scaled as the import
  // scaled the case, the level its height below the surface, OpenFOAM's velocity scaled as the import scaled it.
  // Returns the largest horizontal difference [m/s] and checks the ice run's VTK series.
  static double largest_difference(const char* name, double scale, double velocity_scale, double surface) {
    const fs::path c = work_ / name;
    const io::FieldFile f = io::read_field_file(c / "field.h5");
    const forcing::GriddedField field(std::make_shared<const forcing::GridData>(f.grid), {});
    const Probes probes = read_probes(c);
    EXPECT_EQ(probes.points.size(), 6u) << name;
    EXPECT_EQ(probes.times, f.grid.t.size() > 1 ? f.grid.t : probes.times) << name;
    double worst = 0.0, top = 0.0;
    for (std::size_t it = 0; it < probes.times.size(); ++it)
      for (std::size_t k = 0; k < probes.points.size(); ++k) {
        const Eigen::Vector3d x = scale * probes.points[k];
        const double t = f.grid.t.size() > 1 ? probes.times[it] : 0.0;
        const forcing::Vec2 grid = field.at({x.x(), x.y(), x.z() - surface}, t);
        const forcing::Vec2 foam = velocity_scale * probes.u[it][k].head<2>();
        worst = std::max(worst, (grid - foam).norm());
        top = std::max(top, foam.norm());
      }
    std::cout << "  " << name << ": largest difference from OpenFOAM's probes " << worst << " m/s (speeds up to " << top
              << " m/s)\n";
    EXPECT_TRUE(fs::is_regular_file(c / "field.pvd")) << name;
    EXPECT_TRUE(fs::is_regular_file(c / "ice" / "floes.pvd")) << name;
    EXPECT_TRUE(fs::is_regular_file(c / "ice" / "results.h5")) << name;
    EXPECT_NE(slurp(c / "ice" / "floes.pvd").find("timestep=\"10\""), std::string::npos) << name;
    return worst;
  }

  static inline fs::path work_;
  static inline int status_ = -1;
};

// porousBlockage (pisoFoam, #includeEtc in 0/U): the solution times 1 and 2 s imported, t = 0 (the initial
// condition) left out by default; --times all reads t = 0 too, from a copy OpenFOAM wrote out plainly.
TEST_F(Tutorials, TransientCaseLeavesOutTimeZeroUnlessAskedAndMatchesOpenFoamsProbes) {
  const std::string log = slurp(work_ / "porousBlockage" / "log.import");
  EXPECT_NE(log.find("times read: 1, 2 s of the case's 0, 1, 2 s (t = 0, the initial condition, left out"),
            std::string::npos)
      << log;
  const std::string all = slurp(work_ / "porousBlockage" / "log.import_all");
  EXPECT_NE(all.find("read from a copy OpenFOAM wrote out plainly"), std::string::npos) << all;
  const io::FieldFile f = io::read_field_file(work_ / "porousBlockage" / "field_all.h5");
  ASSERT_EQ(f.grid.t.size(), 3u);
  EXPECT_NEAR(f.grid.u[f.grid.nodes_per_snapshot() / 2], 1.0, 1e-12);  // t = 0: uniform (1 0 0)
  // The grid's nodes fall on the mesh's (12.5 m spacing): the difference is the files' 6 digits. Measured 5.0e-6.
  EXPECT_LT(largest_difference("porousBlockage", 100.0, 1.0, 0.1 * 100.0), 1e-4);
}

// pitzDaily (simpleFoam): a 0.3 m channel made 300 m by --scale 1000, its 10 m/s inflow 1 m/s.
TEST_F(Tutorials, SteadyCaseInMillimetresIsScaledAsAskedAndMatchesOpenFoamsProbes) {
  const std::string log = slurp(work_ / "pitzDaily" / "log.import");
  EXPECT_NE(log.find("steady, 1 time(s)"), std::string::npos) << log;
  EXPECT_NE(log.find("mesh: x -20.6 to 290 m, y -25.4 to 25.4 m"), std::string::npos) << log;
  // A graded mesh, the grid at its finest cell (0.26 m): measured 3.1e-4 m/s, 0.03 % of the inflow.
  EXPECT_LT(largest_difference("pitzDaily", 1000.0, 0.1, 0.5), 0.005);
}

// porousBlockage on two processors, imported from processor0/ and processor1/ before reconstructPar; the probes
// are of the reconstructed case.
TEST_F(Tutorials, DecomposedCaseIsReadFromItsProcessorFoldersAndMatchesOpenFoamsProbes) {
  const std::string log = slurp(work_ / "decomposed" / "log.import");
  EXPECT_NE(log.find("decomposed: read from 2 processor folders"), std::string::npos) << log;
  EXPECT_NE(log.find("times read: 1, 2 s"), std::string::npos) << log;
  // As the reconstructed case's: measured 5.0e-6 m/s.
  EXPECT_LT(largest_difference("decomposed", 100.0, 1.0, 0.1 * 100.0), 1e-4);
}

// A 3-D channel with its seabed at z = 0 and its surface at z = 10 m: levels -2 ... 0 m are z = 8 ... 10 m, where
// the current is near its free-stream speed; the seabed (no-slip) is far below them.
TEST_F(Tutorials, ThreeDimensionalSurfaceAboveZero) {
  const std::string log = slurp(work_ / "surface3d" / "log.import");
  EXPECT_NE(log.find("mesh: x 0 to 200 m, y 0 to 100 m, z 0 to 10 m; water surface at z = 10 m"), std::string::npos)
      << log;
  const io::FieldFile f = io::read_field_file(work_ / "surface3d" / "field.h5");
  EXPECT_EQ(f.grid.z, (std::vector<double>{-2, -1, -0.5, 0}));
  // Graded in z towards the seabed, the levels between the mesh's layers: measured 2.6e-3 m/s (0.2 %).
  EXPECT_LT(largest_difference("surface3d", 1.0, 1.0, 10.0), 0.01);
}

}  // namespace
}  // namespace polyfloe
