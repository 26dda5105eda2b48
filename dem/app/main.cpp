// polyfloe: the command line.
//   polyfloe run SCENE [-o DIR] [--set key.path=value]... [--threads N] [--profile] [--restart CHECKPOINT|DIR]
//   polyfloe check SCENE [--set key.path=value]...
//   polyfloe field import|info|compare ...   (runs polyfloe-field from coupling/, installed beside this program)
//   mpirun -np N polyfloe run SCENE ...      (the planar World cut among MPI ranks: mpi/distributed_run.h)
//   polyfloe --help | --version
// Exit codes: 0 done, 2 bad input, 3 the run became unstable, 1 anything else.
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <filesystem>
#include <iostream>
#include <optional>
#include <sstream>
#include <string>
#include <type_traits>
#include <vector>

#include <CLI/CLI.hpp>

#include "dynamics/parallel.h"
#ifdef POLYFLOE_MPI
#include "mpi/distributed_run.h"
#endif
#include "forcing/field.h"
#include "geometry/polygon.h"
#include "run/output_folder.h"
#include "run/simulation.h"
#include "run/guard.h"
#include "scene/field_statistics.h"
#include "scene/scene_reader.h"

#ifndef POLYFLOE_VERSION
#define POLYFLOE_VERSION "unknown"
#endif

namespace {

using namespace polyfloe;

const char* kUsage = R"(PolyFloe: polyhedral discrete-element simulation of sea-ice floes in wind and currents.

Usage:
  polyfloe run SCENE [options]     run a scene, write VTK (.pvd/.vtp) and HDF5 results
  mpirun -np N polyfloe run SCENE  the same run cut among N MPI ranks (planar scenes, frozen ice too): every
                                   output file bitwise that of one process; one thread per rank unless --threads
  polyfloe check SCENE [options]   validate a scene, print it resolved and the time step it would use
  polyfloe field import CASE -o F  resample an OpenFOAM case's velocity onto a grid: an ocean field file
                                   (also: field info F, field compare CASE F; polyfloe field --help)
  polyfloe --help                  this text
  polyfloe --version               the code version

Options:
  -o, --output DIR        output folder (default: results/<scene name>)
  --set KEY.PATH=VALUE    override a scene value, repeatable, e.g. --set run.duration=60
                          --set forcing.ocean.current=[0.5,0] --set floes.0.position=[10,0]
  --threads N             worker threads of the step (OpenMP; default: the cores, or OMP_NUM_THREADS); the
                          result is bitwise the same for any N
  --profile               print where the step time went (under mpirun: each rank's floes, ghosts and
                          communication)
  --restart CKPT|DIR      continue an interrupted run from a checkpoint file, or from the newest checkpoint of
                          a run's output folder; the result is bitwise that of an uninterrupted run (same scene
                          and --set options). Output goes on in the run's folder (default: the checkpoint's)

Exit codes: 0 done, 2 bad input (scene or arguments), 3 the run became unstable, 1 other failure.
Scene keys are described in docs/scene-reference.md.
)";

struct Args {
  std::string command;
  std::string scene;
  std::filesystem::path output;
  std::vector<std::string> overrides;
  int threads = 0;  // 0 = polyfloe_default_threads()
  bool profile = false;
  std::filesystem::path restart;
};

class UsageError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// The command line on CLI11: the subcommands and their options; a value it cannot take is a UsageError that names
// the option and what it takes.
Args parse_args(int argc, char** argv) {
  Args a;
  if (argc < 2) throw UsageError("no command given");
  a.command = argv[1];
  if (a.command != "run" && a.command != "check") throw UsageError("unknown command '" + a.command + "'");
  auto not_empty = [](const char* what) {
    return CLI::Validator(
        [what](std::string& v) { return v.empty() ? std::string("needs ") + what + ", got ''" : std::string(); }, "");
  };
  const CLI::Validator key_value(
      [](std::string& v) {
        return v.find('=') == std::string::npos || v.front() == '=' ? "expects KEY.PATH=VALUE, got '" + v + "'"
                                                                    : std::string();
      },
      "");
  CLI::App app("PolyFloe", "polyfloe");
  app.set_help_flag();  // --help is answered before the parse (kUsage)
  app.require_subcommand(1, 1);
  CLI::App* cmd = app.add_subcommand(a.command);
  cmd->set_help_flag();
  cmd->add_option("scene", a.scene, "the scene file")->required();
  cmd->add_option("--set", a.overrides, "a scene value")
      ->expected(1)
      ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll)
      ->check(key_value);
  const CLI::Validator thread_count(
      [](std::string& v) {
        char* end = nullptr;
        const long t = std::strtol(v.c_str(), &end, 10);
        return end == v.c_str() || *end != '\0' || t < 1 || t > 1024
                   ? "expects an integer in [1, 1024], got '" + v + "'"
                   : std::string();
      },
      "");
  cmd->add_option("--threads", a.threads, "worker threads")->check(thread_count);
  cmd->add_flag("--profile", a.profile, "print where the step time went");
  std::filesystem::path ignored;
  const CLI::Validator run_only([](std::string&) { return std::string("applies to 'run' only"); }, "");
  const bool run = a.command == "run";
  cmd->add_option("-o,--output", run ? a.output : ignored, "output folder")
      ->check(run ? not_empty("a folder name") : run_only);
  cmd->add_option("--restart", run ? a.restart : ignored, "a checkpoint or a run's folder")
      ->check(run ? not_empty("a checkpoint file or a run's output folder") : run_only);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    throw UsageError(e.what());
  }
  return a;
}

// The lines removed from `was` ("  - ") and added in `now` ("  + "), in order: a longest-common-subsequence diff
// (resolved scenes are a few hundred lines).
std::string changed_lines(const std::string& was, const std::string& now) {
  auto lines = [](const std::string& text) {
    std::vector<std::string> v;
    std::istringstream in(text);
    for (std::string l; std::getline(in, l);) v.push_back(l);
    return v;
  };
  const std::vector<std::string> a = lines(was), b = lines(now);
  const std::size_t n = a.size(), m = b.size();
  // common[i][j]: length of the longest common subsequence of a[i..] and b[j..].
  std::vector<std::vector<int>> common(n + 1, std::vector<int>(m + 1, 0));
  for (std::size_t i = n; i-- > 0;)
    for (std::size_t j = m; j-- > 0;)
      common[i][j] = a[i] == b[j] ? common[i + 1][j + 1] + 1 : std::max(common[i + 1][j], common[i][j + 1]);
  std::ostringstream out;
  std::size_t i = 0, j = 0;
  while (i < n || j < m) {
    if (i < n && j < m && a[i] == b[j]) {
      ++i, ++j;
    } else if (j == m || (i < n && common[i + 1][j] >= common[i][j + 1])) {
      out << "  - " << a[i++] << "\n";
    } else {
      out << "  + " << b[j++] << "\n";
    }
  }
  return out.str();
}

int check(const scene::Scene& sc, const dynamics::World& world, const scene::FieldStatistics& field) {
  const double dt = scene::time_step(sc, world);
  std::cout << scene::resolved_yaml(sc);
  std::size_t dynamic = 0;
  for (std::size_t i = 0; i < world.size(); ++i)
    if (world.motion(static_cast<int>(i)) == dynamics::Motion::dynamic) ++dynamic;
  const double v = scene::reference_speed(sc);
  std::cout << "\n# resolved:\n"
            << "#   bodies: " << world.size() << " (" << dynamic << " dynamic)\n"
            << "#   reference impact speed: " << v << " m/s\n"
            << "#   shortest contact duration at that speed: " << world.shortest_contact_duration(v) << " s\n"
            << "#   time step: " << dt << " s" << (sc.time.dt ? " (fixed by the scene)" : " (automatic)") << "\n"
            << "#   steps: " << static_cast<long long>(std::ceil(sc.time.duration / dt)) << "\n";
  if (sc.floe_field) std::cout << "#   floe field: " << scene::to_string(field) << "\n";
  return run::kExitOk;
}

// Runs `body` (a run and its report; returns the exit code) and turns what it throws into exit codes: 3 for an
// unstable run, 1 for anything else.
template <class F>
int guarded_run(F&& body) {
  try {
    return body();
  } catch (const run::OutputFolderError& e) {  // the folder changed between the check and the run
    std::cerr << "\npolyfloe: error: " << e.what() << "\n";
    return run::kExitBadInput;
  } catch (const run::InstabilityError& e) {
    std::cerr << "\npolyfloe: the run became unstable: " << e.what() << "\n";
    return run::kExitUnstable;
  } catch (const forcing::FieldError& e) {  // ocean or wind, in space or in time: e names the field's source
    std::cerr << "\npolyfloe: a forcing field does not cover the run: " << e.what()
              << "\nThe frames written so far are complete.\n";
    return run::kExitFailure;
  } catch (const std::exception& e) {
    std::cerr << "\npolyfloe: error: " << e.what() << "\n";
    return run::kExitFailure;
  }
}

// The spatial world of a scene: whatever refuses to build it is bad input (a SceneError naming the scene).
dynamics::SpatialWorld build_spatial(const Args& args, const scene::Scene& sc) {
  try {
    return scene::build_spatial_world(sc);
  } catch (const scene::SceneError&) {
    throw;
  } catch (const std::exception& e) {
    throw scene::SceneError(args.scene + ": " + e.what());
  }
}

// `polyfloe check` of a spatial scene (spatial: block): 6-DOF polyhedra.
int check(const scene::Scene& sc, const dynamics::SpatialWorld& world) {
  const double dt = scene::time_step(sc, world);
  std::cout << scene::resolved_yaml(sc);
  const double v = scene::reference_speed(sc);
  std::cout << "\n# resolved:\n"
            << "#   spatial bodies: " << world.size() << "\n"
            << "#   reference impact speed: " << v << " m/s\n"
            << "#   shortest contact duration at that speed: " << world.shortest_contact_duration(v) << " s\n"
            << "#   time step: " << dt << " s" << (sc.time.dt ? " (fixed by the scene)" : " (automatic)") << "\n"
            << "#   steps: " << static_cast<long long>(std::ceil(sc.time.duration / dt)) << "\n";
  return run::kExitOk;
}

// What a finished run prints on stdout.
template <class W>
void report(const scene::Scene& sc, const run::RunSummary& s) {
  constexpr bool planar = std::is_same_v<W, dynamics::World>;
  if (s.steps == 0)
    std::cout << "Nothing to run: the checkpoint is the run's end (t = " << s.simulated << " s).\n";
  else if (s.start_time > 0.0)
    std::cout << "Done: " << s.steps << " steps, t = " << s.start_time << " -> " << s.simulated << " s simulated in "
              << s.wall << " s wall (resumed from the checkpoint).\n";
  else
    std::cout << "Done: " << s.steps << " steps, " << s.simulated << " s simulated in " << s.wall << " s wall.\n";
  if (s.channel_area_passed) {
    std::cout << "Channel: " << *s.channel_area_passed << " m^2 of ice passed the strait entrance; "
              << (s.channel_jam_time ? "jammed from t = " + std::to_string(*s.channel_jam_time) + " s"
                                     : std::string("no jam"))
              << " (results.h5: /diagnostics/channel)\n";
  }
  if constexpr (!planar) {
    if (s.first_contact)
      std::cout << "Contacts: the first at t = " << *s.first_contact << " s; " << s.contact_steps << " of " << s.steps
                << " steps had one.\n";
    else if (s.start_time == 0.0)
      std::cout << "No contact during the run: no two bodies touched (a scene about an impact did not reach it; "
                   "check the bodies' positions, velocities and run.duration).\n";
  }
  std::cout << "Results in " << std::filesystem::absolute(s.output_dir).string() << ":\n";
  if (sc.output.vtk) {
    std::string series = planar ? "floes.pvd" : "bodies.pvd";
    if (sc.output.contacts) series += ", contacts.pvd";
    if (sc.ice_sheet && sc.ice_sheet->bonds) series += ", bonds.pvd";
    if (planar && sc.output.velocity_grid.enabled) series += ", velocity.pvd";
    std::cout << "  " << series << std::string(series.size() < 24 ? 24 - series.size() : 1, ' ')
              << " (open in ParaView)\n";
  }
  if (sc.output.hdf5) std::cout << "  results.h5               (time series; see docs/user-guide.md)\n";
}

// What a run starts from: its options, and a restart's checkpoint with what changed in the scene since.
struct RunStart {
  run::RunOptions opt;
  std::optional<run::Checkpoint> restart;
  std::filesystem::path restart_file;
  std::string scene_changes;  // what differs from the checkpointed run's resolved scene, as a line diff
};

// The options, the restart's checkpoint read and the output folder checked, before any file is touched. Throws
// CheckpointError, OutputFolderError, SceneError (bad input) or std::exception.
RunStart prepare_run(const Args& args, const scene::Scene& sc, int default_threads) {
  RunStart r;
  run::RunOptions& opt = r.opt;
  opt.output_dir = args.output.empty() ? std::filesystem::path("results") / sc.name : args.output;
  opt.threads = args.threads > 0 ? args.threads : default_threads;
  opt.interactive = isatty(fileno(stderr)) != 0;
  opt.profile = args.profile;
  opt.version = POLYFLOE_VERSION;
  if (!args.restart.empty()) {
    r.restart_file = run::find_checkpoint(args.restart);
    r.restart = run::read_checkpoint(r.restart_file);
    if (sc.time.duration < r.restart->time() * (1.0 - 1e-12)) {
      std::ostringstream why;
      why << "run.duration = " << sc.time.duration << " s ends before the checkpoint " << r.restart_file.string()
          << " (t = " << r.restart->time() << " s): a restart goes on from a checkpoint, it cannot take back "
          << "frames already written; for a shorter run, run afresh into another folder (-o DIR)";
      throw scene::SceneError(why.str());
    }
    const std::filesystem::path folder = r.restart_file.parent_path();
    if (args.output.empty() && folder.filename() == "checkpoints") opt.output_dir = folder.parent_path();
    const std::string now = scene::resolved_yaml(sc);
    if (r.restart->scene_resolved != now) r.scene_changes = changed_lines(r.restart->scene_resolved, now);
  }
  opt.output_dir = run::OutputFolder::resolve(opt.output_dir);
  run::OutputFolder::check(opt.output_dir);
  return r;
}

// The exit code of what a run's setup threw, its message on stderr.
int setup_failed(const Args& args, std::exception_ptr failed) {
  try {
    std::rethrow_exception(failed);
  } catch (const run::CheckpointError& e) {
    std::cerr << "polyfloe: error: " << e.what() << "\n";
    return run::kExitBadInput;
  } catch (const run::OutputFolderError& e) {
    std::cerr << "polyfloe: error: " << e.what() << "\n";
    return run::kExitBadInput;
  } catch (const scene::SceneError& e) {  // a setting found unusable once the world exists, before any output
    std::cerr << "polyfloe: error: " << args.scene << ": " << e.what() << "\n";
    return run::kExitBadInput;
  } catch (const std::exception& e) {
    std::cerr << "polyfloe: error: " << e.what() << "\n";
    return run::kExitFailure;
  }
}

// The notes a restart prints before it runs.
void restart_notes(const RunStart& r, double t, std::uint64_t step) {
  if (!r.scene_changes.empty())
    std::cerr << "polyfloe: note: the scene differs from the checkpointed run's; the result will not be that of "
                 "an uninterrupted run of either. Changed lines:\n"
              << r.scene_changes;
  if (!r.restart_file.empty())
    std::cerr << "polyfloe: restarting from " << r.restart_file.string() << " (t = " << t << " s, step " << step
              << ")\n";
}

// The run's first line: the scene, its size and step, the ranks and threads, where the output goes.
void first_line(const scene::Scene& sc, std::size_t bodies, bool planar, double dt, const RunStart& r, int ranks) {
  const int threads = r.opt.threads;
  std::cerr << "polyfloe: " << sc.name << ": " << bodies << (planar ? " bodies, " : " spatial bodies, ")
            << sc.time.duration << " s simulated, dt = " << dt << " s, ";
  if (ranks > 0) std::cerr << ranks << (ranks == 1 ? " MPI rank x " : " MPI ranks x ");
  std::cerr << threads << (threads == 1 ? " thread" : " threads") << (ranks > 0 ? " each" : "") << " -> "
            << r.opt.output_dir.string() << "\n";
}

// `polyfloe run` of a scene whose world (planar or spatial) is built: the options, the restart's checkpoint checked
// against the world and the interrupted run's outputs before any file is touched (a bad checkpoint is bad input),
// then the run.
template <class W>
int run_world(const Args& args, const scene::Scene& sc, W world, const scene::FieldStatistics* field) {
  std::optional<run::BasicSimulation<W>> sim;
  RunStart start;
  try {
    start = prepare_run(args, sc, std::clamp(polyfloe_default_threads(), 1, 1024));
    sim.emplace(sc, std::move(world), start.opt, std::move(start.restart), start.restart_file);
    restart_notes(start, sim->world().time(), sim->world().step_count());
  } catch (...) {
    return setup_failed(args, std::current_exception());
  }

  return guarded_run([&] {
    first_line(sc, sim->world().size(), std::is_same_v<W, dynamics::World>, sim->dt(), start, 0);
    if (field && sc.floe_field && args.restart.empty())
      std::cerr << "polyfloe: floe field: " << scene::to_string(*field) << "\n";
    report<W>(sc, sim->run());
    return run::kExitOk;
  });
}

#ifdef POLYFLOE_MPI
// `polyfloe run` under mpirun: the planar world cut among the ranks (mpi/distributed_run.h); every rank has built
// the same world from the scene, and stops with the same exit code.
int run_distributed(const Args& args, const scene::Scene& sc, dynamics::World world,
                    std::vector<dynamics::BodyDesc> descs, const scene::FieldStatistics& field) {
  MPI_Comm comm = MPI_COMM_WORLD;
  std::optional<mpi::DistributedRun> sim;
  RunStart start;
  // Under mpirun one thread per rank unless asked (--threads, OMP_NUM_THREADS): the ranks take the cores.
  const int threads = std::getenv("OMP_NUM_THREADS") ? std::clamp(polyfloe_default_threads(), 1, 1024) : 1;
  int code = 0;
  try {
    start = prepare_run(args, sc, threads);
  } catch (...) {
    code = setup_failed(args, std::current_exception());
  }
  if ((code = mpi::agree(comm, code)) != 0) return code;
  try {
    sim.emplace(comm, sc, std::move(world), std::move(descs), start.opt, std::move(start.restart), start.restart_file);
    restart_notes(start, sim->start_time(), sim->start_step());
  } catch (const mpi::PeerStopped&) {
    code = 0;
  } catch (...) {
    code = setup_failed(args, std::current_exception());
  }
  if ((code = mpi::agree(comm, code)) != 0) return code;

  code = guarded_run([&] {
    first_line(sc, sim->size(), true, sim->dt(), start, sim->ranks());
    if (sc.floe_field && args.restart.empty()) std::cerr << "polyfloe: floe field: " << scene::to_string(field) << "\n";
    const run::RunSummary s = sim->run();
    if (sim->rank() == 0) report<dynamics::World>(sc, s);
    return run::kExitOk;
  });
  return mpi::agree(comm, code);
}
#endif

}  // namespace

// `polyfloe field ...` is the program polyfloe-field (coupling/: it links VTK's OpenFOAM reader, which the
// simulator itself never needs), run in this process's place, git-style.
int exec_field_tool(int argc, char** argv) {
  std::error_code ec;
  const std::filesystem::path self = std::filesystem::read_symlink("/proc/self/exe", ec);
  const std::filesystem::path tool = (ec ? std::filesystem::path(argv[0]) : self).parent_path() / "polyfloe-field";
  std::vector<char*> args{const_cast<char*>(tool.c_str())};
  for (int i = 2; i < argc; ++i) args.push_back(argv[i]);
  args.push_back(nullptr);
  execv(tool.c_str(), args.data());
  std::cerr << "polyfloe: error: cannot run " << tool.string() << " (" << std::strerror(errno)
            << "); it is built with polyfloe (scripts/build.sh)\n";
  return run::kExitFailure;
}

int main(int argc, char** argv) {
  if (argc >= 2 && std::string(argv[1]) == "field") return exec_field_tool(argc, argv);
#ifdef POLYFLOE_MPI
  mpi::Session mpi(argc, argv);  // (under mpirun: rank 0 alone reports, from the usage on)
#endif
  // --help anywhere (polyfloe run --help) or 'help' as the command: the usage.
  if (argc >= 2 && (std::string(argv[1]) == "help" || std::any_of(argv + 1, argv + argc, [](const char* x) {
                      return std::string(x) == "--help" || std::string(x) == "-h";
                    }))) {
    std::cout << kUsage;
    return run::kExitOk;
  }
  if (argc >= 2 && std::string(argv[1]) == "--version") {
    std::cout << "polyfloe " << POLYFLOE_VERSION << "\n";
    return run::kExitOk;
  }
  Args args;
  try {
    args = parse_args(argc, argv);
  } catch (const UsageError& e) {
    std::cerr << "polyfloe: " << e.what() << "\n\n" << kUsage;
    return run::kExitBadInput;
  }

  // Bad input is found here, before any output is created.
  std::vector<dynamics::BodyDesc> descs;  // under mpirun: the bodies as the world was given them
  scene::Scene sc;
  std::optional<dynamics::World> world;
  std::optional<dynamics::SpatialWorld> spatial;
  scene::FieldStatistics field;
  try {
    sc = scene::read_scene(args.scene, args.overrides);
    if (sc.spatial)
      spatial.emplace(build_spatial(args, sc));
    else
#ifdef POLYFLOE_MPI
      world.emplace(scene::build_world(sc, &field, mpi.active() ? &descs : nullptr));
#else
      world.emplace(scene::build_world(sc, &field));
#endif
    const double dt = spatial ? scene::time_step(sc, *spatial) : scene::time_step(sc, *world);
    if (!(dt > 0.0) || !std::isfinite(dt))
      throw scene::SceneError(args.scene + ": cannot derive a time step (no dynamic body?); set run.dt");
  } catch (const scene::SceneError& e) {
    std::cerr << "polyfloe: error: " << e.what() << "\n";
    return run::kExitBadInput;
  } catch (const geometry::GeometryError& e) {
    std::cerr << "polyfloe: error: " << args.scene << ": " << e.what() << "\n";
    return run::kExitBadInput;
  } catch (const std::invalid_argument& e) {
    std::cerr << "polyfloe: error: " << args.scene << ": " << e.what() << "\n";
    return run::kExitBadInput;
  } catch (const std::exception& e) {
    std::cerr << "polyfloe: error: " << e.what() << "\n";
    return run::kExitFailure;
  }
#ifdef POLYFLOE_MPI
  if (mpi.active() && args.command == "run") {
    if (spatial) {
      std::cerr << "polyfloe: error: " << args.scene
                << ": a spatial scene (spatial:) does not run across MPI ranks: run it in one process (without "
                   "mpirun), with --threads N for the cores\n";
      return run::kExitBadInput;
    }
    return run_distributed(args, sc, std::move(*world), std::move(descs), field);
  }
#endif
  if (spatial) return args.command == "check" ? check(sc, *spatial) : run_world(args, sc, std::move(*spatial), nullptr);
  return args.command == "check" ? check(sc, *world, field) : run_world(args, sc, std::move(*world), &field);
}
