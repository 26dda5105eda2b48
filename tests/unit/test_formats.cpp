// The file formats beneath the writers (dem/formats): atomic replacement of a file, and the HDF5 wrapper's groups,
// series, attributes and errors, read back through the wrapper.
#include <gtest/gtest.h>

#include <cstdint>
#include <filesystem>
#include <span>
#include <string>
#include <vector>

#include "formats/atomic_file.h"
#include "formats/hdf5_file.h"
#include "scratch_dir.h"
#include "text_file.h"

namespace fs = std::filesystem;
using namespace polyfloe;

namespace {

using TempDir = tsupport::TestDir;
using tsupport::slurp;

TEST(Formats, AnAtomicFileReplacesContentAndLeavesNoTemporaries) {
  TempDir dir;
  const fs::path f = dir.path() / "a.pvd";
  io::write_file_atomic(f, "first version, rather long\n");
  EXPECT_EQ(slurp(f), "first version, rather long\n");
  io::write_file_atomic(f, "second");
  EXPECT_EQ(slurp(f), "second");
  io::write_file_atomic(f, "");
  EXPECT_EQ(slurp(f), "");
  int entries = 0;
  for ([[maybe_unused]] const auto& e : fs::directory_iterator(dir.path())) ++entries;
  EXPECT_EQ(entries, 1);
}

TEST(Formats, AnAtomicFileInAMissingFolderThrowsNamingTheFile) {
  TempDir dir;
  const fs::path f = dir.path() / "no_such_folder" / "x.pvd";
  try {
    io::write_file_atomic(f, "x");
    FAIL() << "expected IoError";
  } catch (const io::IoError& e) {
    EXPECT_NE(std::string(e.what()).find("x.pvd"), std::string::npos) << e.what();
  }
}

TEST(Formats, Hdf5SeriesRoundTripAndErrorsNameTheObject) {
  TempDir dir;
  const fs::path path = dir.path() / "w.h5";
  {
    io::hdf5::File f(path, io::hdf5::File::Mode::truncate);
    auto g = f.root().create_group("a/b");  // intermediate groups
    auto s = g.create_series("s", io::hdf5::DType::i64, {2, 3}, 4);
    std::vector<std::int64_t> rows(2 * 2 * 3);
    for (std::size_t k = 0; k < rows.size(); ++k) rows[k] = static_cast<std::int64_t>(k);
    s.append<std::int64_t>(rows);                                          // 2 rows
    s.append<std::int64_t>(std::span<const std::int64_t>(rows).first(6));  // 1 row
    EXPECT_EQ(s.dims(), (io::hdf5::Dims{3, 2, 3}));
    EXPECT_THROW(s.append<std::int64_t>(std::span<const std::int64_t>(rows).first(5)), io::hdf5::Hdf5Error);
    auto empty = g.create_series("empty_rows", io::hdf5::DType::f64, {0, 3}, 1);
    empty.append_rows<double>({}, 2);
    EXPECT_EQ(empty.dims(), (io::hdf5::Dims{2, 0, 3}));
    auto fixed = f.root().write_dataset<std::uint64_t>("u", std::vector<std::uint64_t>{1, 2, ~0ull});
    fixed.set_attribute("note", "x");
    fixed.set_attribute("note", "replaced");
    fixed.set_attribute("count", std::int64_t{42});
    f.root().create_series("v", io::hdf5::DType::f64, {}, 16);
    f.close();
  }
  io::hdf5::File f(path, io::hdf5::File::Mode::read_only);
  auto s = f.root().open_dataset("a/b/s");
  EXPECT_EQ(s.dtype(), io::hdf5::DType::i64);
  const auto all = s.read<std::int64_t>();
  ASSERT_EQ(all.size(), 18u);
  EXPECT_EQ(all[11], 11);
  EXPECT_EQ(all[12], 0);
  EXPECT_EQ(s.read_rows<double>(1, 1)[5], 11.0);  // converted on read
  auto u = f.root().open_dataset("u");
  EXPECT_EQ(u.read<std::uint64_t>()[2], ~0ull);
  EXPECT_EQ(u.string_attribute("note"), "replaced");
  EXPECT_EQ(u.int_attribute("count"), 42);
  EXPECT_FALSE(u.has_attribute("nothing"));
  EXPECT_TRUE(f.root().exists("a/b"));
  EXPECT_FALSE(f.root().exists("zzz"));
  try {
    f.root().open_dataset("a/missing");
    FAIL() << "expected Hdf5Error";
  } catch (const io::hdf5::Hdf5Error& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("w.h5"), std::string::npos) << what;
    EXPECT_NE(what.find("/a/missing"), std::string::npos) << what;
  }
  EXPECT_THROW(io::hdf5::File(dir.path() / "absent.h5", io::hdf5::File::Mode::read_only), io::IoError);
  EXPECT_THROW(io::hdf5::File(path, io::hdf5::File::Mode::exclusive), io::hdf5::Hdf5Error);
}

}  // namespace
