// The study scripts end to end on tiny runs: scripts/sweep.sh (the channel families per seed) with
// postprocess/plot_sweep.py, and scripts/uniaxial_study.sh (the compression study) with its figures.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

#include "scratch_dir.h"

namespace fs = std::filesystem;

namespace {

TEST(StudyScripts, SweepRunsFamiliesPerSeedAndThePlotsFollow) {
  // scripts/sweep.sh on two families and two seeds with a tiny duration, then postprocess/plot_sweep.py on its output.
  const fs::path out = polyfloe::tsupport::scratch_dir("polyfloe_sweep");
  fs::remove_all(out);
  const std::string src = POLYFLOE_SOURCE_DIR;
  const std::string cmd = "POLYFLOE_BIN=" + std::string(POLYFLOE_BINARY) + " bash " + src +
                          "/scripts/sweep.sh -j 2 -s 1,2 -o " + out.string() +
                          " concentration exponent -- --set run.duration=0.02 --set output.interval=0.01 "
                          "--set output.vtk=false > /dev/null 2>&1";
  EXPECT_EQ(std::system(cmd.c_str()), 0);
  for (const char* m : {"concentration/c0.50", "concentration/c0.60", "exponent/a1.2", "exponent/a2.0"}) {
    for (const char* seed : {"s1", "s2"}) EXPECT_TRUE(fs::exists(out / m / seed / "results.h5")) << m << " " << seed;
  }
  // 50 %, alpha 2, 5-10 corners is in both families: it runs once, the second family links to it.
  EXPECT_TRUE(fs::is_symlink(out / "exponent" / "a2.0" / "s2"));
  EXPECT_FALSE(fs::is_symlink(out / "concentration" / "c0.50" / "s2"));
  const std::string plot = "/usr/bin/python3 " + src + "/postprocess/plot_sweep.py " + out.string() + " -o " +
                           (out / "fig").string() + " --summary " + (out / "summary.json").string() + " > " +
                           (out / "plot.log").string() + " 2>&1";
  if (std::system(plot.c_str()) != 0) {
    std::ifstream log(out / "plot.log");
    ADD_FAILURE() << "plot_sweep.py failed:\n"
                  << std::string((std::istreambuf_iterator<char>(log)), std::istreambuf_iterator<char>());
  }
  EXPECT_TRUE(fs::exists(out / "fig" / "sweep_flow.png"));
  // The runs end at 0.02 s: no maps "at 170 s and 200 s", and the plot says why; the summary's columns at those
  // times are n/a (null), not the last frame's values.
  EXPECT_FALSE(fs::exists(out / "fig" / "sweep_maps_exponent.png"));
  std::ifstream plot_log(out / "plot.log");
  const std::string said((std::istreambuf_iterator<char>(plot_log)), std::istreambuf_iterator<char>());
  EXPECT_NE(said.find("no maps at t = 170, 200 s: the runs end at t = 0.02 s"), std::string::npos) << said;
  EXPECT_NE(said.find("columns at 170 s and 200 s are n/a"), std::string::npos) << said;
  EXPECT_EQ(said.find("No artists with labels"), std::string::npos) << said;
  std::ifstream summary(out / "summary.json");
  const std::string text((std::istreambuf_iterator<char>(summary)), std::istreambuf_iterator<char>());
  EXPECT_NE(text.find("\"a1.2\""), std::string::npos) << text;
  EXPECT_NE(text.find("\"seeds\": 2"), std::string::npos) << text;
  EXPECT_NE(text.find("\"mean\": null"), std::string::npos) << text;
  EXPECT_NE(std::system(("bash " + src + "/scripts/sweep.sh bogus > /dev/null 2>&1").c_str()), 0);
  EXPECT_NE(std::system(("bash " + src + "/scripts/sweep.sh -s x > /dev/null 2>&1").c_str()), 0);
  fs::remove_all(out);
}

TEST(StudyScripts, UniaxialCompressionRunsEveryStrengthAndThePlotsFollow) {
  // The compression study on a short run (0.05 s: the plates have barely started): every strength runs, the
  // outputs have the bonds and the plate forces, and the figures are drawn.
  const std::string src = POLYFLOE_SOURCE_DIR;
  const fs::path out = polyfloe::tsupport::scratch_dir("polyfloe_uniaxial");
  fs::remove_all(out);
  const std::string cmd =
      "POLYFLOE_BIN=" + std::string(POLYFLOE_BINARY) + " bash " + src + "/scripts/uniaxial_study.sh -j 2 -o " +
      out.string() + " -f " + (out / "fig").string() +
      " -- --set run.duration=0.05 --set output.interval=0.025 --set output.vtk=false"
      " --set ice_sheet.region=[0,0,60,60] --set floes.0.rectangle.height=90 --set floes.0.position=[-10,30]"
      " --set floes.1.rectangle.height=90 --set floes.1.position=[70,30]"
      " > /dev/null 2>&1";
  EXPECT_EQ(std::system(cmd.c_str()), 0);
  for (const char* s : {"0.1", "0.5", "1.0", "1.5"})
    EXPECT_TRUE(fs::exists(out / ("sigma_" + std::string(s)) / "results.h5")) << s;
  for (const char* png : {"uniaxial_stress_strain.png", "uniaxial_fracture_angles.png", "uniaxial_cracks.png"})
    EXPECT_TRUE(fs::exists(out / "fig" / png)) << png;
  EXPECT_TRUE(fs::exists(out / "uniaxial.json"));
  EXPECT_NE(std::system(("bash " + src + "/scripts/uniaxial_study.sh -j 0 > /dev/null 2>&1").c_str()), 0);
  fs::remove_all(out);
}

}  // namespace
