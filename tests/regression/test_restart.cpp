// Checkpoint and restart, and crash-safe output: a run killed with SIGKILL at random moments and restarted from its
// newest checkpoint each time ends bitwise where the uninterrupted run ends (every HDF5 dataset, every VTK file,
// the final state); after every kill each completed frame and the newest checkpoint read back; bad checkpoints
// and mismatched restarts are refused with exit code 2 before any output is touched; an unstable run leaves its
// state for inspection.
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <random>
#include <set>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "formats/hdf5_file.h"
#include "pvd.h"
#include "run/checkpoint.h"
#include "same_run.h"
#include "spatial_pile.h"

namespace fs = std::filesystem;
using polyfloe::io::hdf5::Dataset;
using polyfloe::io::hdf5::File;
using polyfloe::io::hdf5::Group;

using polyfloe::tsupport::expect_same_run;
using polyfloe::tsupport::run_to_end;
using polyfloe::tsupport::scratch;
using polyfloe::tsupport::slurp;
using polyfloe::tsupport::spawn;
using polyfloe::tsupport::wait_for;

namespace {
const std::string kSource = POLYFLOE_SOURCE_DIR;

// After a kill: every frame the series list is complete and readable, results.h5 opens and holds at least the
// frames of the newest checkpoint, and that checkpoint reads back.
void expect_readable_after_kill(const fs::path& dir) {
  for (const char* pvd : {"floes.pvd", "contacts.pvd", "bonds.pvd", "velocity.pvd"}) {
    if (!fs::exists(dir / pvd)) continue;
    const auto entries = polyfloe::tsupport::read_pvd(dir / pvd);
    const std::string text = slurp(dir / pvd);
    EXPECT_NE(text.find("</VTKFile>"), std::string::npos) << pvd << " is not a complete collection";
    for (const auto& [t, file] : entries) {
      EXPECT_TRUE(fs::exists(dir / file)) << pvd << " lists " << file << " at t = " << t << ", which is missing";
      const std::string body = slurp(dir / file);
      EXPECT_NE(body.find("</VTKFile>"), std::string::npos) << file << " is incomplete";
    }
  }
  std::size_t frames_in_h5 = 0;
  for (const char* name : {"results.h5", ".results.h5.interrupted", "checkpoints/results.h5"}) {
    if (!fs::exists(dir / name)) continue;
    try {
      const File f(dir / name, File::Mode::read_only);
      frames_in_h5 = std::max<std::size_t>(frames_in_h5, f.root().open_dataset("time").rows());
      if (std::string(name) == ".results.h5.interrupted") break;  // the restart's source of truth
    } catch (const std::exception& e) {
      if (std::string(name) == "results.h5" && fs::exists(dir / ".results.h5.interrupted")) continue;  // being rebuilt
      // HDF5 does not promise a file its killed writer leaves: the copy taken with the checkpoints must then hold
      // every frame of the newest checkpoint (checked below).
      if (std::string(name) != "checkpoints/results.h5" && fs::exists(dir / "checkpoints/results.h5")) {
        std::fprintf(stderr, "note: %s unreadable after a kill (%s); the checkpoints' copy stands in\n", name,
                     e.what());
        continue;
      }
      // Killed while a fresh run was creating its files, before its first frame: nothing was complete to lose.
      const fs::path pvd = dir / (fs::exists(dir / "bodies.pvd") ? "bodies.pvd" : "floes.pvd");
      const bool nothing_done = !fs::exists(pvd) || polyfloe::tsupport::read_pvd(pvd).empty();
      if (nothing_done && !fs::is_directory(dir / "checkpoints")) continue;
      ADD_FAILURE() << name << " is unreadable after the kill: " << e.what();
    }
  }
  if (fs::is_directory(dir / "checkpoints")) {
    const fs::path newest = polyfloe::run::find_checkpoint(dir);
    const polyfloe::run::Checkpoint c = polyfloe::run::read_checkpoint(newest);  // throws if unreadable
    EXPECT_GE(frames_in_h5, static_cast<std::size_t>(c.frames)) << "results.h5 lost frames of " << newest;
  }
}

struct Interrupted {
  int kills = 0;     // kills that hit a running simulation
  int restarts = 0;  // runs started with --restart
};

// Runs `args` into `dir`, killing it `kills` times at random moments (uniform over the part of the uninterrupted
// run's wall time `wall` still to go; `duration` is the simulated time [s]), each time restarting from the newest
// checkpoint (or afresh before the first), then lets it finish.
Interrupted run_with_kills(const std::vector<std::string>& args, const fs::path& dir, int kills, double wall,
                           double duration, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> when(0.15, 0.85);
  Interrupted r;
  auto next_args = [&] {
    std::vector<std::string> a = args;
    a.insert(a.end(), {"-o", dir.string()});
    if (fs::is_directory(dir / "checkpoints") && !fs::is_empty(dir / "checkpoints")) {
      a.insert(a.end(), {"--restart", dir.string()});
      ++r.restarts;
    }
    return a;
  };
  for (int k = 0; k < kills; ++k) {
    // A random moment of what is left to run (the uninterrupted run's wall time scaled by the simulated time left).
    double done = 0.0;
    if (fs::is_directory(dir / "checkpoints") && !fs::is_empty(dir / "checkpoints"))
      done = polyfloe::run::read_checkpoint(polyfloe::run::find_checkpoint(dir)).time() / duration;
    const pid_t pid = spawn(next_args(), dir.string() + ".log");
    std::this_thread::sleep_for(std::chrono::duration<double>(when(rng) * wall * (1.0 - done)));
    kill(pid, SIGKILL);
    const int code = wait_for(pid);
    if (code == -SIGKILL)
      ++r.kills;
    else
      EXPECT_EQ(code, 0) << slurp(dir.string() + ".log");
    expect_readable_after_kill(dir);
  }
  const int code = run_to_end(next_args(), dir.string() + ".log");
  EXPECT_EQ(code, 0) << slurp(dir.string() + ".log");
  return r;
}

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

}  // namespace

namespace {

// Runs `args` whole, then again killed `kills` times and restarted, into scratch(name); the two must be the same
// bits. Returns the killed run's folder (removed with the base by the caller).
fs::path killed_run_restarts_bitwise(const std::string& name, const std::vector<std::string>& args, int kills,
                                     double duration, std::uint64_t seed, int min_kills, int min_restarts) {
  const fs::path base = scratch(name);
  fs::remove_all(base);
  fs::create_directories(base);
  std::vector<std::string> a = args;
  a.insert(a.end(), {"-o", (base / "whole").string()});
  const auto t0 = std::chrono::steady_clock::now();
  EXPECT_EQ(run_to_end(a, base / "whole.log"), 0) << slurp(base / "whole.log");
  const double wall = seconds_since(t0);
  const Interrupted r = run_with_kills(args, base / "killed", kills, wall, duration, seed);
  std::printf("uninterrupted run %.2f s wall; %d kills hit the running simulation, %d restarts\n", wall, r.kills,
              r.restarts);
  EXPECT_GE(r.kills, min_kills);
  EXPECT_GE(r.restarts, min_restarts);
  expect_same_run(base / "whole", base / "killed");
  return base;
}

}  // namespace

TEST(Restart, KilledChannelRunRestartsBitwise) {
  // The channel scene shortened: 1,158 floes and walls, contacts with friction history, all drift terms, the
  // channel monitor and the velocity grid; frames every 0.25 s, a checkpoint every 2 frames.
  const fs::path base = killed_run_restarts_bitwise(
      "channel",
      {"run", kSource + "/dem/scenes/channel.yaml", "--set", "run.duration=6", "--set", "output.interval=0.25", "--set",
       "output.checkpoint.every=2", "--set", "output.checkpoint.keep=2"},
      4, 6.0, 20261122, 3, 2);
  // Checkpoints are pruned to the newest `keep`; the final one is among them.
  int count = 0;
  for (const auto& e : fs::directory_iterator(base / "killed" / "checkpoints"))
    count += e.path().filename().string().rfind("checkpoint_", 0) == 0;
  EXPECT_EQ(count, 2);
  fs::remove_all(base);
}

TEST(Restart, KilledSpatialRunRestartsBitwise) {
  // 290 boxes piling up on a plate under gravity (tests/support/spatial_pile.h): quaternions, angular momenta,
  // manifold contacts and their friction springs, the narrow phase's counts; a checkpoint every 2 frames.
  const fs::path scene_dir = scratch("spatial_scene");
  fs::create_directories(scene_dir);
  const std::string scene = polyfloe::tsupport::write_spatial_pile(scene_dir / "pile.yaml");
  fs::remove_all(killed_run_restarts_bitwise(
      "spatial", {"run", scene, "--set", "output.checkpoint.every=2", "--set", "output.checkpoint.keep=2"}, 3, 0.4,
      20261127, 2, 1));
  fs::remove_all(scene_dir);
}

TEST(Restart, KilledFoundationForceModelRunRestartsBitwise) {
  // The channel scene under the foundation force model, whose first contact step depends on whether the pair
  // touched the step before (the contact history a checkpoint carries): 1.5 s, a checkpoint every 2 frames.
  fs::remove_all(
      killed_run_restarts_bitwise("foundation",
                                  {"run", kSource + "/dem/scenes/channel.yaml", "--set", "run.duration=1.5", "--set",
                                   "contact.force_model=foundation", "--set", "output.interval=0.125", "--set",
                                   "output.checkpoint.every=2", "--set", "output.checkpoint.keep=2"},
                                  3, 1.5, 20261126, 2, 1));
}

TEST(Restart, KilledFrozenSheetRunRestartsBitwise) {
  // A small frozen sheet of triangles squeezed between plates until its bonds break: the bond state (intact points,
  // stresses, broken times) carries across the restarts.
  const std::vector<std::string> args{"run",   kSource + "/dem/scenes/uniaxial_compression.yaml",
                                      "--set", "ice_sheet.region=[0,0,60,60]",
                                      "--set", "ice_sheet.cell_size=8",
                                      "--set", "ice_sheet.bonds.tensile_strength=1e5",
                                      "--set", "ice_sheet.bonds.shear_strength=1e5",
                                      "--set", "floes.0.position=[-10,30]",
                                      "--set", "floes.1.position=[70,30]",
                                      "--set", "run.duration=0.3",
                                      "--set", "output.interval=0.01",
                                      "--set", "output.checkpoint.every=3"};
  const fs::path base = scratch("sheet");
  fs::remove_all(base);
  fs::create_directories(base);
  std::vector<std::string> a = args;
  a.insert(a.end(), {"-o", (base / "whole").string()});
  const auto t0 = std::chrono::steady_clock::now();
  ASSERT_EQ(run_to_end(a, base / "whole.log"), 0) << slurp(base / "whole.log");
  const double wall = seconds_since(t0);
  {
    const File f(base / "whole" / "results.h5", File::Mode::read_only);
    const auto intact = f.root().open_group("bonds").open_dataset("intact_faces").read<std::int64_t>();
    ASSERT_LT(intact.back(), intact.front()) << "the test needs bonds that break";
  }
  const Interrupted r = run_with_kills(args, base / "killed", 2, wall, 0.3, 7);
  EXPECT_GE(r.kills, 1);
  expect_same_run(base / "whole", base / "killed");
  fs::remove_all(base);
}

// Every series dataset of the file readable: at least rows() - 1 rows (a kill between two appends of a frame
// leaves some series one row ahead of /time) and its rows readable.
std::uint64_t expect_series_readable(const Group& g, std::uint64_t frames) {
  std::uint64_t checked = 0;
  for (const Group::Child& c : g.children()) {
    if (c.group) {
      checked += expect_series_readable(g.open_group(c.name), frames);
      continue;
    }
    const Dataset d = g.open_dataset(c.name);
    if (!d.extendible()) {
      (void)d.read<double>();
      continue;
    }
    EXPECT_GE(d.rows() + 1, frames) << d.where();
    if (d.rows() > 0) (void)d.read_rows<double>(0, d.rows());
    ++checked;
  }
  return checked;
}

TEST(Restart, KilledWhileWritingHdf5EveryStepLeavesAReadableFile) {
  // Two floes, HDF5 only, a frame at every step (2,528 frames), a checkpoint every 200 frames: the process spends
  // most of its time appending to results.h5 and flushing it, so the kills land in the middle of writes. Every kill
  // must leave every flushed frame readable in results.h5, or (HDF5 does not promise a file its killed writer
  // leaves, and 1 kill in a few hundred here tears a metadata block) every frame of the newest checkpoint readable
  // in the copy taken with it, checkpoints/results.h5.
  const std::vector<std::string> args{
      "run",   kSource + "/dem/scenes/two_floes.yaml", "--set", "output.vtk=false", "--set", "output.interval=1e-4",
      "--set", "output.checkpoint.every=200"};
  const fs::path out = scratch("h5kill");
  fs::remove_all(out);
  std::vector<std::string> a = args;
  a.insert(a.end(), {"-o", out.string()});
  // The uninterrupted run's wall time: the faster of two (the first may pay for a cold start).
  double wall = 1e300;
  for (int k = 0; k < 2; ++k) {
    const auto t0 = std::chrono::steady_clock::now();
    ASSERT_EQ(run_to_end(a, out.string() + ".log"), 0) << slurp(out.string() + ".log");
    wall = std::min(wall, seconds_since(t0));
  }
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> when(0.4, 0.95);
  // 20 kills that hit the running process: a run that ends before its kill (the machine got faster than when
  // the wall time was measured) does not count, and the kills come earlier from then on.
  int killed = 0, torn = 0, finished = 0;
  for (int k = 0; killed < 20 && k < 60; ++k) {
    const pid_t pid = spawn(a, out.string() + ".log");
    std::this_thread::sleep_for(std::chrono::duration<double>(when(rng) * wall));
    kill(pid, SIGKILL);
    const int code = wait_for(pid);
    if (code != -SIGKILL) {
      EXPECT_EQ(code, 0) << slurp(out.string() + ".log");
      ++finished;
      wall *= 0.8;
      continue;
    }
    ++killed;
    if (!fs::exists(out / "results.h5")) continue;  // killed before the file was created
    try {
      const File f(out / "results.h5", File::Mode::read_only);
      const std::uint64_t frames = f.root().open_dataset("time").rows();
      EXPECT_GT(expect_series_readable(f.root(), frames), 10u);
    } catch (const std::exception& e) {
      ++torn;
      std::fprintf(stderr, "kill %d left results.h5 unreadable (%s)\n", k, e.what());
      if (!fs::is_directory(out / "checkpoints")) continue;  // before the first checkpoint: nothing promised
      const polyfloe::run::Checkpoint c = polyfloe::run::read_checkpoint(polyfloe::run::find_checkpoint(out));
      const File f(out / "checkpoints/results.h5", File::Mode::read_only);
      EXPECT_GE(f.root().open_dataset("time").rows(), static_cast<std::uint64_t>(c.frames)) << "kill " << k;
      EXPECT_GT(expect_series_readable(f.root(), static_cast<std::uint64_t>(c.frames)), 10u) << "kill " << k;
    }
  }
  std::fprintf(stderr, "%d kills (%d runs ended first), results.h5 unreadable after %d\n", killed, finished, torn);
  EXPECT_EQ(killed, 20);
  fs::remove_all(out);
  fs::remove(out.string() + ".log");
}

// A results.h5 the kill left unreadable (here: cut in half): the restart copies the frames from the copy taken with
// the checkpoint, and the run still ends bitwise as the uninterrupted one.
TEST(Restart, UnreadableResultsAreRebuiltFromTheCheckpointsCopy) {
  const std::vector<std::string> args{"run", kSource + "/dem/scenes/two_floes.yaml", "--set",
                                      "output.checkpoint.every=5"};
  const fs::path ref = scratch("torn_ref"), dir = scratch("torn");
  fs::remove_all(ref);
  fs::remove_all(dir);
  std::vector<std::string> a = args;
  a.insert(a.end(), {"-o", ref.string()});
  const auto t0 = std::chrono::steady_clock::now();
  ASSERT_EQ(run_to_end(a, ref.string() + ".log"), 0) << slurp(ref.string() + ".log");
  const double wall = seconds_since(t0);
  a = args;
  a.insert(a.end(), {"-o", dir.string()});
  const pid_t pid = spawn(a, dir.string() + ".log");
  std::this_thread::sleep_for(std::chrono::duration<double>(0.6 * wall));
  kill(pid, SIGKILL);
  wait_for(pid);
  ASSERT_TRUE(fs::exists(dir / "checkpoints/results.h5"));
  const std::string bytes = slurp(dir / "results.h5");
  std::ofstream(dir / "results.h5", std::ios::binary | std::ios::trunc) << bytes.substr(0, bytes.size() / 2);
  a.insert(a.end(), {"--restart", dir.string()});
  ASSERT_EQ(run_to_end(a, dir.string() + ".log"), 0) << slurp(dir.string() + ".log");
  expect_same_run(ref, dir);
  EXPECT_FALSE(fs::exists(dir / ".results.h5.interrupted"));
  // Both copies gone: refused, naming each file and why.
  std::ofstream(dir / "results.h5", std::ios::trunc) << "x";
  std::ofstream(dir / "checkpoints/results.h5", std::ios::trunc) << "x";
  EXPECT_EQ(run_to_end(a, dir.string() + ".log"), 2);
  const std::string log = slurp(dir.string() + ".log");
  EXPECT_NE(log.find("no copy of the interrupted run's results holds the checkpoint's frames"), std::string::npos)
      << log;
  EXPECT_NE(log.find("checkpoints/results.h5 cannot be read"), std::string::npos) << log;
  fs::remove_all(ref);
  fs::remove_all(dir);
  fs::remove(ref.string() + ".log");
  fs::remove(dir.string() + ".log");
}

TEST(Restart, BadCheckpointsAreRefusedBeforeAnyOutputIsTouched) {
  const std::string scene = kSource + "/dem/scenes/two_floes.yaml";
  const fs::path base = scratch("bad");
  fs::remove_all(base);
  fs::create_directories(base);
  const fs::path run = base / "run";
  ASSERT_EQ(run_to_end({"run", scene, "-o", run.string(), "--set", "output.checkpoint.every=1"}, base / "log"), 0)
      << slurp(base / "log");
  const fs::path good = polyfloe::run::find_checkpoint(run);
  const std::string results = slurp(run / "results.h5"), floes = slurp(run / "floes.pvd");

  auto refused = [&](const std::vector<std::string>& args, const std::string& expect) {
    SCOPED_TRACE(expect);
    const int code = run_to_end(args, base / "log");
    const std::string log = slurp(base / "log");
    EXPECT_EQ(code, 2) << log;
    EXPECT_NE(log.find(expect), std::string::npos) << log;
    // The interrupted run's outputs are untouched.
    EXPECT_TRUE(slurp(run / "results.h5") == results);
    EXPECT_EQ(slurp(run / "floes.pvd"), floes);
  };
  refused({"run", scene, "--restart", (base / "missing.h5").string()}, "missing.h5: no such file or folder");
  std::ofstream(base / "text.h5") << "not HDF5\n";
  refused({"run", scene, "--restart", (base / "text.h5").string()}, "text.h5: cannot be read");
  {  // truncated
    const std::string bytes = slurp(good);
    std::ofstream(base / "truncated.h5", std::ios::binary) << bytes.substr(0, bytes.size() / 2);
  }
  refused({"run", scene, "--restart", (base / "truncated.h5").string(), "-o", run.string()}, "truncated.h5");
  {  // an HDF5 file that is not a checkpoint: the results file itself
    fs::copy_file(run / "results.h5", base / "results_copy.h5");
  }
  refused({"run", scene, "--restart", (base / "results_copy.h5").string()}, "not a PolyFloe checkpoint");
  // Another scene's bodies.
  refused({"run", kSource + "/dem/scenes/drift_tidal.yaml", "--restart", good.string()},
          "was written for other bodies than the scene builds");
  refused({"run", scene, "--set", "floes.0.thickness=2", "--restart", good.string()}, "was written for other bodies");
  // Output settings changed.
  refused({"run", scene, "--set", "output.interval=0.5", "--restart", good.string()}, "output settings differ");
  // Another contact law: its history is not this one's (never a silent switch).
  refused({"run", scene, "--set", "contact.force_model=foundation", "--restart", good.string()},
          "the interrupted run's contacts followed contact.force_model 'centroid', the scene gives 'foundation'");
  // A folder without checkpoints.
  fs::create_directories(base / "empty");
  refused({"run", scene, "--restart", (base / "empty").string()}, "no checkpoint");
  // The outputs of the run are gone.
  fs::create_directories(base / "elsewhere");
  refused({"run", scene, "--restart", good.string(), "-o", (base / "elsewhere").string()}, "no results.h5");
  EXPECT_TRUE(fs::is_empty(base / "elsewhere"));
  // The schedule's keys are checked like every other.
  refused({"run", scene, "--set", "output.checkpoint.every=-1", "--restart", good.string()}, "output.checkpoint.every");
  refused({"run", scene, "--set", "output.checkpoint.keep=0", "--restart", good.string()}, "output.checkpoint.keep");
  // --restart is an option of run only.
  EXPECT_EQ(run_to_end({"check", scene, "--restart", good.string()}, base / "log"), 2);
  // A run.duration that ends before the checkpoint: the frames past it cannot be taken back.
  refused({"run", scene, "--set", "run.duration=0.5", "--restart", run.string()},
          "run.duration = 0.5 s ends before the checkpoint");
  fs::remove_all(base);
}

// The same scene under another spelling of its path (./, .., a link) is the same scene: the restart says nothing of
// a changed scene, and goes on; its summary counts its own steps and times (a finished run: nothing to run).
TEST(Restart, AnotherSpellingOfTheScenePathIsTheSameSceneAndTheSummaryCountsThisRun) {
  const fs::path base = scratch("spelling");
  fs::remove_all(base);
  fs::create_directories(base);
  const std::string scene = kSource + "/dem/scenes/two_floes.yaml";
  const fs::path run = base / "run";
  ASSERT_EQ(
      run_to_end({"run", scene, "-o", run.string(), "--set", "output.checkpoint.every=1", "--set", "run.duration=0.5"},
                 base / "log"),
      0)
      << slurp(base / "log");
  // A restart of the finished run has nothing to do, and says so (no rate over zero seconds).
  ASSERT_EQ(run_to_end({"run", scene, "--set", "output.checkpoint.every=1", "--set", "run.duration=0.5", "--restart",
                        run.string()},
                       base / "log"),
            0)
      << slurp(base / "log");
  EXPECT_NE(slurp(base / "log").find("Nothing to run: the checkpoint is the run's end (t = 0.5 s)"), std::string::npos)
      << slurp(base / "log");
  EXPECT_EQ(slurp(base / "log").find("steps/s"), std::string::npos) << slurp(base / "log");
  fs::create_symlink(kSource + "/dem/scenes", base / "scenes");
  const std::string other = (base / "scenes" / ".." / "scenes" / "." / "two_floes.yaml").string();
  ASSERT_EQ(run_to_end({"run", other, "--set", "output.checkpoint.every=1", "--set", "run.duration=1", "--restart",
                        run.string()},
                       base / "log"),
            0)
      << slurp(base / "log");
  const std::string log = slurp(base / "log");
  EXPECT_NE(log.find("run.duration"), std::string::npos) << log;                 // the one real change is listed ...
  EXPECT_EQ(log.find("# from:"), std::string::npos) << log;                      // ... the path's spelling is not
  EXPECT_NE(log.find("t = 0.5 -> 1 s simulated in"), std::string::npos) << log;  // this run's part
  fs::remove_all(base);
}

TEST(Restart, UnstableRunLeavesItsStateForInspection) {
  const std::string scene = kSource + "/dem/scenes/two_floes.yaml";
  const fs::path out = scratch("unstable");
  fs::remove_all(out);
  const int code = run_to_end({"run", scene, "-o", out.string(), "--set", "run.dt=0.05"}, out.string() + ".log");
  const std::string log = slurp(out.string() + ".log");
  EXPECT_EQ(code, 3) << log;
  EXPECT_NE(log.find("unstable.h5"), std::string::npos) << log;
  const polyfloe::run::Checkpoint c = polyfloe::run::read_checkpoint(out / "checkpoints" / "unstable.h5");
  EXPECT_EQ(c.kind, "unstable");
  EXPECT_GT(c.world.time, 0.0);
  EXPECT_EQ(c.world.ids.size(), 2u);
  // It is not a restart point.
  const int again =
      run_to_end({"run", scene, "--restart", (out / "checkpoints" / "unstable.h5").string()}, out.string() + ".log");
  EXPECT_EQ(again, 2);
  EXPECT_NE(slurp(out.string() + ".log").find("for inspection"), std::string::npos);
  fs::remove_all(out);
  fs::remove(out.string() + ".log");
}

TEST(Restart, ResultsXmfNamesTheFramesOfTheRestartedRunOnly) {
  // results.xmf's frames are in xdmf/frames_FIRST-LAST.h5, one file per checkpoint. A restart keeps the files that
  // hold only frames it adopted, where their times match results.h5's (here the second file's time is spoiled
  // first, so it and everything after it are rewritten), writes anew those of frames past its checkpoint (a
  // second restart with another step: the same times, other states), and removes the files the new results.xmf
  // does not name.
  const fs::path dir = scratch("xdmf_restart");
  fs::remove_all(dir);
  const std::vector<std::string> args = {"run",   kSource + "/dem/scenes/channel.yaml",
                                         "--set", "run.duration=2",
                                         "--set", "output.interval=0.25",
                                         "--set", "output.checkpoint.every=2",
                                         "--set", "output.checkpoint.keep=10",
                                         "-o",    dir.string()};
  ASSERT_EQ(run_to_end(args, dir.string() + ".log"), 0) << slurp(dir.string() + ".log");
  {
    File f(dir / "xdmf/frames_000002-000003.h5", File::Mode::read_write);
    Dataset t = f.root().open_dataset("time");
    std::vector<double> times = t.read<double>();
    times[0] = -1.0;
    t.write<double>(times);
  }
  auto restart_from = [&](const char* checkpoint, std::vector<std::string> extra) {
    std::vector<std::string> a = args;
    a.insert(a.end(), extra.begin(), extra.end());
    a.insert(a.end(), {"--restart", (dir / "checkpoints" / checkpoint).string()});
    return run_to_end(a, dir.string() + ".log");
  };
  // The folder's xdmf/ files, named by results.xmf, every frame as results.h5 holds it (time and velocity, bit
  // for bit).
  auto expect_frames_of_results = [&](const std::vector<std::string>& expected) {
    std::vector<std::string> on_disk;
    for (const auto& e : fs::directory_iterator(dir / "xdmf")) on_disk.push_back(e.path().filename().string());
    std::sort(on_disk.begin(), on_disk.end());
    EXPECT_EQ(on_disk, expected);
    const std::string xmf = slurp(dir / "results.xmf");
    std::set<std::string> named;
    for (std::size_t at = xmf.find("xdmf/frames_"); at != std::string::npos; at = xmf.find("xdmf/frames_", at + 1))
      named.insert(xmf.substr(at + 5, xmf.find(':', at) - at - 5));
    EXPECT_EQ(named, std::set<std::string>(on_disk.begin(), on_disk.end()));
    const File results(dir / "results.h5", File::Mode::read_only);
    const std::vector<double> times = results.root().open_dataset("time").read<double>();
    const Dataset velocity = results.root().open_dataset("state/velocity");
    std::size_t frames = 0;
    for (const std::string& name : on_disk) {
      const File view(dir / "xdmf" / name, File::Mode::read_only);
      const std::vector<double> t = view.root().open_dataset("time").read<double>();
      const int first = std::stoi(name.substr(7, 6));
      for (std::size_t k = 0; k < t.size(); ++k, ++frames) {
        ASSERT_LT(first + k, times.size());
        EXPECT_EQ(t[k], times[first + k]) << name;
        char group[32];
        std::snprintf(group, sizeof group, "frames/%06zu/velocity", first + k);
        EXPECT_EQ(view.root().open_dataset(group).read<double>(), velocity.read_rows<double>(first + k, 1)) << name;
      }
    }
    EXPECT_EQ(frames, times.size());
  };
  ASSERT_EQ(restart_from("checkpoint_000004.h5", {}), 0) << slurp(dir.string() + ".log");
  expect_frames_of_results(
      {"frames_000000-000001.h5", "frames_000002-000005.h5", "frames_000006-000007.h5", "frames_000008-000008.h5"});
  ASSERT_EQ(restart_from("checkpoint_000006.h5", {"--set", "run.dt=4e-4"}), 0) << slurp(dir.string() + ".log");
  expect_frames_of_results(
      {"frames_000000-000001.h5", "frames_000002-000005.h5", "frames_000006-000007.h5", "frames_000008-000008.h5"});
  fs::remove_all(dir);
}
