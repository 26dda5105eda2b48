// The polyfloe command line: help, version, exit codes 0/2/3, messages that name file, line and key, and no
// output folder left behind by bad input.
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>
#include <string>
#include <thread>

#include "scratch_dir.h"
#include "cli_support.h"
#include "text_file.h"

namespace fs = std::filesystem;

namespace {

std::string slurp_file(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

using Result = polyfloe::tsupport::CommandResult;
using polyfloe::tsupport::run_polyfloe;

fs::path write_scene(const std::string& name, const std::string& text) {
  // One folder per test process, removed when the process ends.
  static const struct SceneDir {
    fs::path path = polyfloe::tsupport::scratch_dir("polyfloe_cli_scenes");
    SceneDir() { fs::create_directories(path); }
    ~SceneDir() {
      std::error_code ec;
      fs::remove_all(path, ec);
    }
  } dir;
  const fs::path p = dir.path / name;
  std::ofstream(p) << text;
  return p;
}

const std::string kScene = std::string(POLYFLOE_SOURCE_DIR) + "/dem/scenes/two_floes.yaml";

}  // namespace

TEST(Cli, HelpShowsTheUsageAndVersionNamesTheProgramBothExitingZero) {
  Result r = run_polyfloe("--help");
  EXPECT_EQ(r.code, 0);
  EXPECT_NE(r.output.find("polyfloe run SCENE"), std::string::npos);
  r = run_polyfloe("--version");
  EXPECT_EQ(r.code, 0);
  EXPECT_EQ(r.output.rfind("polyfloe ", 0), 0u);
}

TEST(Cli, UsageErrorsExitTwo) {
  EXPECT_EQ(run_polyfloe("").code, 2);
  EXPECT_EQ(run_polyfloe("fly " + kScene).code, 2);
  EXPECT_EQ(run_polyfloe("run").code, 2);
  EXPECT_EQ(run_polyfloe("run " + kScene + " --threads 0").code, 2);
  EXPECT_EQ(run_polyfloe("run " + kScene + " --set novalue").code, 2);
  EXPECT_EQ(run_polyfloe("run " + kScene + " --bogus").code, 2);
}

TEST(Cli, CheckPrintsTheTimeStep) {
  const Result r = run_polyfloe("check " + kScene);
  EXPECT_EQ(r.code, 0) << r.output;
  EXPECT_NE(r.output.find("time step:"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("bodies: 2"), std::string::npos) << r.output;
}

TEST(Cli, BadSceneNamesLineAndKeyAndWritesNothing) {
  const fs::path scene = write_scene("polyfloe_bad_scene.yaml",
                                     "run:\n  duration: 10\ncontact:\n  restitution: 1.5\nfloes:\n"
                                     "  - regular: {sides: 6, radius: 5}\n");
  const fs::path out = polyfloe::tsupport::scratch_dir("polyfloe_bad_scene_out");
  fs::remove_all(out);
  const Result r = run_polyfloe("run " + scene.string() + " -o " + out.string());
  EXPECT_EQ(r.code, 2) << r.output;
  EXPECT_NE(r.output.find("polyfloe_bad_scene.yaml:4:"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("contact.restitution"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(out));
  // A misspelt key from the command line.
  const Result s = run_polyfloe("run " + kScene + " -o " + out.string() + " --set contact.restitutio=0.5");
  EXPECT_EQ(s.code, 2);
  EXPECT_NE(s.output.find("--set contact.restitutio"), std::string::npos) << s.output;
  EXPECT_FALSE(fs::exists(out));
  // A missing file.
  const Result m = run_polyfloe("run /nonexistent/scene.yaml -o " + out.string());
  EXPECT_EQ(m.code, 2);
  EXPECT_NE(m.output.find("/nonexistent/scene.yaml"), std::string::npos) << m.output;
  EXPECT_FALSE(fs::exists(out));
}

TEST(Cli, ARunWritesFloesContactsResultsAndTheResolvedScene) {
  const fs::path out = polyfloe::tsupport::scratch_dir("polyfloe_cli_run");
  fs::remove_all(out);
  const Result r = run_polyfloe("run " + kScene + " -o " + out.string() + " --set run.duration=1.5");
  EXPECT_EQ(r.code, 0) << r.output;
  for (const char* f : {"floes.pvd", "contacts.pvd", "results.h5", "scene.resolved.yaml"})
    EXPECT_TRUE(fs::exists(out / f)) << f;
  fs::remove_all(out);
}

// A spatial scene runs through its own driver: the cube-plate impact, its outputs, and Eq. 6-7 at the end (the
// cube is clear of the plate after 0.1 s; tolerance 1 % of v0 as tests/validation/test_cube_plate.cpp).
TEST(Cli, CubePlateSceneRunsAndMatchesEquations6And7) {
  const fs::path out = polyfloe::tsupport::scratch_dir("polyfloe_cli_cube_plate");
  fs::remove_all(out);
  const std::string scene = std::string(POLYFLOE_SOURCE_DIR) + "/dem/scenes/cube_plate.yaml";
  const Result r = run_polyfloe("run " + scene + " -o " + out.string());
  ASSERT_EQ(r.code, 0) << r.output;
  for (const char* f : {"bodies.pvd", "contacts.pvd", "results.h5", "scene.resolved.yaml"})
    EXPECT_TRUE(fs::exists(out / f)) << f;
  const std::string py = "/usr/bin/python3 -c \"import h5py, math; f = h5py.File('" + (out / "results.h5").string() +
                         "', 'r'); v = f['state/velocity'][-1, 1, 2]; w = f['state/angular_velocity'][-1, 1, 1]; "
                         "print('%.6f %.6f' % (-v, abs(w) * math.sqrt(2)))\"";
  FILE* p = popen(py.c_str(), "r");
  ASSERT_NE(p, nullptr);
  double v = 0.0, w = 0.0;
  ASSERT_EQ(std::fscanf(p, "%lf %lf", &v, &w), 2);
  pclose(p);
  // Eq. 6-7 at alpha = 15 deg, e = 0.5: v'/v0 = 1/7, w' r / v0 = 9/7
  EXPECT_NEAR(v, 1.0 / 7.0, 0.01);
  EXPECT_NEAR(w, 9.0 / 7.0, 0.01);
  // The summary says when the impact came; the last frame is the end state (t = run.duration exactly, the last
  // step shortened as in planar runs), the frames before it at each multiple of 2 ms exactly.
  EXPECT_NE(r.output.find("Contacts: the first at t = 0.00"), std::string::npos) << r.output;
  std::ifstream pvd(out / "bodies.pvd");
  const std::string series((std::istreambuf_iterator<char>(pvd)), std::istreambuf_iterator<char>());
  EXPECT_NE(series.find("timestep=\"0.1\" group=\"\" part=\"0\" file=\"bodies/bodies_000050.vtp\""), std::string::npos)
      << series;
  EXPECT_EQ(series.find("bodies_000051"), std::string::npos) << series;
  EXPECT_NE(series.find("timestep=\"0.002\" group=\"\" part=\"0\" file=\"bodies/bodies_000001.vtp\""),
            std::string::npos)
      << series;
  EXPECT_NE(series.find("timestep=\"0.098\" group=\"\" part=\"0\" file=\"bodies/bodies_000049.vtp\""),
            std::string::npos)
      << series;
  // bodies.pvd carries `speed` as floes.pvd does: |velocity| of the body on each of its faces.
  const std::string vtp = "/usr/bin/python3 -c \"import vtk, math; r = vtk.vtkXMLPolyDataReader(); r.SetFileName('" +
                          (out / "bodies" / "bodies_000050.vtp").string() +
                          "'); r.Update(); d = r.GetOutput().GetCellData(); s = d.GetArray('speed'); "
                          "v = d.GetArray('velocity'); print('%.12g %.12g' % (s.GetValue(0), "
                          "math.sqrt(sum(x * x for x in v.GetTuple3(0)))))\"";
  FILE* q = popen(vtp.c_str(), "r");
  ASSERT_NE(q, nullptr);
  double speed = -1.0, norm = -2.0;
  EXPECT_EQ(std::fscanf(q, "%lf %lf", &speed, &norm), 2);
  pclose(q);
  EXPECT_NEAR(speed, norm, 1e-12);
  // The cube lifted clear of the plate: no impact, and the summary says so instead of a silent exit 0.
  const Result none = run_polyfloe("run " + scene + " -o " + out.string() + " --set spatial.bodies.1.position=[0,0,5]");
  ASSERT_EQ(none.code, 0) << none.output;
  EXPECT_NE(none.output.find("No contact during the run"), std::string::npos) << none.output;
  fs::remove_all(out);
}

// plot_frames refuses a time the run has no frame at (it used to show the nearest frame under the asked time).
TEST(Cli, PlotFramesRefusesATimeTheRunDidNotReach) {
  const fs::path out = polyfloe::tsupport::scratch_dir("polyfloe_cli_plot_frames");
  fs::remove_all(out);
  ASSERT_EQ(run_polyfloe("run " + kScene + " -o " + out.string() + " --set run.duration=0.2").code, 0);
  const std::string plot = "/usr/bin/python3 " + std::string(POLYFLOE_SOURCE_DIR) + "/postprocess/plot_frames.py " +
                           (out / "results.h5").string() + " -t 0 ";
  const std::string log = (out / "plot.log").string();
  EXPECT_EQ(std::system((plot + "0.2 -o " + (out / "ok.png").string() + " > " + log + " 2>&1").c_str()), 0)
      << slurp_file(log);
  EXPECT_NE(std::system((plot + "150 -o " + (out / "no.png").string() + " > " + log + " 2>&1").c_str()), 0);
  EXPECT_NE(slurp_file(log).find("has no frame at t = 150 s: its frames span 0 to 0.2 s"), std::string::npos)
      << slurp_file(log);
  EXPECT_FALSE(fs::exists(out / "no.png"));
  fs::remove_all(out);
}

TEST(Cli, SpatialUnresolvedContactStopsWithExitThree) {
  const fs::path out = polyfloe::tsupport::scratch_dir("polyfloe_cli_cube_plate_unstable");
  const std::string scene = std::string(POLYFLOE_SOURCE_DIR) + "/dem/scenes/cube_plate.yaml";
  const Result r = run_polyfloe("run " + scene + " -o " + out.string() + " --set run.dt=0.005");
  EXPECT_EQ(r.code, 3) << r.output;
  // The same guard and words as a planar run's: the pair, its impact speed and the step to use.
  EXPECT_NE(r.output.find("the contact between bodies 0 and 1 at t = 0.005 s"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("Set run.reference_speed to"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("or run.dt to"), std::string::npos) << r.output;
  fs::remove_all(out);
}

TEST(Cli, UnresolvedContactStopsWithExitThree) {
  // A 0.05 s step cannot resolve a ~0.03 s Hertz impact: the guard must stop the run, name the bodies and say
  // what to change, instead of letting the floes fly apart at ten times their impact speed.
  const fs::path out = polyfloe::tsupport::scratch_dir("polyfloe_cli_unstable");
  const Result r = run_polyfloe("run " + kScene + " -o " + out.string() + " --set run.dt=0.05");
  EXPECT_EQ(r.code, 3) << r.output;
  EXPECT_NE(r.output.find("bodies 0 and 1"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("run.dt"), std::string::npos) << r.output;
  fs::remove_all(out);
}

TEST(Cli, KinematicBodiesDoNotTripTheSpeedGuard) {
  // A long plate spinning at 0.6 rad/s: its tip moves at 60 m/s, as the scene prescribes; that is not instability.
  const fs::path scene = write_scene("polyfloe_kinematic.yaml",
                                     "run: {duration: 1, dt: 0.001}\n"
                                     "forcing: {ocean: {skin_drag: {enabled: false}}, air: {drag: {enabled: false}}}\n"
                                     "floes:\n"
                                     "  - regular: {sides: 6, radius: 5}\n"
                                     "    position: [0, 50]\n"
                                     "  - rectangle: {width: 200, height: 2}\n"
                                     "    motion: kinematic\n"
                                     "    angular_velocity: 0.6\n");
  const fs::path out = polyfloe::tsupport::scratch_dir("polyfloe_cli_kinematic");
  const Result r = run_polyfloe("run " + scene.string() + " -o " + out.string());
  EXPECT_EQ(r.code, 0) << r.output;
  fs::remove_all(out);
}

TEST(Cli, OverflowingDragStopsWithExitThree) {
  // dt = 100 s makes the explicit quadratic drag overshoot and grow without bound within a few steps (the default
  // semi-implicit treatment is stable there: tests/validation/test_drift.cpp).
  const fs::path out = polyfloe::tsupport::scratch_dir("polyfloe_cli_overflow");
  const Result r = run_polyfloe("run " + kScene + " -o " + out.string() +
                                " --set run.dt=100 --set run.duration=3000 --set forcing.ocean.skin_drag.enabled=true"
                                " --set forcing.treatment=explicit"
                                " --set floes.0.velocity=[10,0] --set floes.0.position=[-1000,0]");
  EXPECT_EQ(r.code, 3) << r.output;
  fs::remove_all(out);
  // Without checkpoints too, the stopped run leaves results.xmf describing the frames results.h5 holds (t = 0).
  const Result again =
      run_polyfloe("run " + kScene + " -o " + out.string() +
                   " --set run.dt=100 --set run.duration=3000 --set forcing.ocean.skin_drag.enabled=true"
                   " --set forcing.treatment=explicit --set output.checkpoint.every=0"
                   " --set floes.0.velocity=[10,0] --set floes.0.position=[-1000,0]");
  EXPECT_EQ(again.code, 3) << again.output;
  const std::string xmf = polyfloe::tsupport::slurp(out / "results.xmf");
  EXPECT_NE(xmf.find("<Time Value=\"0\"/>"), std::string::npos) << xmf;
  EXPECT_EQ(xmf.find("frame 1"), std::string::npos) << xmf;
  fs::remove_all(out);
}

// An output interval shorter than the step writes a frame at every step (the old schedule), says so, and finishes:
// 1e-300 s neither hangs nor shrinks the step.
TEST(Cli, OutputIntervalShorterThanTheStepWritesEveryStep) {
  const fs::path out = polyfloe::tsupport::scratch_dir("polyfloe_cli_tiny_interval");
  fs::remove_all(out);
  Result r =
      run_polyfloe("run " + kScene + " -o " + out.string() + " --set output.interval=1e-300 --set run.duration=0.01");
  EXPECT_EQ(r.code, 0) << r.output;
  EXPECT_NE(r.output.find("note: output.interval 1e-300 s is shorter than the step"), std::string::npos) << r.output;
  r = run_polyfloe("run " + kScene + " -o " + out.string() +
                   " --set run.dt=1e-3 --set output.interval=5e-4 --set run.duration=0.01");
  EXPECT_EQ(r.code, 0) << r.output;
  EXPECT_NE(r.output.find("10 steps"), std::string::npos) << r.output;
  EXPECT_TRUE(fs::exists(out / "floes" / "floes_000010.vtp"));
  EXPECT_FALSE(fs::exists(out / "floes" / "floes_000011.vtp"));
  // An interval of exactly one step: a frame every step, no note.
  r = run_polyfloe("run " + kScene + " -o " + out.string() +
                   " --set run.dt=1e-3 --set output.interval=1e-3 --set run.duration=0.01");
  EXPECT_EQ(r.code, 0) << r.output;
  EXPECT_EQ(r.output.find("note: output.interval"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("10 steps"), std::string::npos) << r.output;
  EXPECT_TRUE(fs::exists(out / "floes" / "floes_000010.vtp"));
  fs::remove_all(out);
}

// Frames at the exact multiples of the interval (the step before each shortened to land on it) and at the end,
// whatever the step: the .pvd's times are k * interval, written exactly.
TEST(Cli, FramesLandOnMultiplesOfTheInterval) {
  const fs::path out = polyfloe::tsupport::scratch_dir("polyfloe_cli_frame_times");
  fs::remove_all(out);
  const Result r = run_polyfloe("run " + kScene + " -o " + out.string() +
                                " --set run.dt=0.0013 --set output.interval=0.01 --set run.duration=0.035");
  ASSERT_EQ(r.code, 0) << r.output;
  const std::string pvd = polyfloe::tsupport::slurp(out / "floes.pvd");
  for (const char* t :
       {"timestep=\"0\"", "timestep=\"0.01\"", "timestep=\"0.02\"", "timestep=\"0.03\"", "timestep=\"0.035\""}) {
    EXPECT_NE(pvd.find(t), std::string::npos) << t << " not in\n" << pvd;
  }
  EXPECT_EQ(pvd.find("timestep=\"0.0104"), std::string::npos) << pvd;
  // 0.035 s in steps of 0.0013 s, 8 per interval (the 8th shortened to land on it) and 4 to the end: 28 steps.
  EXPECT_NE(r.output.find("28 steps"), std::string::npos) << r.output;
  fs::remove_all(out);
}

// The output folder contract (docs/user-guide.md, "The output folder"): a rerun removes what the previous run's
// manifest lists and nothing else, however alike the names; a folder of unlisted results is refused, untouched.
TEST(Cli, RerunRemovesOnlyWhatThePreviousRunListed) {
  const fs::path out = polyfloe::tsupport::scratch_dir("polyfloe_cli_keep");
  fs::remove_all(out);
  Result r = run_polyfloe("run " + kScene + " -o " + out.string() +
                          " --set run.duration=0.4 --set output.interval=0.1 --set output.checkpoint.every=1");
  ASSERT_EQ(r.code, 0) << r.output;
  ASSERT_TRUE(fs::exists(out / "floes" / "floes_000004.vtp"));
  ASSERT_TRUE(fs::exists(out / ".polyfloe-manifest"));
  // The user's own files, named like the program's.
  std::ofstream(out / "floes" / "notes.txt") << "mine";
  std::ofstream(out / "floes" / "floes_12.vtp") << "mine";
  std::ofstream(out / "floes" / "floes_000099.vtp") << "mine";
  std::ofstream(out / "checkpoints" / "checkpoint_best.h5") << "mine";
  std::ofstream(out / "checkpoints" / ".checkpoint_000004.h5.tmp.1.2") << "left by a killed writer";
  std::ofstream(out / "results.csv") << "mine";
  r = run_polyfloe("run " + kScene + " -o " + out.string() + " --set run.duration=0.2 --set output.interval=0.1");
  ASSERT_EQ(r.code, 0) << r.output;
  for (const char* mine : {"floes/notes.txt", "floes/floes_12.vtp", "floes/floes_000099.vtp",
                           "checkpoints/checkpoint_best.h5", "results.csv"})
    EXPECT_TRUE(fs::exists(out / mine)) << mine << " was removed";
  EXPECT_TRUE(fs::exists(out / "floes" / "floes_000002.vtp"));
  EXPECT_FALSE(fs::exists(out / "floes" / "floes_000003.vtp")) << "a frame of the previous run stayed";
  EXPECT_FALSE(fs::exists(out / "checkpoints" / "checkpoint_000004.h5")) << "a checkpoint of the previous run stayed";
  EXPECT_FALSE(fs::exists(out / "checkpoints" / ".checkpoint_000004.h5.tmp.1.2"));
  // A run without VTK output leaves floes/ (your files are in it), still the program's: a later run writes there.
  r = run_polyfloe("run " + kScene + " -o " + out.string() + " --set run.duration=0.1 --set output.vtk=false");
  ASSERT_EQ(r.code, 0) << r.output;
  r = run_polyfloe("run " + kScene + " -o " + out.string() + " --set run.duration=0.1");
  ASSERT_EQ(r.code, 0) << r.output;
  EXPECT_TRUE(fs::exists(out / "floes" / "notes.txt"));
  fs::remove_all(out);

  // Results polyfloe did not list (another program's, or a version before the manifest): refused, untouched.
  fs::create_directories(out / "floes");
  std::ofstream(out / "results.h5") << "not ours";
  r = run_polyfloe("run " + kScene + " -o " + out.string() + " --set run.duration=0.2");
  EXPECT_EQ(r.code, 2) << r.output;
  EXPECT_NE(r.output.find("exists but no polyfloe run into this folder wrote it"), std::string::npos) << r.output;
  EXPECT_EQ(slurp_file(out / "results.h5"), "not ours");
  EXPECT_FALSE(fs::exists(out / ".polyfloe-lock"));
  EXPECT_FALSE(fs::exists(out / ".polyfloe-manifest"));
  fs::remove_all(out);
}

// An empty output name is refused (it used to mean the default folder).
TEST(Cli, EmptyOutputNameIsRefused) {
  const Result r = run_polyfloe("run " + kScene + " -o ''");
  EXPECT_EQ(r.code, 2) << r.output;
  EXPECT_NE(r.output.find("--output: needs a folder name"), std::string::npos) << r.output;
}

// A scene file named "...yaml" without a name: the default name is "scene", never ".." (which made the default
// folder results/.. = the current folder, where the run replaced the user's results.h5).
TEST(Cli, ADotNamedSceneFileWritesBelowResults) {
  const fs::path dir = polyfloe::tsupport::scratch_dir("polyfloe_cli_dots");
  fs::remove_all(dir);
  fs::create_directories(dir);
  std::ofstream(dir / "...yaml") << "run: {duration: 0.1}\nfloes:\n  - rectangle: {width: 10, height: 10}\n";
  std::ofstream(dir / "results.h5") << "the user's";
  const std::string cmd = "cd " + dir.string() + " && " + POLYFLOE_BINARY + " run ...yaml > log 2>&1";
  EXPECT_EQ(std::system(cmd.c_str()), 0) << slurp_file(dir / "log");
  EXPECT_EQ(slurp_file(dir / "results.h5"), "the user's");
  EXPECT_TRUE(fs::exists(dir / "results" / "scene" / "results.h5"));
  fs::remove_all(dir);
}

// One run at a time per folder: a second run into a folder a run holds is refused, naming the first's process.
TEST(Cli, SecondRunIntoABusyFolderIsRefused) {
  const fs::path out = polyfloe::tsupport::scratch_dir("polyfloe_cli_busy");
  fs::remove_all(out);
  const std::string first = "exec " + std::string(POLYFLOE_BINARY) + " run " + kScene + " -o " + out.string() +
                            " --set run.duration=1e6 --set output.interval=1e5 > /dev/null 2>&1";
  FILE* pipe = popen(("sh -c '" + first + "' & echo $!").c_str(), "r");
  ASSERT_NE(pipe, nullptr);
  long pid = 0;
  ASSERT_EQ(std::fscanf(pipe, "%ld", &pid), 1);
  pclose(pipe);
  for (int i = 0; i < 200 && !fs::exists(out / "floes.pvd"); ++i)
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  const Result r = run_polyfloe("run " + kScene + " -o " + out.string() + " --set run.duration=0.2");
  kill(static_cast<pid_t>(pid), SIGKILL);
  EXPECT_EQ(r.code, 2) << r.output;
  EXPECT_NE(r.output.find("(process " + std::to_string(pid) + ") is writing into it"), std::string::npos) << r.output;
  EXPECT_TRUE(fs::exists(out / "floes" / "floes_000000.vtp")) << "the second run removed the first's files";
  // Once the first is gone (killed: the kernel releases its lock), the folder is free again.
  for (int i = 0; i < 100 && kill(static_cast<pid_t>(pid), 0) == 0; ++i)
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  const Result again = run_polyfloe("run " + kScene + " -o " + out.string() + " --set run.duration=0.2");
  EXPECT_EQ(again.code, 0) << again.output;
  fs::remove_all(out);
}

TEST(Cli, FieldDrivenFreeDriftRunsAtLargeSteps) {
  // Two days of tidal drift with wind and Coriolis at 30 s steps (semi-implicit drag and Coriolis).
  const std::string scene = std::string(POLYFLOE_SOURCE_DIR) + "/dem/scenes/drift_tidal.yaml";
  const fs::path out = polyfloe::tsupport::scratch_dir("polyfloe_cli_tidal");
  Result r = run_polyfloe("run " + scene + " -o " + out.string());
  EXPECT_EQ(r.code, 0) << r.output;
  std::ifstream resolved(out / "scene.resolved.yaml");
  const std::string text((std::istreambuf_iterator<char>(resolved)), std::istreambuf_iterator<char>());
  EXPECT_NE(text.find("field: {type: tidal, velocity: [0.05, 0], amplitude: [0.25, 0.1], period: 44712, phase: 0}"),
            std::string::npos)
      << text;
  EXPECT_NE(text.find("coriolis: {enabled: true, latitude: 75"), std::string::npos) << text;
  // Steered into each other, two floes meet within a few steps: the contact cannot be resolved at 30 s steps, and
  // the run stops (exit 3) saying which bodies and what step would do.
  r = run_polyfloe("run " + scene + " -o " + out.string() +
                   " --set floes.1.position=[200,0] --set floes.1.velocity=[-1,0]");
  EXPECT_EQ(r.code, 3) << r.output;
  EXPECT_NE(r.output.find("the contact between bodies 0 and 1"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("or run.dt to"), std::string::npos) << r.output;
  fs::remove_all(out);
}

TEST(Cli, TheDriftVortexSceneRunsAndWritesFloeFrames) {
  const std::string scene = std::string(POLYFLOE_SOURCE_DIR) + "/dem/scenes/drift_vortex.yaml";
  const fs::path out = polyfloe::tsupport::scratch_dir("polyfloe_cli_vortex");
  const Result r =
      run_polyfloe("run " + scene + " -o " + out.string() + " --set run.duration=0.5 --set output.interval=0.25");
  EXPECT_EQ(r.code, 0) << r.output;
  EXPECT_TRUE(fs::exists(out / "floes.pvd"));
  fs::remove_all(out);
}

TEST(Cli, VelocityGridTooLargeIsRefusedBeforeAnyOutput) {
  // The automatic grid spans every body: 1 m cells over the channel's 2.2 km x 1.1 km are too many.
  const std::string scene = std::string(POLYFLOE_SOURCE_DIR) + "/dem/scenes/channel.yaml";
  const fs::path out = polyfloe::tsupport::scratch_dir("polyfloe_cli_grid");
  fs::remove_all(out);
  const Result r = run_polyfloe("run " + scene + " -o " + out.string() + " --set output.velocity_grid.cell=0.5");
  EXPECT_EQ(r.code, 2) << r.output;
  EXPECT_NE(r.output.find("output.velocity_grid.cell: the bodies span"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("raise output.velocity_grid.cell"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(out));
  // A grid that fits runs and lists its series.
  const Result ok = run_polyfloe("run " + scene + " -o " + out.string() +
                                 " --set run.duration=0.01 --set output.interval=0.005 --set output.contacts=false");
  EXPECT_EQ(ok.code, 0) << ok.output;
  EXPECT_NE(ok.output.find("floes.pvd, velocity.pvd"), std::string::npos) << ok.output;
  EXPECT_TRUE(fs::exists(out / "velocity" / "velocity_000002.vti"));
  fs::remove_all(out);
}

TEST(Cli, ChannelGeometryFigureFromARun) {
  const std::string src = POLYFLOE_SOURCE_DIR;
  const fs::path out = polyfloe::tsupport::scratch_dir("polyfloe_cli_geometry");
  fs::remove_all(out);
  const Result r = run_polyfloe("run " + src + "/dem/scenes/channel.yaml -o " + out.string() +
                                " --set run.duration=0.001 --set output.vtk=false");
  ASSERT_EQ(r.code, 0) << r.output;
  const std::string plot = "/usr/bin/python3 " + src + "/postprocess/plot_channel_geometry.py " + out.string() +
                           " -o " + (out / "geometry.png").string() + " > /dev/null 2>&1";
  EXPECT_EQ(std::system(plot.c_str()), 0);
  EXPECT_GT(fs::file_size(out / "geometry.png"), 10000u);
  // A run without a channel has nothing to draw: a clear refusal.
  const Result two = run_polyfloe("run " + kScene + " -o " + (out / "two").string() + " --set run.duration=0.01");
  ASSERT_EQ(two.code, 0) << two.output;
  const std::string none = "/usr/bin/python3 " + src + "/postprocess/plot_channel_geometry.py " +
                           (out / "two").string() + " -o " + (out / "none.png").string() + " > /dev/null 2>&1";
  EXPECT_NE(std::system(none.c_str()), 0);
  EXPECT_FALSE(fs::exists(out / "none.png"));
  fs::remove_all(out);
}
