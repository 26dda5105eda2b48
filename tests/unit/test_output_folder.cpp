// The output folder contract (run/output_folder.h, io/output_manifest.h): refused locations, the manifest as input,
// the clean-up that removes listed files only and never follows a link, the lock, and nothing left behind by a
// refusal.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <set>
#include <string>

#include "formats/output_manifest.h"
#include "run/output_folder.h"
#include "scratch_dir.h"

namespace polyfloe::run {
namespace {

namespace fs = std::filesystem;

std::string refusal(const fs::path& p) {
  try {
    (void)OutputFolder::resolve(p);
  } catch (const OutputFolderError& e) {
    return e.what();
  }
  return "";
}

class OutputFolderTest : public ::testing::Test {
 protected:
  void SetUp() override {
    base_ = tsupport::scratch_dir("polyfloe_output_folder");
    fs::remove_all(base_);
    fs::create_directories(base_);
  }
  void TearDown() override { fs::remove_all(base_); }
  fs::path base_;
};

TEST_F(OutputFolderTest, SystemFoldersTheRootAndFoldersAboveTheCurrentOneAreRefused) {
  for (const char* p : {"/", "/etc", "/etc/polyfloe", "/usr/share/x", "/proc/self", "/dev/shm/x", "/sys/x", "/tmp"})
    EXPECT_NE(refusal(p), "") << p;
  EXPECT_NE(refusal(fs::current_path().parent_path()).find("a folder above the current folder"), std::string::npos);
  EXPECT_EQ(refusal(fs::current_path()), "");  // the current folder itself is allowed
  EXPECT_EQ(refusal(base_ / "new" / "deeper"), "");
  EXPECT_NE(refusal(base_ / std::string(300, 'n')).find("at most 255"), std::string::npos);
  EXPECT_NE(refusal("").find("an empty name"), std::string::npos);
}

TEST_F(OutputFolderTest, LinksAreResolvedOnceAndDanglingOnesRefused) {
  fs::create_directories(base_ / "real");
  fs::create_symlink(base_ / "real", base_ / "link");
  EXPECT_EQ(OutputFolder::resolve(base_ / "link"), fs::canonical(base_ / "real"));
  fs::create_symlink(base_ / "nowhere", base_ / "dangling");
  EXPECT_NE(refusal(base_ / "dangling").find("which does not exist"), std::string::npos);
  std::ofstream(base_ / "file") << "x";
  EXPECT_NE(refusal(base_ / "file" / "out").find("is not a folder"), std::string::npos);
}

TEST_F(OutputFolderTest, TheManifestIsReadAsInput) {
  std::ofstream(base_ / io::OutputManifest::kFileName) << "results.h5\n../outside\n/etc/passwd\nfloes/\n\n"
                                                          "a/./b\nfloes/floes_000000.vtp\nresults.h5\n";
  EXPECT_EQ(io::OutputManifest::read(base_),
            (std::vector<std::string>{"results.h5", "floes/", "floes/floes_000000.vtp"}));
}

TEST_F(OutputFolderTest, TheCleanUpRemovesListedFilesOnlyAndNeverFollowsLinks) {
  const fs::path out = base_ / "out";
  fs::create_directories(out / "floes");
  fs::create_directories(base_ / "elsewhere");
  std::ofstream(base_ / "elsewhere" / "floes_000001.vtp") << "keep";
  std::ofstream(out / "floes" / "floes_000000.vtp") << "old frame";
  std::ofstream(out / "floes" / ".floes_000000.vtp.tmp.12.3") << "a killed writer's";
  std::ofstream(out / "floes" / "floes_12.vtp") << "mine";
  std::ofstream(out / "results.h5") << "old results";
  fs::create_symlink(base_ / "elsewhere" / "floes_000001.vtp", out / "floes" / "floes_000001.vtp");
  std::ofstream(out / io::OutputManifest::kFileName)
      << "floes/\nfloes/floes_000000.vtp\nfloes/floes_000001.vtp\nresults.h5\n../elsewhere/floes_000001.vtp\n";
  {
    OutputFolder folder(out, OutputFolder::Mode::fresh);
    EXPECT_FALSE(fs::exists(out / "floes" / "floes_000000.vtp"));
    EXPECT_FALSE(fs::exists(out / "floes" / ".floes_000000.vtp.tmp.12.3"));
    EXPECT_FALSE(fs::exists(out / "results.h5"));
    EXPECT_TRUE(fs::exists(out / "floes" / "floes_12.vtp"));
    EXPECT_TRUE(fs::is_symlink(out / "floes" / "floes_000001.vtp"));  // listed, but a link: left alone
    EXPECT_TRUE(fs::exists(base_ / "elsewhere" / "floes_000001.vtp"));
    // A fresh list, but for floes/, which the clean-up left (the user's files are in it): still the program's.
    EXPECT_EQ(folder.manifest().entries(), (std::set<std::string>{"floes/"}));
  }
  EXPECT_TRUE(fs::exists(out / OutputFolder::kLockName));
}

TEST_F(OutputFolderTest, ALinkedOrForeignEntryIsRefusedAndNothingIsLeftBehind) {
  const fs::path out = base_ / "out";
  fs::create_directories(base_ / "elsewhere");
  fs::create_directories(out);
  fs::create_symlink(base_ / "elsewhere", out / "floes");
  EXPECT_THROW(OutputFolder(out, OutputFolder::Mode::fresh), OutputFolderError);
  EXPECT_FALSE(fs::exists(out / OutputFolder::kLockName));
  EXPECT_FALSE(fs::exists(out / io::OutputManifest::kFileName));
  fs::remove(out / "floes");
  std::ofstream(out / "results.h5") << "another program's";
  try {
    OutputFolder folder(out, OutputFolder::Mode::fresh);
    FAIL() << "an unlisted results.h5 was accepted";
  } catch (const OutputFolderError& e) {
    EXPECT_NE(std::string(e.what()).find("results.h5 exists but no polyfloe run into this folder wrote it"),
              std::string::npos);
  }
  EXPECT_EQ(std::ifstream(out / "results.h5").rdbuf() ? fs::file_size(out / "results.h5") : 0u, 17u);
}

TEST_F(OutputFolderTest, OneRunAtATime) {
  const fs::path out = base_ / "out";
  OutputFolder first(out, OutputFolder::Mode::fresh);
  try {
    OutputFolder second(out, OutputFolder::Mode::fresh);
    FAIL() << "a second holder of the folder was allowed";
  } catch (const OutputFolderError& e) {
    EXPECT_NE(std::string(e.what()).find("(process " + std::to_string(getpid()) + ") is writing into it"),
              std::string::npos)
        << e.what();
  }
}

TEST_F(OutputFolderTest, AResumedRunKeepsTheListAndRemovesOnlyListedTemporaries) {
  const fs::path out = base_ / "out";
  {
    OutputFolder folder(out, OutputFolder::Mode::fresh);
    folder.manifest().record("checkpoints/");
    folder.manifest().record("checkpoints/checkpoint_000010.h5");
  }
  fs::create_directories(out / "checkpoints");
  std::ofstream(out / "checkpoints" / ".checkpoint_000010.h5.tmp.5.1") << "torn";
  std::ofstream(out / "checkpoints" / ".mine.tmp.5.1") << "mine";
  OutputFolder folder(out, OutputFolder::Mode::resume);
  EXPECT_TRUE(folder.manifest().lists("checkpoints/checkpoint_000010.h5"));
  folder.manifest().remove_temporaries("checkpoints/");
  EXPECT_FALSE(fs::exists(out / "checkpoints" / ".checkpoint_000010.h5.tmp.5.1"));
  EXPECT_TRUE(fs::exists(out / "checkpoints" / ".mine.tmp.5.1"));
}

}  // namespace
}  // namespace polyfloe::run
