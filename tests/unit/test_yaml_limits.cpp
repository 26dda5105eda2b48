// The limits that make reading a scene safe on any input (scene/yaml_limits.h): recursive aliases, alias trees that
// expand past the budget, nesting, file kinds and sizes, and messages that quote a long value by its start.
#include <gtest/gtest.h>
#include <sys/stat.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <string>

#include "scene/scene_reader.h"
#include "scene/yaml_limits.h"
#include "scratch_dir.h"

namespace polyfloe::scene {
namespace {

const std::string kFloe = "floes:\n  - rectangle: {width: 10, height: 10}\n";

std::string error_of(const std::string& text, const std::vector<std::string>& overrides = {}) {
  try {
    (void)parse_scene(text, "t.yaml", overrides);
  } catch (const SceneError& e) {
    return e.what();
  }
  return "";
}

TEST(YamlLimits, ARecursiveAliasIsRefusedNamingItsLine) {
  for (const std::string& text :
       {"a: &x [*x]\n" + kFloe, "run: &a {duration: *a}\n" + kFloe, std::string("run: {duration: 1}\nfloes: &a [*a]\n"),
        "run: {duration: 1}\nforcing: &m {ocean: {x: [[*m]]}}\n" + kFloe}) {
    const std::string e = error_of(text);
    EXPECT_NE(e.find("a recursive YAML alias"), std::string::npos) << text << "\n" << e;
    EXPECT_EQ(e.rfind("t.yaml:", 0), 0u) << e;
  }
  // In a --set value too.
  const std::string e = error_of("run: {duration: 1}\n" + kFloe, {"run=&a [*a]"});
  EXPECT_NE(e.find("--set run"), std::string::npos) << e;
  EXPECT_NE(e.find("a recursive YAML alias"), std::string::npos) << e;
}

TEST(YamlLimits, BillionLaughsIsRefusedWithinTheBudget) {
  std::string text = "a0: &a0 [lol, lol, lol, lol, lol, lol, lol, lol, lol, lol]\n";
  for (int i = 1; i < 10; ++i) {
    text += "a" + std::to_string(i) + ": &a" + std::to_string(i) + " [";
    for (int k = 0; k < 10; ++k) text += (k ? ", *a" : "*a") + std::to_string(i - 1);
    text += "]\n";
  }
  const auto t0 = std::chrono::steady_clock::now();
  const std::string e = error_of(text + kFloe);
  EXPECT_NE(e.find("more than 4000000 values once its aliases are expanded"), std::string::npos) << e;
  // The walk stops at the budget (4e6 values), not at the 1e10 the aliases stand for: well under a minute even
  // under the sanitizers (a correctness bound, not a timing).
  EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count(), 60.0);
}

TEST(YamlLimits, AliasesWithinTheBudgetAreUsedAsCopies) {
  const Scene s = parse_scene(
      "run: {duration: 1}\nfloes:\n  - {rectangle: &r {width: 10, height: 4}, position: [0, 0]}\n"
      "  - {rectangle: *r, position: [20, 0]}\n",
      "t.yaml");
  ASSERT_EQ(s.bodies.size(), 2u);
}

TEST(YamlLimits, NestingDeeperThanTheLimitIsRefused) {
  const std::string deep = "x: " + std::string(70, '[') + std::string(70, ']') + "\n";
  EXPECT_NE(error_of(deep + kFloe).find("blocks nested more than 64 levels deep"), std::string::npos);
  const std::string deeper = "x: " + std::string(5000, '[') + std::string(5000, ']') + "\n";
  EXPECT_NE(error_of(deeper + kFloe).find("levels deep"), std::string::npos);
}

TEST(YamlLimits, OnlyRegularFilesWithinTheSizeLimitAreRead) {
  namespace fs = std::filesystem;
  const fs::path dir = tsupport::scratch_dir("polyfloe_yaml_limits");
  fs::remove_all(dir);
  fs::create_directories(dir);
  auto error_reading = [](const fs::path& p) {
    try {
      (void)read_scene(p);
    } catch (const SceneError& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  EXPECT_NE(error_reading("/dev/zero").find("not a regular file"), std::string::npos);
  ASSERT_EQ(mkfifo((dir / "fifo.yaml").c_str(), 0644), 0);
  EXPECT_NE(error_reading(dir / "fifo.yaml").find("not a regular file"), std::string::npos);
  fs::create_symlink("b.yaml", dir / "a.yaml");
  fs::create_symlink("a.yaml", dir / "b.yaml");
  EXPECT_NE(error_reading(dir / "a.yaml").find("Too many levels of symbolic links"), std::string::npos);
  {
    std::ofstream big(dir / "big.yaml");
    big << "#" << std::string(detail::kMaxSceneBytes, 'x') << "\n";
  }
  EXPECT_NE(error_reading(dir / "big.yaml").find("at most 16.0 MiB is read"), std::string::npos);
  {
    std::ofstream ok(dir / "ok.yaml");
    ok << "run: {duration: 1}\n" << kFloe;
  }
  EXPECT_EQ(read_scene(dir / "ok.yaml").bodies.size(), 1u);
  fs::remove_all(dir);
}

TEST(YamlLimits, MessagesQuoteALongValueByItsStart) {
  const std::string e = error_of("run: {duration: " + std::string(3000, 'x') + "}\n" + kFloe);
  EXPECT_NE(e.find("'xxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxx... (3000 characters)'"), std::string::npos) << e;
  EXPECT_LT(e.size(), 400u) << e;
}

TEST(YamlLimits, TheDefaultNameIsNeverAFolderAbove) {
  EXPECT_EQ(parse_scene("run: {duration: 1}\n" + kFloe, "...yaml").name, "scene");
  EXPECT_EQ(parse_scene("run: {duration: 1}\n" + kFloe, "dir/..yaml").name, "scene");
  EXPECT_EQ(parse_scene("run: {duration: 1}\n" + kFloe, "dir/ice.yaml").name, "ice");
}

}  // namespace
}  // namespace polyfloe::scene
