// The tidal pulse end to end (of_cases/tidal/Allrun --quick on a copy of the case): OpenFOAM's unsteady flow
// imported at every snapshot, and the current it gives follows the inflow in time. Needs OpenFOAM (Debian's
// openfoam, installed by scripts/setup.sh): without it the test fails and says so.
#include <gtest/gtest.h>

#include <filesystem>
#include <memory>

#include "forcing/gridded_field.h"
#include "formats/field_file.h"
#include "openfoam_case_run.h"

namespace polyfloe {
namespace {

namespace fs = std::filesystem;
using tsupport::CaseRun;

// The tidal pulse (of_cases/tidal): every snapshot imported, and the ice run sees the current change in time.
class Tidal : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    run_ = std::make_unique<CaseRun>();
    run_->run("tidal");
  }
  static void TearDownTestSuite() { run_.reset(); }
  void SetUp() override { run_->check(); }
  static inline std::unique_ptr<CaseRun> run_;
};

TEST_F(Tidal, EverySnapshotIsImportedAndTheCurrentFollowsTheInflow) {
  const io::FieldFile f = io::read_field_file(run_->dir / "field.h5");
  ASSERT_EQ(f.grid.t.size(), 21u);  // 0, 60, ..., 1200 s
  EXPECT_EQ(f.grid.t.front(), 0.0);
  EXPECT_EQ(f.grid.t.back(), 1200.0);
  forcing::GriddedFieldOptions o;
  o.time_outside = forcing::TimeBoundary::error;
  const forcing::GriddedField field(std::make_shared<const forcing::GridData>(f.grid), o);
  // The inflow 0.5 (1 - cos(2 pi t / 1200 s)) m/s: at rest at 0, 1 m/s at 600 s; the basin follows it (the flow
  // is nearly incompressible in 2-D: the whole basin answers the inlet at once), the jet 4-5 times faster.
  const forcing::Vec3 basin{500, 500, -0.5}, jet{1700, 500, -0.5};
  EXPECT_NEAR(field.at(basin, 0).norm(), 0.0, 1e-9);
  EXPECT_NEAR(field.at(basin, 600).x(), 1.06, 0.06);
  EXPECT_GT(field.at(jet, 600).x(), 4.5);
  EXPECT_NEAR(field.at(basin, 300).x(), 0.5 * 1.06, 0.06);
  // Between snapshots: linear in time.
  const double a = field.at(jet, 240).x(), b = field.at(jet, 300).x();
  EXPECT_NEAR(field.at(jet, 270).x(), 0.5 * (a + b), 1e-12);
  EXPECT_THROW((void)field.at(jet, 1200.5), forcing::FieldError);
  EXPECT_TRUE(fs::is_regular_file(run_->dir / "field" / "field_0020.vtr"));
  EXPECT_TRUE(fs::is_regular_file(run_->dir / "ice" / "openfoam" / "floes.pvd"));
}

}  // namespace
}  // namespace polyfloe
