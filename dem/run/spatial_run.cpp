#include "run/spatial_run.h"

#include "scene/scene_reader.h"

#include <chrono>
#include <cstdio>
#include <cmath>
#include <filesystem>
#include <optional>
#include <sstream>

#include "formats/atomic_file.h"
#include "io/spatial_hdf5_writer.h"
#include "io/vtk_writer.h"
#include "run/output_folder.h"

namespace polyfloe::run {

void check_stability(const dynamics::SpatialWorld& w, double dt) {
  for (int i = 0; i < static_cast<int>(w.size()); ++i) {
    if (!w.position(i).allFinite() || !w.velocity(i).allFinite() || !w.angular_velocity(i).allFinite()) {
      std::ostringstream m;
      m << "body " << w.id(i) << " has a non-finite position or velocity at t = " << w.time() << " s (dt = " << dt
        << " s); lower run.dt or raise run.steps_per_contact";
      throw InstabilityError(m.str());
    }
  }
  for (const auto& c : w.contacts()) {
    if (c.duration < dynamics::kMinStepsPerContact * dt) {
      std::ostringstream m;
      m << "the contact of bodies " << w.id(c.a) << " and " << w.id(c.b) << " at t = " << w.time() << " s lasts about "
        << c.duration << " s, fewer than " << dynamics::kMinStepsPerContact << " steps of dt = " << dt
        << " s: lower run.dt to " << c.duration / 40.0
        << " s or less, or raise run.reference_speed (the automatic step divides the contact duration at that speed)";
      throw InstabilityError(m.str());
    }
    const double r = std::min(w.shape(c.a).equivalent_radius(), w.shape(c.b).equivalent_radius());
    if (c.depth > 0.25 * r) {
      std::ostringstream m;
      m << "bodies " << w.id(c.a) << " and " << w.id(c.b) << " overlap by " << c.depth << " m at t = " << w.time()
        << " s, more than a quarter of the smaller body's radius (" << r << " m): the step dt = " << dt
        << " s does not resolve the contact; try run.dt = " << dt / 4 << " s or a larger run.steps_per_contact"
        << " (or a larger run.reference_speed when bodies speed up under gravity)";
      throw InstabilityError(m.str());
    }
  }
}

RunSummary run_spatial(const scene::Scene& scene, dynamics::SpatialWorld& world, const RunOptions& options) {
  namespace fs = std::filesystem;
  RunSummary summary;
  summary.dt = scene::time_step(scene, world);
  OutputFolder folder(options.output_dir, OutputFolder::Mode::fresh);  // the contract of run/output_folder.h
  const fs::path& out = folder.path();
  summary.output_dir = out;
  folder.manifest().record("scene.resolved.yaml");
  io::write_file_atomic(out / "scene.resolved.yaml", scene::resolved_yaml(scene));
  std::optional<io::SpatialVtkSeriesWriter> vtk;
  if (scene.output.vtk) vtk.emplace(out, scene.output.contacts, &folder.manifest());
  std::optional<io::SpatialHdf5Writer> h5;
  if (scene.output.hdf5) {
    io::RunInfo info;
    info.scene_path = scene.source_path;
    info.scene_text = scene.source_text;
    info.version = options.version;
    for (const auto& o : scene.overrides) info.overrides += (info.overrides.empty() ? "" : "\n") + o;
    info.dt = summary.dt;
    folder.manifest().record("results.h5");
    h5.emplace(out / "results.h5", world, info);
  }
  auto frame = [&] {
    if (vtk) vtk->write_frame(world);
    if (h5) h5->write_frame(world);
    ++summary.frames;
  };
  const auto start = std::chrono::steady_clock::now();
  const double dt = summary.dt;
  world.compute_forces(dt);
  frame();
  // The planar driver's schedule (FrameClock): steps of dt landing on every frame time and on the end time.
  FrameClock schedule = FrameClock::make(scene.output.interval, scene.time.duration, dt);
  if (schedule.every_step) std::fprintf(stderr, "%s\n", schedule.note(dt).c_str());
  while (!schedule.at_end(world.time())) {
    world.step(schedule.step(world.time(), dt));
    check_stability(world, dt);
    if (!world.contacts().empty()) {
      if (!summary.first_contact) summary.first_contact = world.time();
      ++summary.contact_steps;
    }
    if (schedule.frame_due(world.time())) {
      schedule.frame_written(world.time());
      frame();
    }
  }
  summary.steps = world.step_count();  // spatial runs always start at t = 0
  summary.simulated = world.time();
  summary.wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return summary;
}

}  // namespace polyfloe::run
