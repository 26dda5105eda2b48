// The bad-input corpus (tests/bad_input/*.yaml; its README says how a case is written): every case is run as
// `polyfloe run CASE [its args] -o SCRATCH/out` and must exit with code 2, print each of its `# expect:` lines (the
// file, key or line and what is allowed), and leave no output: the output folder is not created and nothing else
// appears in the case's scratch folder.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <optional>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "run/checkpoint.h"

namespace fs = std::filesystem;

namespace {

const fs::path kCorpus = fs::path(POLYFLOE_SOURCE_DIR) / "tests" / "bad_input";

std::string slurp(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

// Runs polyfloe with `args`, stdout and stderr to `log`; returns the exit code, or -signal.
int run_polyfloe(const std::vector<std::string>& args, const fs::path& log) {
  std::vector<std::string> all{POLYFLOE_BINARY};
  all.insert(all.end(), args.begin(), args.end());
  const pid_t pid = fork();
  if (pid == 0) {
    if (std::FILE* f = std::fopen(log.c_str(), "w")) {
      dup2(fileno(f), 1);
      dup2(fileno(f), 2);
    }
    std::vector<char*> argv;
    for (std::string& a : all) argv.push_back(a.data());
    argv.push_back(nullptr);
    execv(argv[0], argv.data());
    _exit(127);
  }
  int status = 0;
  waitpid(pid, &status, 0);
  return WIFEXITED(status) ? WEXITSTATUS(status) : -WTERMSIG(status);
}

struct Case {
  std::string name;  // file stem
  fs::path file;
  std::vector<std::string> args;    // "# args:" split on spaces, placeholders not yet replaced
  std::vector<std::string> expect;  // "# expect:" lines
  std::string what;                 // "# Bad input:" line
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

std::set<std::string> entries(const fs::path& dir) {
  std::set<std::string> s;
  for (const fs::directory_entry& e : fs::recursive_directory_iterator(dir)) s.insert(e.path().string());
  return s;
}

// The files some cases refer to: a real checkpoint and results file of a small run, and spoilt copies.
class BadInput : public ::testing::TestWithParam<Case> {
 protected:
  static inline fs::path base_;
  static inline fs::path checkpoint_, results_;

  static void SetUpTestSuite() {
    base_ = fs::temp_directory_path() / ("polyfloe_bad_input_" + std::to_string(getpid()));
    fs::remove_all(base_);
    fs::create_directories(base_);
    const fs::path run = base_ / "reference_run";
    const int code = run_polyfloe({"run", std::string(POLYFLOE_SOURCE_DIR) + "/dem/scenes/two_floes.yaml", "-o",
                                   run.string(), "--set", "output.checkpoint.every=1", "--set", "run.duration=1"},
                                  base_ / "reference_run.log");
    ASSERT_EQ(code, 0) << slurp(base_ / "reference_run.log");
    checkpoint_ = polyfloe::run::find_checkpoint(run);
    results_ = run / "results.h5";
    std::ofstream(base_ / "text.h5") << "not HDF5\n";
    const std::string bytes = slurp(checkpoint_);
    std::ofstream(base_ / "truncated.h5", std::ios::binary) << bytes.substr(0, bytes.size() / 2);
  }
  static void TearDownTestSuite() { fs::remove_all(base_); }
};

std::string replace_all(std::string s, const std::string& from, const std::string& to) {
  for (std::size_t at = s.find(from); at != std::string::npos; at = s.find(from, at + to.size()))
    s.replace(at, from.size(), to);
  return s;
}

TEST_P(BadInput, ExitsTwoNamingTheProblemAndWritesNothing) {
  const Case& c = GetParam();
  SCOPED_TRACE(c.file.string() + ": " + c.what);
  ASSERT_FALSE(c.what.empty()) << "the case has no '# Bad input:' line saying what is wrong";
  const fs::path scratch = base_ / c.name;
  fs::create_directories(scratch);
  std::ofstream(scratch / "file") << "a regular file\n";
  const fs::path out = scratch / "out";

  std::string scene = c.file.string();
  std::vector<std::string> args;
  bool has_output = false;
  for (std::string a : c.args) {
    a = replace_all(a, "@CKPT_TEXT", (base_ / "text.h5").string());
    a = replace_all(a, "@CKPT_TRUNCATED", (base_ / "truncated.h5").string());
    a = replace_all(a, "@CKPT", checkpoint_.string());
    a = replace_all(a, "@RESULTS", results_.string());
    a = replace_all(a, "@FILE", (scratch / "file").string());
    a = replace_all(a, "@SCRATCH", scratch.string());
    if (a.rfind("@SCENE=", 0) == 0) {
      scene = a.substr(7);
      continue;
    }
    has_output = has_output || a == "-o";
    args.push_back(a);
  }
  if (!has_output) args.insert(args.end(), {"-o", out.string()});
  args.insert(args.begin(), {"run", scene});

  const std::set<std::string> before = entries(scratch);
  const fs::path log = base_ / (c.name + ".log");
  const int code = run_polyfloe(args, log);
  const std::string text = slurp(log);
  EXPECT_EQ(code, 2) << text;
  EXPECT_FALSE(c.expect.empty()) << "the case has no '# expect:' line; polyfloe printed:\n" << text;
  for (const std::string& e : c.expect) EXPECT_NE(text.find(e), std::string::npos) << "expected '" << e << "' in:\n" << text;
  EXPECT_FALSE(fs::exists(out)) << "the output folder was created";
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

TEST(BadInputCorpus, HasAtLeastFiftyCases) { EXPECT_GE(corpus().size(), 50u); }

}  // namespace
