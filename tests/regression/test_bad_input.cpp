// The bad-input corpus (tests/bad_input/*.yaml; its README says how a case is written): every case is run as
// `polyfloe run CASE [its args] -o SCRATCH/out` and must exit with code 2, print each of its `# expect:` lines (the
// file, key or line and what is allowed), and leave no output: the output folder is not created and nothing else
// appears in the case's scratch folder.
#include <fcntl.h>
#include <gtest/gtest.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <functional>
#include <limits>
#include <filesystem>
#include <fstream>
#include <optional>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "run/checkpoint.h"
#include "same_run.h"

namespace fs = std::filesystem;

namespace {

const fs::path kCorpus = fs::path(POLYFLOE_SOURCE_DIR) / "tests" / "bad_input";

using polyfloe::tsupport::slurp;

// Runs polyfloe with `args`, stdout and stderr to `log`; returns the exit code, or -signal.
int run_polyfloe(const std::vector<std::string>& args, const fs::path& log) {
  return polyfloe::tsupport::run_to_end(args, log);
}

std::string replace_all(std::string s, const std::string& from, const std::string& to) {
  for (std::size_t at = s.find(from); at != std::string::npos; at = s.find(from, at + to.size()))
    s.replace(at, from.size(), to);
  return s;
}

std::string home() {
  const char* h = std::getenv("HOME");
  return h && *h ? h : "/root";
}

struct Case {
  std::string name;  // file stem
  fs::path file;
  std::vector<std::string> args;                // "# args:" split on spaces, placeholders not yet replaced
  std::vector<std::string> expect;              // "# expect:" lines
  std::vector<std::vector<std::string>> setup;  // "# setup:" lines, split on spaces
  std::string what;                             // "# Bad input:" line
};

void PrintTo(const Case& c, std::ostream* os) { *os << c.file.filename().string(); }

Case read_case(const fs::path& file) {
  Case c;
  c.name = file.stem().string();
  c.file = file;
  std::istringstream in(slurp(file));
  for (std::string line; std::getline(in, line);) {
    if (line.rfind('#', 0) != 0) break;  // the header is the leading comment block
    auto value = [&](const std::string& key) -> std::optional<std::string> {
      if (line.rfind(key, 0) != 0) return std::nullopt;
      std::string v = line.substr(key.size());
      v.erase(0, v.find_first_not_of(' '));
      while (!v.empty() && (v.back() == ' ' || v.back() == '\r')) v.pop_back();
      return v;
    };
    if (auto v = value("# expect:")) c.expect.push_back(*v);
    if (auto v = value("# Bad input:")) c.what = *v;
    if (auto v = value("# args:")) {
      std::istringstream words(*v);
      for (std::string w; words >> w;) c.args.push_back(w);
    }
    if (auto v = value("# setup:")) {
      std::istringstream words(*v);
      c.setup.emplace_back();
      for (std::string w; words >> w;) c.setup.back().push_back(w);
    }
  }
  return c;
}

std::vector<Case> corpus() {
  std::vector<Case> out;
  for (const fs::directory_entry& e : fs::directory_iterator(kCorpus))
    if (e.path().extension() == ".yaml") out.push_back(read_case(e.path()));
  std::sort(out.begin(), out.end(), [](const Case& a, const Case& b) { return a.name < b.name; });
  return out;
}

// Every entry below `dir` (links not followed), with a digest of each regular file's content: a file replaced
// under the same name counts as a change.
std::set<std::string> entries(const fs::path& dir) {
  std::set<std::string> s;
  for (const fs::directory_entry& e : fs::recursive_directory_iterator(dir)) {
    std::string entry = e.path().string();
    const fs::file_status st = e.symlink_status();
    if (fs::is_symlink(st))
      entry += " -> " + fs::read_symlink(e.path()).string();
    else if (fs::is_regular_file(st))
      entry += " #" + std::to_string(std::hash<std::string>{}(slurp(e.path())));
    s.insert(entry);
  }
  return s;
}

// The files some cases refer to: a real checkpoint and results file of a small run, and spoilt copies.
class BadInput : public ::testing::TestWithParam<Case> {
 protected:
  static inline fs::path base_;
  static inline fs::path checkpoint_, results_;
  static inline bool made_ = false;

  static void SetUpTestSuite() {
    base_ = fs::temp_directory_path() / ("polyfloe_bad_input_" + std::to_string(getpid()));
    fs::remove_all(base_);
    fs::create_directories(base_);
    made_ = false;  // (a repeated suite, --gtest_repeat, starts from an empty folder)
  }
  // Makes those files once, for the first case that refers to them (@CKPT..., @RESULTS). Most cases do not, and
  // CTest runs each case in a process of its own: the two runs this takes cost ~1.5 s a case under the sanitizers.
  static void make_files() {
    if (made_) return;
    const fs::path run = base_ / "reference_run";
    fs::remove_all(run);
    const int code = run_polyfloe({"run", std::string(POLYFLOE_SOURCE_DIR) + "/dem/scenes/two_floes.yaml", "-o",
                                   run.string(), "--set", "output.checkpoint.every=1", "--set", "run.duration=1"},
                                  base_ / "reference_run.log");
    ASSERT_EQ(code, 0) << slurp(base_ / "reference_run.log");
    checkpoint_ = polyfloe::run::find_checkpoint(run);
    results_ = run / "results.h5";
    std::ofstream(base_ / "text.h5") << "not HDF5\n";
    const std::string bytes = slurp(checkpoint_);
    std::ofstream(base_ / "truncated.h5", std::ios::binary) << bytes.substr(0, bytes.size() / 2);
    // Checkpoints with one field spoilt (@CKPT_EDIT_<name>): what a damaged or hand-edited file may hold.
    const polyfloe::run::Checkpoint good = polyfloe::run::read_checkpoint(checkpoint_);
    const double nan = std::numeric_limits<double>::quiet_NaN();
    const std::vector<std::pair<std::string, std::function<void(polyfloe::run::Checkpoint&)>>> edits{
        {"negative_steps", [](auto& c) { c.world.steps = static_cast<std::uint64_t>(-5); }},
        {"nan_time", [&](auto& c) { c.world.time = nan; }},
        {"huge_frames", [](auto& c) { c.frames = 5'000'000; }},
        {"nan_position", [&](auto& c) { c.world.position[0].x() = nan; }},
        {"unstable", [](auto& c) { c.kind = "unstable"; }},
        {"unknown_kind", [](auto& c) { c.kind = "best"; }},
        {"frames_backwards", [](auto& c) { std::swap(c.frame_times.front(), c.frame_times.back()); }},
        {"short_ids", [](auto& c) { c.world.ids.pop_back(); }},
        {"negative_dt", [](auto& c) { c.dt = -1e-3; }},
        {"short_history", [](auto& c) { c.world.velocity.pop_back(); }},
    };
    for (const auto& [name, edit] : edits) {
      polyfloe::run::Checkpoint c = good;
      edit(c);
      polyfloe::run::write_checkpoint(base_ / ("edit_" + name + ".h5"), c);
    }
    // The same for a spatial run's checkpoint (@CKPT_EDIT_spatial_<name>): the cube striking the plate.
    const fs::path spatial = base_ / "spatial_run";
    fs::remove_all(spatial);
    ASSERT_EQ(run_polyfloe({"run", std::string(POLYFLOE_SOURCE_DIR) + "/dem/scenes/cube_plate.yaml", "-o",
                            spatial.string(), "--set", "output.checkpoint.every=1", "--set", "run.duration=0.01"},
                           base_ / "spatial_run.log"),
              0)
        << slurp(base_ / "spatial_run.log");
    const polyfloe::run::Checkpoint cube = polyfloe::run::read_checkpoint(polyfloe::run::find_checkpoint(spatial));
    const std::vector<std::pair<std::string, std::function<void(polyfloe::run::Checkpoint&)>>> spatial_edits{
        {"spatial_orientation", [](auto& c) { c.spatial->orientation[1].coeffs() *= 1.01; }},
        {"spatial_nan_momentum", [&](auto& c) { c.spatial->angular_momentum[1].x() = nan; }},
        {"spatial_short_force", [](auto& c) { c.spatial->force.pop_back(); }},
    };
    for (const auto& [name, edit] : spatial_edits) {
      polyfloe::run::Checkpoint c = cube;
      edit(c);
      polyfloe::run::write_checkpoint(base_ / ("edit_" + name + ".h5"), c);
    }
    made_ = true;
  }
  static void TearDownTestSuite() { fs::remove_all(base_); }
};

// Runs a case's "# setup:" lines in its scratch folder (paths relative to it). Returns the descriptors of the locks
// it holds, released after the run.
std::vector<int> set_up(const std::vector<std::vector<std::string>>& lines, const fs::path& scratch) {
  std::vector<int> locks;
  for (const std::vector<std::string>& w : lines) {
    if (w.empty()) continue;
    const std::string& op = w[0];
    auto arg = [&](std::size_t i) {
      if (i >= w.size()) throw std::runtime_error("setup '" + op + "' needs " + std::to_string(i) + " arguments");
      return w[i];
    };
    if (op == "dir") {
      fs::create_directories(scratch / arg(1));
    } else if (op == "file") {  // file PATH [words of its content...]
      std::string text;
      for (std::size_t i = 2; i < w.size(); ++i) text += (i > 2 ? " " : "") + w[i];
      std::ofstream(scratch / arg(1)) << text << "\n";
    } else if (op == "link") {  // link TARGET PATH (TARGET as written, relative to PATH's folder or absolute)
      fs::create_symlink(replace_all(arg(1), "@SCRATCH", scratch.string()), scratch / arg(2));
    } else if (op == "big") {  // big PATH BYTES: a file of that many bytes (a YAML comment)
      std::ofstream f(scratch / arg(1), std::ios::binary);
      f << "#";
      f << std::string(std::stoul(arg(2)) - 2, 'x') << "\n";
    } else if (op == "fifo") {
      if (mkfifo((scratch / arg(1)).c_str(), 0644) != 0) throw std::runtime_error("mkfifo failed");
    } else if (op == "lock") {  // lock DIR: this process holds DIR/.polyfloe-lock as a run would
      const fs::path lock = scratch / arg(1) / ".polyfloe-lock";
      const int fd = open(lock.c_str(), O_RDWR | O_CREAT, 0644);
      if (fd < 0 || flock(fd, LOCK_EX | LOCK_NB) != 0) throw std::runtime_error("cannot lock " + lock.string());
      const std::string pid = std::to_string(getpid()) + "\n";
      if (write(fd, pid.data(), pid.size()) < 0) throw std::runtime_error("cannot write " + lock.string());
      locks.push_back(fd);
    } else {
      throw std::runtime_error("unknown setup '" + op + "'");
    }
  }
  return locks;
}

TEST_P(BadInput, ExitsTwoNamingTheProblemAndWritesNothing) {
  const Case& c = GetParam();
  SCOPED_TRACE(c.file.string() + ": " + c.what);
  ASSERT_FALSE(c.what.empty()) << "the case has no '# Bad input:' line saying what is wrong";
  const fs::path scratch = base_ / c.name;
  fs::create_directories(scratch);
  std::ofstream(scratch / "file") << "a regular file\n";
  const fs::path out = scratch / "out";
  for (const std::string& a : c.args) {
    if (a.find("@CKPT") != std::string::npos || a.find("@RESULTS") != std::string::npos) {
      ASSERT_NO_FATAL_FAILURE(make_files());
      break;
    }
  }

  std::string scene = c.file.string();
  std::vector<std::string> args;
  bool has_output = false;
  for (std::string a : c.args) {
    a = replace_all(a, "@SP", " ");  // a space inside one argument
    for (std::size_t at = a.find("@CKPT_EDIT_"); at != std::string::npos; at = a.find("@CKPT_EDIT_")) {
      std::size_t end = at + 11;
      while (end < a.size() && (std::isalnum(static_cast<unsigned char>(a[end])) || a[end] == '_')) ++end;
      a.replace(at, end - at, (base_ / ("edit_" + a.substr(at + 11, end - at - 11) + ".h5")).string());
    }
    a = replace_all(a, "@CKPT_TEXT", (base_ / "text.h5").string());
    a = replace_all(a, "@CKPT_TRUNCATED", (base_ / "truncated.h5").string());
    a = replace_all(a, "@CKPT", checkpoint_.string());
    a = replace_all(a, "@RESULTS", results_.string());
    a = replace_all(a, "@FILE", (scratch / "file").string());
    a = replace_all(a, "@SCRATCH", scratch.string());
    a = replace_all(a, "@HOME", home());
    if (a.rfind("@SCENE=", 0) == 0) {  // a relative path is the repository's (the test may run anywhere)
      scene = a.substr(7);
      if (fs::path(scene).is_relative()) scene = (fs::path(POLYFLOE_SOURCE_DIR) / scene).string();
      continue;
    }
    has_output = has_output || a == "-o";
    args.push_back(a);
  }
  if (!has_output) args.insert(args.end(), {"-o", out.string()});
  args.insert(args.begin(), {"run", scene});

  const std::vector<int> locks = set_up(c.setup, scratch);
  const bool out_existed = fs::exists(fs::symlink_status(out));
  const std::set<std::string> before = entries(scratch);
  const fs::path log = base_ / (c.name + ".log");
  const int code = run_polyfloe(args, log);
  for (const int fd : locks) close(fd);
  const std::string text = slurp(log);
  EXPECT_EQ(code, 2) << text;
  EXPECT_FALSE(c.expect.empty()) << "the case has no '# expect:' line; polyfloe printed:\n" << text;
  for (const std::string& e : c.expect)
    EXPECT_NE(text.find(e), std::string::npos) << "expected '" << e << "' in:\n" << text;
  if (!out_existed) {
    EXPECT_FALSE(fs::exists(fs::symlink_status(out))) << "the output folder was created";
  }
  EXPECT_EQ(entries(scratch), before) << "files appeared in " << scratch;
  EXPECT_EQ(text.find("AddressSanitizer"), std::string::npos) << text;
  EXPECT_EQ(text.find("runtime error"), std::string::npos) << text;
}

INSTANTIATE_TEST_SUITE_P(Corpus, BadInput, ::testing::ValuesIn(corpus()),
                         [](const ::testing::TestParamInfo<Case>& info) { return info.param.name; });

// An output folder inside a folder without write permission (the corpus has one below a regular file). Root may
// write anywhere, so this is skipped when the tests run as root.
TEST(BadInputOutput, FolderWithoutWritePermission) {
  if (geteuid() == 0) GTEST_SKIP() << "running as root: every folder is writable";
  const fs::path base = fs::temp_directory_path() / ("polyfloe_read_only_" + std::to_string(getpid()));
  fs::remove_all(base);
  fs::create_directories(base / "locked");
  fs::permissions(base / "locked", fs::perms::owner_read | fs::perms::owner_exec);
  const fs::path log = base / "log";
  const int code = run_polyfloe({"run", std::string(POLYFLOE_SOURCE_DIR) + "/dem/scenes/two_floes.yaml", "-o",
                                 (base / "locked" / "out").string()},
                                log);
  const std::string text = slurp(log);
  EXPECT_EQ(code, 2) << text;
  EXPECT_NE(text.find("locked is not writable"), std::string::npos) << text;
  EXPECT_NE(text.find("choose another with -o DIR"), std::string::npos) << text;
  EXPECT_FALSE(fs::exists(base / "locked" / "out"));
  fs::permissions(base / "locked", fs::perms::owner_all);
  fs::remove_all(base);
}

TEST(BadInputCorpus, HasAtLeastTwoHundredCases) { EXPECT_GE(corpus().size(), 200u); }

}  // namespace
