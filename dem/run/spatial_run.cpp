#include "run/spatial_run.h"

#include "scene/scene_reader.h"

#include <chrono>
#include <cmath>
#include <filesystem>
#include <optional>
#include <sstream>

#include "io/atomic_file.h"
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
      m << "the contact of bodies " << w.id(c.a) << " and " << w.id(c.b) << " at t = " << w.time()
        << " s lasts about " << c.duration << " s, fewer than " << dynamics::kMinStepsPerContact
        << " steps of dt = " << dt << " s: lower run.dt to " << c.duration / 40.0
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
  // The planar driver's schedule: steps of dt, the last one shortened to land on the end time; a frame at the
  // first step at or after each multiple of the output interval, and at the end.
  const double t_end = scene.time.duration, interval = scene.output.interval;
  double next_frame = interval;
  while (world.time() < t_end * (1.0 - 1e-12)) {
    world.step(std::min(dt, t_end - world.time()));
    check_stability(world, dt);
    if (!world.contacts().empty()) {
      if (!summary.first_contact) summary.first_contact = world.time();
      ++summary.contact_steps;
    }
    const bool last = world.time() >= t_end * (1.0 - 1e-12);
    if (last || world.time() >= next_frame * (1.0 - 1e-12)) {
      next_frame = interval * (std::floor(world.time() / interval * (1.0 + 1e-12)) + 1.0);
      frame();
    }
  }
  summary.steps = world.step_count();  // spatial runs always start at t = 0
  summary.simulated = world.time();
  summary.wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return summary;
}

}  // namespace polyfloe::run
