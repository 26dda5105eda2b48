// The thread count does not change a run: the channel scene (contacts with friction history, every drift term,
// walls), a breaking frozen sheet (bonds) and a spatial pile of 290 boxes (manifolds, friction springs, sat and
// libccd), each run with 1 and 2 threads, give the same bits in every dataset, VTK file and the final state.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>
#include <vector>

#include "same_run.h"
#include "spatial_pile.h"

namespace fs = std::filesystem;
using polyfloe::tsupport::expect_same_run;
using polyfloe::tsupport::run_to_end;
using polyfloe::tsupport::scratch;
using polyfloe::tsupport::slurp;

namespace {
const std::string kSource = POLYFLOE_SOURCE_DIR;
}  // namespace

TEST(Threads, TwoThreadsGiveTheOneThreadRunBitwise) {
#ifndef _OPENMP
  GTEST_SKIP() << "built without OpenMP: the step is serial";
#endif
  // The channel scene (contacts with friction history, every drift term, walls) and a frozen sheet breaking
  // (bonds), each run with 1 and 2 threads: every dataset, VTK file and the final state must be the same bits.
  const std::vector<std::vector<std::string>> scenes{
      {"run", kSource + "/dem/scenes/channel.yaml", "--set", "run.duration=3", "--set", "output.interval=0.5"},
      {"run", kSource + "/dem/scenes/uniaxial_compression.yaml", "--set", "ice_sheet.region=[0,0,60,60]", "--set",
       "ice_sheet.cell_size=8", "--set", "ice_sheet.bonds.tensile_strength=1e5", "--set",
       "ice_sheet.bonds.shear_strength=1e5", "--set", "floes.0.position=[-10,30]", "--set", "floes.1.position=[70,30]",
       "--set", "run.duration=0.2", "--set", "output.interval=0.02"}};
  const fs::path base = scratch("threads");
  for (std::size_t k = 0; k < scenes.size(); ++k) {
    fs::remove_all(base);
    fs::create_directories(base);
    for (const char* t : {"1", "2"}) {
      std::vector<std::string> a = scenes[k];
      a.insert(a.end(), {"--threads", t, "-o", (base / t).string()});
      ASSERT_EQ(run_to_end(a, base / (std::string(t) + ".log")), 0) << slurp(base / (std::string(t) + ".log"));
    }
    SCOPED_TRACE(scenes[k][1]);
    expect_same_run(base / "1", base / "2");
  }
  fs::remove_all(base);
}

TEST(Threads, TwoThreadsGiveTheOneThreadSpatialRunBitwise) {
#ifndef _OPENMP
  GTEST_SKIP() << "built without OpenMP: the step is serial";
#endif
  // 290 boxes piling up on a plate (tests/support/spatial_pile.h): manifold contacts with friction springs, measured
  // by sat and by libccd's GJK-EPA (whose failures sat answers and the step counts), 1 and 2 threads.
  const fs::path base = scratch("threads_spatial");
  fs::remove_all(base);
  fs::create_directories(base);
  const std::string scene = polyfloe::tsupport::write_spatial_pile(base / "pile.yaml");
  for (const char* narrow : {"sat", "gjk_epa_tiebreak"}) {
    SCOPED_TRACE(narrow);
    for (const char* t : {"1", "2"}) {
      const fs::path out = base / (std::string(narrow) + t);
      const std::vector<std::string> a{
          "run",       scene, "--set", "run.duration=0.15", "--set", "spatial.narrow_phase=" + std::string(narrow),
          "--threads", t,     "-o",    out.string()};
      ASSERT_EQ(run_to_end(a, out.string() + ".log"), 0) << slurp(out.string() + ".log");
    }
    expect_same_run(base / (std::string(narrow) + "1"), base / (std::string(narrow) + "2"));
  }
  fs::remove_all(base);
}
