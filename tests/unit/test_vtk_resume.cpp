// A restart's VTK series: resume() drops the frames after the checkpoint, and its collections never list a frame
// that is missing, even when the run stops part-way through the resume (a kill, or a frame it cannot remove).
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <memory>
#include <string>
#include <vector>

#include "dynamics/world.h"
#include "formats/atomic_file.h"
#include "io/vtk_writer.h"
#include "pvd.h"
#include "scratch_dir.h"

namespace fs = std::filesystem;
using namespace polyfloe;

namespace {

constexpr double kWater = 1025.0;  // [kg/m^3]

struct Scratch {
  fs::path dir = tsupport::scratch_dir("polyfloe_vtk_resume_" +
                                       std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()));
  Scratch() {
    fs::remove_all(dir);
    fs::create_directories(dir);
  }
  ~Scratch() {
    std::error_code ec;
    fs::remove_all(dir, ec);
  }
};

// One hexagon drifting: a world whose frames differ.
std::unique_ptr<dynamics::World> drifting_floe() {
  auto world = std::make_unique<dynamics::World>(dynamics::WorldSettings{});
  dynamics::BodyDesc d;
  d.shape = std::make_shared<const geometry::ConvexPolygon>(geometry::ConvexPolygon::regular(6, 5.0));
  d.density = 920.0;
  d.thickness = 1.0;
  d.velocity = {0.5, 0.0};
  world->add_body(d);
  return world;
}

// Three frames, 0.1 s apart; returns their times.
std::vector<double> write_three_frames(const fs::path& dir) {
  auto world = drifting_floe();
  io::VtkSeriesWriter vtk(dir, false, kWater);
  std::vector<double> times;
  for (int f = 0; f < 3; ++f) {
    if (f > 0) world->step(0.1);
    vtk.write_frame(*world);
    times.push_back(world->time());
  }
  return times;
}

// Every file the collection lists exists and is a complete VTK file.
void expect_listed_frames_complete(const fs::path& dir, std::size_t count) {
  const auto entries = tsupport::read_pvd(dir / "floes.pvd");
  ASSERT_EQ(entries.size(), count);
  for (const auto& [t, file] : entries) {
    ASSERT_TRUE(fs::is_regular_file(dir / file))
        << "floes.pvd lists " << file << " (t = " << t << "), which is not a file";
    std::ifstream in(dir / file);
    const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    EXPECT_NE(text.find("</VTKFile>"), std::string::npos) << file;
  }
}

}  // namespace

TEST(VtkResume, DropsTheFramesAfterTheCheckpointAndGoesOnFromThere) {
  Scratch s;
  const std::vector<double> times = write_three_frames(s.dir);
  ASSERT_TRUE(fs::exists(s.dir / "floes" / "floes_000002.vtp"));

  io::VtkSeriesWriter vtk(s.dir, false, kWater);
  vtk.resume(std::vector<double>(times.begin(), times.begin() + 2), false);
  EXPECT_EQ(vtk.frames(), 2);
  EXPECT_FALSE(fs::exists(s.dir / "floes" / "floes_000002.vtp")) << "a frame after the checkpoint was kept";
  expect_listed_frames_complete(s.dir, 2);

  auto world = drifting_floe();
  vtk.write_frame(*world);
  expect_listed_frames_complete(s.dir, 3);
}

TEST(VtkResume, AFrameThatCannotBeRemovedLeavesACollectionOfCompleteFrames) {
  // The collection is rewritten before the frames it drops are removed: a run stopped in between (here by a
  // frame that cannot be removed, a folder in its place) leaves an unlisted leftover, never a listed gap.
  Scratch s;
  const std::vector<double> times = write_three_frames(s.dir);
  const fs::path blocker = s.dir / "floes" / "floes_000001.vtp";
  fs::remove(blocker);
  fs::create_directories(blocker / "keep");

  io::VtkSeriesWriter vtk(s.dir, false, kWater);
  try {
    vtk.resume(std::vector<double>(times.begin(), times.begin() + 1), false);
    ADD_FAILURE() << "resume() removed a non-empty folder";
  } catch (const io::IoError& e) {
    EXPECT_NE(std::string(e.what()).find("floes_000001.vtp"), std::string::npos) << e.what();
  }
  expect_listed_frames_complete(s.dir, 1);
}
