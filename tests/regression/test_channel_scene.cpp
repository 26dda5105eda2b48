// The default scene end to end: `polyfloe run dem/scenes/channel.yaml`, then every frame of the .pvd series is read
// back with VTK's XML reader (the one ParaView uses) and must hold every floe; the HDF5 file must agree; and the ice
// must have drifted down the channel. CI runs its first 100 s (21 frames, 30 s of the suite); the study tier
// (ChannelSceneStudy, label study) runs the whole 300 s the README's first command runs (about 2 minutes on one core).
#include <gtest/gtest.h>
#include <hdf5.h>
#include <vtkCellData.h>
#include <vtkDataArray.h>
#include <vtkNew.h>
#include <vtkPolyData.h>
#include <vtkXMLPolyDataReader.h>

#include "scratch_dir.h"
#include "pvd.h"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <set>
#include <string>
#include <utility>
#include <vector>

namespace fs = std::filesystem;

namespace {

std::vector<std::uint64_t> read_u64(hid_t file, const char* name) {
  const hid_t ds = H5Dopen2(file, name, H5P_DEFAULT);
  EXPECT_GE(ds, 0) << name;
  const hid_t sp = H5Dget_space(ds);
  const auto n = H5Sget_simple_extent_npoints(sp);
  std::vector<std::uint64_t> v(static_cast<std::size_t>(n));
  H5Dread(ds, H5T_NATIVE_UINT64, H5S_ALL, H5S_ALL, H5P_DEFAULT, v.data());
  H5Sclose(sp);
  H5Dclose(ds);
  return v;
}

// Runs the default scene for `duration` s (every 5 s a frame) and checks every frame; returns the mean x of the
// floes' prism cells in the first and the last frame.
std::pair<double, double> run_default_scene(const std::string& tag, double duration) {
  const fs::path out = polyfloe::tsupport::scratch_dir("polyfloe_channel_" + tag);
  fs::remove_all(out);
  char set[64];
  std::snprintf(set, sizeof set, " --set run.duration=%g", duration);
  const std::string cmd = std::string(POLYFLOE_BINARY) + " run " + POLYFLOE_SOURCE_DIR +
                          "/dem/scenes/channel.yaml -o " + out.string() + set + " > " + (out.string() + ".log") +
                          " 2>&1";
  EXPECT_EQ(std::system(cmd.c_str()), 0) << "see " << out.string() << ".log";

  // Ids and motion of every body, from the HDF5 file.
  const hid_t h5 = H5Fopen((out / "results.h5").c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  if (h5 < 0) {
    ADD_FAILURE() << "no results.h5 in " << out;
    return {0.0, 0.0};
  }
  const std::vector<std::uint64_t> ids = read_u64(h5, "/floes/id");
  const std::vector<std::uint64_t> motion = read_u64(h5, "/floes/motion");
  std::set<std::uint64_t> floes;
  for (std::size_t i = 0; i < ids.size(); ++i)
    if (motion[i] == 0) floes.insert(ids[i]);
  const hid_t t_ds = H5Dopen2(h5, "/time", H5P_DEFAULT);
  const hid_t t_sp = H5Dget_space(t_ds);
  const auto frames_h5 = H5Sget_simple_extent_npoints(t_sp);
  H5Sclose(t_sp);
  H5Dclose(t_ds);
  H5Fclose(h5);
  EXPECT_GT(floes.size(), 1000u);  // a 1 km x 1 km field at 50 %: ~1200 floes

  const auto entries = polyfloe::tsupport::read_pvd(out / "floes.pvd");
  EXPECT_EQ(static_cast<long long>(entries.size()), static_cast<long long>(frames_h5));
  EXPECT_EQ(entries.size(), static_cast<std::size_t>(std::lround(duration / 5.0)) + 1);  // t = 0, 5, ..., duration
  if (entries.empty()) return {0.0, 0.0};
  EXPECT_NEAR(entries.back().first, duration, 1e-6);

  double mean_x_first = 0.0, mean_x_last = 0.0;
  for (std::size_t f = 0; f < entries.size(); ++f) {
    vtkNew<vtkXMLPolyDataReader> reader;
    reader->SetFileName((out / entries[f].second).c_str());
    reader->Update();
    vtkPolyData* pd = reader->GetOutput();
    vtkDataArray* id = pd->GetCellData()->GetArray("id");
    vtkDataArray* mo = pd->GetCellData()->GetArray("motion");
    if (reader->GetErrorCode() != 0u || id == nullptr || mo == nullptr) {
      ADD_FAILURE() << entries[f].second << ": unreadable, or no id or motion array";
      return {0.0, 0.0};
    }
    std::set<std::uint64_t> seen;
    for (vtkIdType c = 0; c < pd->GetNumberOfCells(); ++c)
      if (mo->GetTuple1(c) == 0) seen.insert(static_cast<std::uint64_t>(id->GetTuple1(c)));
    EXPECT_EQ(seen, floes) << "frame " << f << " (" << entries[f].second << ")";
    // Mean x of the floe points (bottom and top rings).
    double sx = 0.0;
    vtkIdType np = 0;
    for (vtkIdType c = 0; c < pd->GetNumberOfCells(); ++c) {
      if (mo->GetTuple1(c) != 0) continue;
      double b[6];
      pd->GetCellBounds(c, b);
      sx += 0.5 * (b[0] + b[1]);
      ++np;
    }
    if (f == 0) mean_x_first = sx / np;
    if (f + 1 == entries.size()) mean_x_last = sx / np;
  }
  std::printf("mean floe x: %.1f m at t = 0, %.1f m at t = %g s\n", mean_x_first, mean_x_last, duration);
  if (!::testing::Test::HasFailure()) fs::remove_all(out);
  return {mean_x_first, mean_x_last};
}

}  // namespace

// Free drift is ~4.25 m/s; the walls and the strait hold the ice back, but it must have moved well downstream.
TEST(ChannelScene, RunsAHundredSecondsAndEveryFrameHoldsAllFloes) {
  const auto [first, last] = run_default_scene("test", 100.0);
  EXPECT_GT(last - first, 150.0);  // measured 501.8 -> 745.3 m (+244 m)
}

TEST(ChannelSceneStudy, RunsTheWholeThreeHundredSecondsAndEveryFrameHoldsAllFloes) {
  const auto [first, last] = run_default_scene("study", 300.0);
  EXPECT_GT(last - first, 300.0);  // measured 501.8 -> 1,117.1 m (+615 m)
}
