// Ocean field files (dem/io/field_file.*) and scenes that use them (forcing.ocean.field: {type: file}): the file
// round-trips exactly; a missing, foreign, malformed or mismatched file is refused with its name and the problem,
// and a failed write leaves nothing behind; the scene resolves the path against its own folder.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>

#include "scratch_dir.h"
#include "forcing/gridded_field.h"
#include "formats/field_file.h"
#include "formats/hdf5_file.h"
#include "scene/scene.h"
#include "scene/scene_reader.h"
#include "scene_compare.h"
#include "scene_test_support.h"

namespace polyfloe {
namespace {

namespace fs = std::filesystem;
using forcing::GridData;

class FieldFileTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = polyfloe::tsupport::scratch_dir(
        "polyfloe_field_file_" + std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  fs::path dir_;
};

// 4 x 3 nodes, 2 levels, 2 snapshots; u = x/100 + t/1000, v = y/100 + z; the node x = 30, y = 20 is land.
io::FieldFile sample_file() {
  io::FieldFile f;
  GridData& g = f.grid;
  g.x = {0, 10, 20, 30};
  g.y = {0, 10, 20};
  g.z = {-2, -0.5};
  g.t = {0, 600};
  g.u.resize(48);
  g.v.resize(48);
  f.w.resize(48);
  g.wet.assign(24, 1);
  for (std::size_t it = 0; it < 2; ++it)
    for (std::size_t iz = 0; iz < 2; ++iz)
      for (std::size_t iy = 0; iy < 3; ++iy)
        for (std::size_t ix = 0; ix < 4; ++ix) {
          const std::size_t k = g.index(it, iz, iy, ix);
          g.u[k] = g.x[ix] / 100 + g.t[it] / 1000;
          g.v[k] = g.y[iy] / 100 + g.z[iz];
          f.w[k] = 1e-3 * static_cast<double>(k);
        }
  for (std::size_t iz = 0; iz < 2; ++iz) {
    g.wet[g.index(0, iz, 2, 3)] = 0;
    g.u[g.index(0, iz, 2, 3)] = g.v[g.index(0, iz, 2, 3)] = 0;
    g.u[g.index(1, iz, 2, 3)] = g.v[g.index(1, iz, 2, 3)] = 0;
  }
  f.info = {"a test", "test_field_file"};
  return f;
}

TEST_F(FieldFileTest, RoundTripsExactly) {
  const io::FieldFile f = sample_file();
  io::write_field_file(dir_ / "f.h5", f);
  const io::FieldFile r = io::read_field_file(dir_ / "f.h5");
  EXPECT_EQ(r.grid.x, f.grid.x);
  EXPECT_EQ(r.grid.y, f.grid.y);
  EXPECT_EQ(r.grid.z, f.grid.z);
  EXPECT_EQ(r.grid.t, f.grid.t);
  EXPECT_EQ(r.grid.u, f.grid.u);
  EXPECT_EQ(r.grid.v, f.grid.v);
  EXPECT_EQ(r.w, f.w);
  EXPECT_EQ(r.grid.wet, f.grid.wet);
  EXPECT_EQ(r.info.source, "a test");
  EXPECT_EQ(r.info.created_by, "test_field_file");
  // Nothing but the file itself is left in the folder (the temporary was renamed).
  EXPECT_EQ(std::distance(fs::directory_iterator(dir_), fs::directory_iterator()), 1);
}

std::string error_of(const fs::path& p) {
  return scene::error_of<io::FieldFileError>([&] { (void)io::read_field_file(p); });
}

TEST_F(FieldFileTest, RefusesMissingForeignAndMalformedFiles) {
  EXPECT_EQ(error_of(dir_ / "none.h5"), (dir_ / "none.h5").string() + ": no such file");
  EXPECT_EQ(error_of(dir_), dir_.string() + ": not a regular file");
  { std::ofstream(dir_ / "text.h5") << "U = 1 m/s\n"; }
  EXPECT_NE(error_of(dir_ / "text.h5").find((dir_ / "text.h5").string() + ": cannot read"), std::string::npos)
      << error_of(dir_ / "text.h5");
  {
    io::hdf5::File h(dir_ / "foreign.h5", io::hdf5::File::Mode::truncate);
    h.root().set_attribute("format", "something else");
    h.close();
  }
  EXPECT_NE(error_of(dir_ / "foreign.h5").find("not an ocean field file"), std::string::npos);

  // A valid file, then one piece spoiled at a time.
  const auto spoil = [&](const char* name, auto&& edit) {
    const fs::path p = dir_ / name;
    io::write_field_file(p, sample_file());
    io::hdf5::File h(p, io::hdf5::File::Mode::read_write);
    edit(h.root());
    h.close();
    return error_of(p);
  };
  EXPECT_NE(spoil("version.h5", [](io::hdf5::Group& r) { r.set_attribute("format_version", std::int64_t{7}); })
                .find("format_version 7 is not supported (this build reads version 1)"),
            std::string::npos);
  // Written by hand (what another program might write): the sample's axes, zero velocities, and a chosen time
  // axis and mask shape.
  const auto by_hand = [&](const char* name, const std::vector<double>& t, const io::hdf5::Dims& mask) {
    const fs::path p = dir_ / name;
    io::hdf5::File h(p, io::hdf5::File::Mode::truncate);
    io::hdf5::Group& r = h.root();
    r.set_attribute("format", "polyfloe-ocean-field");
    r.set_attribute("format_version", std::int64_t{1});
    const io::FieldFile f = sample_file();
    r.write_dataset<double>("x", f.grid.x);
    r.write_dataset<double>("y", f.grid.y);
    r.write_dataset<double>("z", f.grid.z);
    r.write_dataset<double>("t", t);
    r.write_dataset<double>("U", std::vector<double>(2 * 2 * 3 * 4 * 3, 0.0), {2, 2, 3, 4, 3});
    r.write_dataset<std::uint8_t>("mask", std::vector<std::uint8_t>(24, 1), mask);
    h.close();
    return error_of(p);
  };
  EXPECT_EQ(
      by_hand("mask.h5", {0.0, 600.0}, {2, 4, 3}),  // y and x swapped
      (dir_ / "mask.h5").string() + ": /mask has shape [2, 4, 3], expected [nz, ny, nx] = [2, 3, 4] from the axes");
  EXPECT_EQ(by_hand("time.h5", {0.0, 0.0}, {2, 3, 4}),
            (dir_ / "time.h5").string() + ": axis t is not strictly increasing at index 1 (0, 0)");
}

TEST_F(FieldFileTest, AFailedWriteLeavesNoFile) {
  io::FieldFile f = sample_file();
  f.grid.u[3] = std::nan("");
  EXPECT_THROW(io::write_field_file(dir_ / "f.h5", f), io::FieldFileError);
  f = sample_file();
  f.w.pop_back();
  EXPECT_THROW(io::write_field_file(dir_ / "f.h5", f), io::FieldFileError);
  EXPECT_TRUE(fs::is_empty(dir_));
}

std::string scene_with_field(const std::string& field) {
  return "name: f\nforcing:\n  ocean:\n    field: " + field + "\nfloes:\n  - rectangle: {width: 5, height: 5}\n";
}

std::string scene_error(const fs::path& file) {
  return scene::error_of([&] { (void)scene::read_scene(file); });
}

TEST_F(FieldFileTest, ASceneReadsItsFieldFileRelativeToItsFolder) {
  fs::create_directories(dir_ / "fields");
  io::write_field_file(dir_ / "fields" / "f.h5", sample_file());
  const fs::path scene_file = dir_ / "s.yaml";
  std::ofstream(scene_file) << scene_with_field(
      "{type: file, path: fields/f.h5, outside: cyclic, no_water: velocity, no_water_velocity: [0.5, -0.25]}");
  const scene::Scene s = scene::read_scene(scene_file);
  ASSERT_EQ(s.ocean_field.kind, forcing::FieldKind::file);
  EXPECT_EQ(s.ocean_field.path, (dir_ / "fields" / "f.h5").string());
  EXPECT_EQ(s.ocean_field.outside, forcing::TimeBoundary::cyclic);
  ASSERT_TRUE(s.world.drift.ocean);
  // u = x/100 + t/1000 at 700 s = 100 s into the next cycle; v = y/100 + z.
  const forcing::Vec2 u = s.world.drift.ocean->at({15, 5, -1}, 700);
  EXPECT_NEAR(u.x(), 0.15 + 0.1, 1e-12);
  EXPECT_NEAR(u.y(), 0.05 - 1, 1e-12);
  // The resolved scene names the file absolutely, so it reads from anywhere (the output folder).
  const std::string resolved = scene::resolved_yaml(s);
  EXPECT_NE(resolved.find("path: \"" + (dir_ / "fields" / "f.h5").string() +
                          "\", outside: cyclic, no_water: velocity, no_water_velocity: [0.5, -0.25]"),
            std::string::npos)
      << resolved;
  fs::create_directories(dir_ / "out");
  std::ofstream(dir_ / "out" / "scene.resolved.yaml") << resolved;
  scene::expect_same_settings(s, scene::read_scene(dir_ / "out" / "scene.resolved.yaml"));
  EXPECT_EQ(s.world.drift.ocean->at({1e6, 0, -1}, 0), forcing::Vec2(0.5, -0.25));  // off the grid

  // Placed in the scene: the file's (0, 0) at (100, -20) m, the scene's t = 0 at the file's 100 s (a spin-up
  // skipped): the scene's (115, -15) m at 600 s is the file's (15, 5) m at 700 s, as above.
  std::ofstream(scene_file) << scene_with_field(
      "{type: file, path: fields/f.h5, outside: cyclic, no_water: velocity, no_water_velocity: [0.5, -0.25], "
      "offset: [100, -20], time_offset: 100}");
  const scene::Scene placed = scene::read_scene(scene_file);
  const forcing::Vec2 up = placed.world.drift.ocean->at({115, -15, -1}, 600);
  EXPECT_NEAR(up.x(), 0.15 + 0.1, 1e-12);
  EXPECT_NEAR(up.y(), 0.05 - 1, 1e-12);
  EXPECT_EQ(placed.world.drift.ocean->at({15, 5, -1}, 600), forcing::Vec2(0.5, -0.25));  // off the placed grid
  const std::string placed_yaml = scene::resolved_yaml(placed);
  EXPECT_NE(placed_yaml.find("offset: [100, -20], time_offset: 100"), std::string::npos) << placed_yaml;
  std::ofstream(dir_ / "out" / "scene.resolved.yaml") << placed_yaml;
  scene::expect_same_settings(placed, scene::read_scene(dir_ / "out" / "scene.resolved.yaml"));
}

// land: walls makes the file's land (the surface level's dry nodes, here x = 30 m, y = 20 m: the square [25, 35] x
// [15, 25] m, and with offset [100, 0] m at [125, 135] x [15, 25] m) a fixed wall; a floe field keeps off the land
// whether or not it is a wall; an explicit floe on it is refused, naming the land and the floe.
TEST_F(FieldFileTest, TheFilesLandBecomesWallsAndFloeFieldsKeepOffIt) {
  io::write_field_file(dir_ / "f.h5", sample_file());
  const fs::path scene_file = dir_ / "s.yaml";
  const std::string field =
      "{type: file, path: f.h5, outside: clamp, no_water: velocity, no_water_velocity: [0, 0], "
      "offset: [100, 0]";
  std::ofstream(scene_file)
      << "name: f\nforcing:\n  ocean:\n    field: " + field +
             ", land: walls}\nfloes:\n  - {rectangle: {width: 2, height: 2}, position: [105, 5]}\n";
  const dynamics::World w = scene::build_world(scene::read_scene(scene_file));
  ASSERT_EQ(w.size(), 2u);
  EXPECT_EQ(w.motion(1), dynamics::Motion::fixed);
  std::vector<forcing::Vec2> v(w.world_vertices(1).begin(), w.world_vertices(1).end());
  ASSERT_EQ(v.size(), 4u);
  forcing::Vec2 lo = v[0], hi = v[0];
  for (const forcing::Vec2& p : v) lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
  EXPECT_LT((lo - forcing::Vec2(125, 15)).norm(), 1e-9);
  EXPECT_LT((hi - forcing::Vec2(135, 25)).norm(), 1e-9);
  // A floe field over the whole grid, land included: no floe overlaps the land square, with or without walls.
  for (const char* land : {"walls", "none"}) {
    std::ofstream(scene_file) << "name: f\nforcing:\n  ocean:\n    field: " + field + ", land: " + land +
                                     "}\nfloe_field: {region: [96, -4, 134, 24], concentration: 0.3, size: {min: 1, "
                                     "max: 3}, seed: 2}\n";
    const dynamics::World fw = scene::build_world(scene::read_scene(scene_file));
    int floes = 0;
    for (int i = 0; i < static_cast<int>(fw.size()); ++i) {
      if (fw.motion(i) != dynamics::Motion::dynamic) continue;
      ++floes;
      for (const forcing::Vec2& p : fw.world_vertices(i))
        EXPECT_FALSE(p.x() > 125 + 1e-9 && p.y() > 15 + 1e-9) << land << ": floe " << i << " on the land";
    }
    EXPECT_GT(floes, 20) << land;
  }
  std::ofstream(scene_file)
      << "name: f\nforcing:\n  ocean:\n    field: " + field +
             ", land: walls}\nfloes:\n  - {rectangle: {width: 2, height: 2}, position: [129, 19]}\n";
  const std::string e = scene::error_of([&] { (void)scene::build_world(scene::read_scene(scene_file)); });
  EXPECT_NE(e.find("(floes.0): lies on the land of " + (dir_ / "f.h5").string()), std::string::npos) << e;
  EXPECT_NE(e.find("move it into the water"), std::string::npos) << e;
  std::ofstream(scene_file) << "name: f\nforcing:\n  ocean:\n    field: " + field + ", land: island}\n";
  EXPECT_NE(scene_error(scene_file).find("forcing.ocean.field.land"), std::string::npos) << scene_error(scene_file);
}

TEST_F(FieldFileTest, SceneErrorsNameTheKeyAndTheFile) {
  io::write_field_file(dir_ / "f.h5", sample_file());
  const fs::path scene_file = dir_ / "s.yaml";
  std::ofstream(scene_file) << scene_with_field("{type: file, path: f.h5}");
  EXPECT_NE(scene_error(scene_file)
                .find("the field file has 2 snapshots (0 to 600 s): say what the field does beyond "
                      "them with 'outside' (clamp, cyclic or error)"),
            std::string::npos)
      << scene_error(scene_file);
  std::ofstream(scene_file) << scene_with_field("{type: file, path: missing.h5, outside: clamp}");
  EXPECT_NE(
      scene_error(scene_file)
          .find("s.yaml:4:31: key 'forcing.ocean.field.path': " + (dir_ / "missing.h5").string() + ": no such file"),
      std::string::npos)
      << scene_error(scene_file);
  std::ofstream(scene_file) << scene_with_field("{type: file, path: f.h5, outside: clamp, no_water: velocity}");
  EXPECT_NE(scene_error(scene_file).find("no_water: velocity needs no_water_velocity: [u, v] [m/s]"), std::string::npos)
      << scene_error(scene_file);
  std::ofstream(scene_file) << scene_with_field("{type: file, path: f.h5, outside: error}") + "run: {duration: 700}\n";
  EXPECT_NE(scene_error(scene_file)
                .find("key 'forcing.ocean.field.path': the file's snapshots cover [0, 600] s but the "
                      "run spans [0, 700] s with outside: error; import more snapshots or choose "
                      "clamp or cyclic"),
            std::string::npos)
      << scene_error(scene_file);
  // time_offset moves the run's span in the file's time.
  std::ofstream(scene_file) << scene_with_field("{type: file, path: f.h5, outside: error, time_offset: 100}") +
                                   "run: {duration: 550}\n";
  EXPECT_NE(scene_error(scene_file)
                .find("the file's snapshots cover [0, 600] s but the run spans [100, 650] s of the "
                      "file's time (time_offset 100 s) with outside: error"),
            std::string::npos)
      << scene_error(scene_file);
  std::ofstream(scene_file) << scene_with_field("{type: file, path: f.h5, outside: error, offset: [1, .nan]}");
  EXPECT_NE(scene_error(scene_file).find("forcing.ocean.field.offset"), std::string::npos) << scene_error(scene_file);
  std::ofstream(scene_file) << scene_with_field("{type: file, outside: clamp}");
  EXPECT_NE(scene_error(scene_file).find("missing required key 'path'"), std::string::npos) << scene_error(scene_file);
  std::ofstream(scene_file) << scene_with_field("{type: file, path: f.h5, outside: clamp, velocity: [1, 0]}");
  EXPECT_NE(scene_error(scene_file)
                .find("unknown key 'forcing.ocean.field.velocity'; allowed in "
                      "'forcing.ocean.field': type, path, outside, no_water, no_water_velocity, offset, "
                      "time_offset, land"),
            std::string::npos)
      << scene_error(scene_file);
}

TEST_F(FieldFileTest, AFloeOutsideTheWaterIsRefusedAtTheStartAndStopsTheRunWhenItDriftsOut) {
  io::write_field_file(dir_ / "f.h5", sample_file());  // a grid on x [0, 30], y [0, 20]
  const fs::path scene_file = dir_ / "s.yaml";
  const auto scene_at = [&](const char* position, const char* velocity) {
    std::ofstream(scene_file) << "name: f\nforcing:\n  ocean:\n    field: {type: file, path: f.h5, outside: clamp}\n"
                              << "floes:\n  - {rectangle: {width: 4, height: 4}, position: " << position
                              << ", velocity: " << velocity << "}\n";
    return scene::read_scene(scene_file);
  };
  try {
    (void)scene::build_world(scene_at("[29, 19]", "[0, 0]"));
    FAIL() << "a floe on land was accepted";
  } catch (const scene::SceneError& e) {
    EXPECT_NE(std::string(e.what()).find(
                  "body 0 starts where the ocean field has no water: " + (dir_ / "f.h5").string() + ": no water at ("),
              std::string::npos)
        << e.what();
  }
  dynamics::World w = scene::build_world(scene_at("[15, 10]", "[20, 0]"));
  try {
    for (int k = 0; k < 100000; ++k) w.step(1e-3);
    FAIL() << "the floe left the field without an error";
  } catch (const forcing::FieldError& e) {
    const std::string m = e.what();
    EXPECT_EQ(m.rfind("body 0 at (", 0), 0u) << m;
    EXPECT_NE(m.find("outside the field's grid x [0, 30], y [0, 20] m"), std::string::npos) << m;
    EXPECT_GT(w.positions()[0].x(), 27.0);  // its side faces reached x = 30 (half-width 2 m)
    EXPECT_LT(w.positions()[0].x(), 28.1);
  }
}

}  // namespace
}  // namespace polyfloe
