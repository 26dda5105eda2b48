// Running polyfloe from a test and comparing two runs bitwise: every dataset of results.h5, every VTK file and
// .pvd, and the final state of the newest checkpoint (forces, drift model, contact history, bonds: what no output
// shows). Shared by the restart and thread-count tests.
#pragma once

#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <utility>
#include <optional>
#include <vector>

#include "formats/hdf5_file.h"
#include "run/checkpoint.h"
#include "state_bytes.h"

namespace polyfloe::tsupport {

namespace fs = std::filesystem;

// Starts polyfloe with `args`, stdout and stderr to `log`.
inline pid_t spawn(const std::vector<std::string>& args, const fs::path& log) {
  std::vector<std::string> all{POLYFLOE_BINARY};
  all.insert(all.end(), args.begin(), args.end());
  const pid_t pid = fork();
  if (pid == 0) {
    std::FILE* f = std::fopen(log.c_str(), "w");
    if (f) {
      dup2(fileno(f), 1);
      dup2(fileno(f), 2);
    }
    std::vector<char*> argv;
    for (std::string& a : all) argv.push_back(a.data());
    argv.push_back(nullptr);
    execv(argv[0], argv.data());
    _exit(127);
  }
  return pid;
}

// Exit code, or -signal.
inline int wait_for(pid_t pid) {
  int status = 0;
  waitpid(pid, &status, 0);
  return WIFEXITED(status) ? WEXITSTATUS(status) : -WTERMSIG(status);
}

inline int run_to_end(const std::vector<std::string>& args, const fs::path& log) { return wait_for(spawn(args, log)); }

inline std::string slurp(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

// Every dataset of the file by path, as raw bytes of its values read as doubles / integers.
inline void collect(const io::hdf5::Group& g, const std::string& prefix,
                    std::vector<std::pair<std::string, std::vector<std::uint64_t>>>& out) {
  using io::hdf5::DType;
  for (const io::hdf5::Group::Child& c : g.children()) {
    const std::string name = prefix + "/" + c.name;
    if (c.group) {
      collect(g.open_group(c.name), name, out);
      continue;
    }
    const io::hdf5::Dataset d = g.open_dataset(c.name);
    std::vector<std::uint64_t> bits;
    if (d.dtype() == DType::f64 || d.dtype() == DType::f32) {
      for (double v : d.read<double>()) {
        std::uint64_t b;
        std::memcpy(&b, &v, sizeof b);
        bits.push_back(b);
      }
    } else if (d.dtype() == DType::u64) {
      bits = d.read<std::uint64_t>();
    } else {
      for (std::int64_t v : d.read<std::int64_t>()) bits.push_back(static_cast<std::uint64_t>(v));
    }
    out.emplace_back(name, std::move(bits));
  }
}

inline std::vector<std::pair<std::string, std::vector<std::uint64_t>>> datasets(const fs::path& file) {
  const io::hdf5::File f(file, io::hdf5::File::Mode::read_only);
  std::vector<std::pair<std::string, std::vector<std::uint64_t>>> out;
  collect(f.root(), "", out);
  return out;
}

// The files of a run's VTK series, relative to its folder.
inline std::vector<std::string> vtk_files(const fs::path& dir) {
  std::vector<std::string> out;
  for (const char* sub : {"floes", "bodies", "contacts", "bonds", "velocity"}) {
    if (!fs::is_directory(dir / sub)) continue;
    for (const auto& e : fs::directory_iterator(dir / sub))
      out.push_back(std::string(sub) + "/" + e.path().filename().string());
  }
  std::sort(out.begin(), out.end());
  return out;
}

inline void expect_same_run(const fs::path& a, const fs::path& b) {
  const auto da = datasets(a / "results.h5"), db = datasets(b / "results.h5");
  ASSERT_EQ(da.size(), db.size());
  for (std::size_t k = 0; k < da.size(); ++k) {
    EXPECT_EQ(da[k].first, db[k].first);
    EXPECT_TRUE(da[k].second == db[k].second) << "results.h5:" << da[k].first << " differs";
  }
  const auto fa = vtk_files(a), fb = vtk_files(b);
  EXPECT_EQ(fa, fb);
  for (const std::string& f : fa) EXPECT_TRUE(slurp(a / f) == slurp(b / f)) << f << " differs";
  for (const char* pvd : {"floes.pvd", "bodies.pvd", "contacts.pvd", "bonds.pvd", "velocity.pvd"})
    EXPECT_EQ(slurp(a / pvd), slurp(b / pvd)) << pvd;
  // results.xmf and the files of its frames (a restart keeps the interrupted run's files of the frames it adopts,
  // rewrites the rest and removes what the new results.xmf does not name): the same names, the same bits.
  EXPECT_EQ(fs::exists(a / "results.xmf"), fs::exists(b / "results.xmf"));
  if (fs::exists(a / "results.xmf")) {
    EXPECT_EQ(slurp(a / "results.xmf"), slurp(b / "results.xmf"));
  }
  const auto xdmf_files = [](const fs::path& dir) {
    std::vector<std::string> out;
    if (fs::is_directory(dir / "xdmf"))
      for (const auto& e : fs::directory_iterator(dir / "xdmf")) out.push_back("xdmf/" + e.path().filename().string());
    std::sort(out.begin(), out.end());
    return out;
  };
  const auto xa = xdmf_files(a), xb = xdmf_files(b);
  EXPECT_EQ(xa, xb);
  if (xa == xb) {
    for (const std::string& f : xa) EXPECT_TRUE(datasets(a / f) == datasets(b / f)) << f << " differs";
  }
  // The final state, including what no output shows (forces, drift loads, spring history, bond stresses): every
  // field of the state (dynamics/state_fields.h), planar or spatial, as bytes.
  const auto ca = run::read_checkpoint(run::find_checkpoint(a));
  const auto cb = run::read_checkpoint(run::find_checkpoint(b));
  EXPECT_EQ(ca.frames, cb.frames);
  ASSERT_EQ(ca.spatial.has_value(), cb.spatial.has_value());
  const auto sa = ca.spatial ? state_bytes(*ca.spatial) : state_bytes(ca.world);
  const auto sb = cb.spatial ? state_bytes(*cb.spatial) : state_bytes(cb.world);
  ASSERT_EQ(sa.size(), sb.size());
  for (std::size_t k = 0; k < sa.size(); ++k) {
    EXPECT_EQ(sa[k].first, sb[k].first);
    EXPECT_TRUE(sa[k].second == sb[k].second) << "the final state's " << sa[k].first << " differs";
  }
}

// A scratch folder of this process (tests may run concurrently).
inline fs::path scratch(const std::string& name) {
  return fs::temp_directory_path() / ("polyfloe_restart_" + name + "_" + std::to_string(getpid()));
}

}  // namespace polyfloe::tsupport
