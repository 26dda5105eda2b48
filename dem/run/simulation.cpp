#include "run/simulation.h"

#include "run/channel_monitor.h"
#include "run/output_folder.h"
#include "run/run_outputs.h"
#include "run/velocity_grid.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <exception>
#include <sstream>

#include "contact/contact_law.h"
#include "formats/atomic_file.h"
#include "io/hdf5_writer.h"
#include "io/progress.h"
#include "io/vtk_writer.h"
#include "scene/scene_reader.h"

namespace polyfloe::run {

std::string FrameClock::note(double dt) const {
  std::ostringstream m;
  m << "polyfloe: note: output.interval " << interval << " s is shorter than the step dt = " << dt
    << " s: a frame at every step (at the step times, not the interval's multiples)";
  return m.str();
}

using geometry::Vec2;

namespace {

// The velocity grid the scene asks for (its region, or every body at t = 0), checked against the size limit.
GridGeometry velocity_grid_geometry(const scene::VelocityGridSettings& g, const dynamics::World& world) {
  GridGeometry geo;
  if (g.region) {
    const auto& r = *g.region;
    geo.x0 = r[0];
    geo.y0 = r[1];
    geo.cell = g.cell;
    geo.nx = static_cast<int>(std::max(1.0, std::ceil((r[2] - r[0]) / g.cell)));
    geo.ny = static_cast<int>(std::max(1.0, std::ceil((r[3] - r[1]) / g.cell)));
    return geo;
  }
  // The automatic region: every body at t = 0 (covering() refuses a grid past the size limit).
  return VelocityGrid::covering(world, g.cell);
}

}  // namespace

void check_contact_resolution(const dynamics::World& w, double dt) {
  std::ostringstream why;
  const dynamics::World::ContactResolution r = w.shortest_active_contact();
  if (r.a >= 0 && r.duration < dynamics::kMinStepsPerContact * dt) {
    why << "the contact between bodies " << w.id(r.a) << " and " << w.id(r.b) << " at t = " << w.time() << " s (step "
        << w.step_count() << ") has an impact speed of about " << r.impact_speed << " m/s, so it lasts " << r.duration
        << " s: only " << r.duration / dt << " time steps of dt = " << dt << " s (at least "
        << dynamics::kMinStepsPerContact << " are needed, 40 for accuracy). Set run.reference_speed to "
        << r.impact_speed << " (the automatic time step then resolves such impacts), or run.dt to " << r.duration / 40.0
        << ".";
    throw InstabilityError(why.str());
  }
}

namespace {

void check_deepest_overlap(const dynamics::World& w, double dt) {
  // The deepest overlap against half the smaller floe's radius (tracked by the World in its contact sum).
  if (const dynamics::World::DeepestOverlap& c = w.deepest_overlap(); c.ratio > 1.0) {
    std::ostringstream why;
    why << "bodies " << w.id(c.a) << " and " << w.id(c.b) << " overlap by " << c.depth
        << " m (more than half the smaller floe's radius, " << c.limit << " m) at t = " << w.time() << " s (step "
        << w.step_count() << "). The contact is too soft or the time step too large for the impact speeds: set "
        << "run.dt to " << 0.25 * dt << ", or raise run.reference_speed or run.steps_per_contact.";
    throw InstabilityError(why.str());
  }
}

}  // namespace

void check_stability(const dynamics::World& w, double dt, double reference_speed) {
  check_contact_resolution(w, dt);
  // Runaway: far faster than anything the forcing or the impacts can produce.
  const double speed_limit = std::max(50.0, 20.0 * reference_speed);
  const double energy_limit =
      0.5 * w.dynamic_mass() * 100.0 * std::max(1.0, reference_speed) * std::max(1.0, reference_speed);
  // The World's summary of the step (gathered in its final kick) clears the bodies at once; only a state it
  // cannot clear is searched body by body below, for the body to name (and decides by itself).
  if (const dynamics::World::MotionSummary& s = w.motion_summary();
      s.all_finite && std::sqrt(s.max_speed2) + s.max_spin_speed <= speed_limit && s.energy <= energy_limit) {
    check_deepest_overlap(w, dt);
    return;
  }
  const auto pos = w.positions();
  const auto vel = w.velocities();
  const auto om = w.angular_velocities();
  std::ostringstream why;
  auto advice = [&] {
    why << " at t = " << w.time() << " s (step " << w.step_count() << "). The time step dt = " << dt
        << " s is probably too large for the contact stiffness: set run.dt to " << 0.25 * dt
        << " or raise run.steps_per_contact (e.g. x4), or lower ice.youngs_modulus.";
    throw InstabilityError(why.str());
  };
  // Runaway energy: the kinetic energy of the dynamic bodies beyond what they would have all moving at 10 x the
  // reference speed (an instability that grows in many bodies at once, before any one reaches the speed limit).
  double energy = 0.0, worst = 0.0;
  std::size_t worst_body = 0;
  for (std::size_t i = 0; i < w.size(); ++i) {
    const int b = static_cast<int>(i);
    const bool dynamic = w.motion(b) == dynamics::Motion::dynamic;
    const bool finite = std::isfinite(pos[i].x()) && std::isfinite(pos[i].y()) && std::isfinite(vel[i].x()) &&
                        std::isfinite(vel[i].y()) && std::isfinite(om[i]) && std::isfinite(w.yaws()[i]);
    const double speed = finite ? vel[i].norm() + std::abs(om[i]) * w.shape(b).circumradius() : 0.0;
    if (!finite) {
      why << "body " << w.id(b) << " has a non-finite state (NaN or Inf)";
    } else if (dynamic && speed > speed_limit) {  // kinematic bodies move as the scene prescribes
      why << "body " << w.id(b) << " moves at " << speed << " m/s (limit " << speed_limit
          << " m/s = max(50, 20 x reference speed))";
    } else {
      if (dynamic) {
        const double e = 0.5 * w.mass(b) * vel[i].squaredNorm() + 0.5 * w.inertia(b) * om[i] * om[i];
        energy += e;
        if (e > worst) {
          worst = e;
          worst_body = i;
        }
      }
      continue;
    }
    advice();
  }
  if (energy > energy_limit) {
    why << "the kinetic energy of the ice, " << energy << " J, exceeds " << energy_limit
        << " J (every floe at 10 x the reference speed; the most energetic is body "
        << w.id(static_cast<int>(worst_body)) << " with " << worst << " J): runaway energy";
    advice();
  }
  check_deepest_overlap(w, dt);
}

namespace {

// The lines of the `output` block of a resolved scene, without its checkpoint settings (which a restart may change).
std::string output_block(const std::string& resolved) {
  std::string out, line;
  std::istringstream in(resolved);
  bool inside = false, checkpoint = false;
  while (std::getline(in, line)) {
    if (!line.empty() && line[0] != ' ' && line[0] != '#') {
      inside = line.rfind("output:", 0) == 0;
      continue;
    }
    if (!inside) continue;
    if (line.rfind("  ", 0) == 0 && line.size() > 2 && line[2] != ' ') checkpoint = line.rfind("  checkpoint:", 0) == 0;
    if (!checkpoint) out += line + "\n";
  }
  return out;
}

// Reads what a restart copies from an interrupted run's results: the first `frames` rows of every series and every
// other dataset whole. Throws io::IoError (naming the dataset) when a block cannot be read or a series is short.
void readable_frames(const io::hdf5::Group& g, std::uint64_t frames) {
  for (const io::hdf5::Group::Child& c : g.children()) {
    if (c.group) {
      readable_frames(g.open_group(c.name), frames);
      continue;
    }
    const io::hdf5::Dataset d = g.open_dataset(c.name);
    if (!d.extendible()) {
      (void)d.read<double>();
    } else if (d.rows() < frames) {
      throw io::IoError(d.where() + ": " + std::to_string(d.rows()) + " rows, fewer than the checkpoint's " +
                        std::to_string(frames) + " frames");
    } else if (frames > 0) {
      (void)d.read_rows<double>(0, frames);
    }
  }
}

}  // namespace

Simulation::Simulation(const scene::Scene& scene, dynamics::World world, const RunOptions& options,
                       std::optional<Checkpoint> restart, const std::filesystem::path& restart_file)
    : scene_(scene), world_(std::move(world)), options_(options) {
  namespace fs = std::filesystem;
  world_.set_threads(options_.threads);
  // From the world as the scene builds it (a restart's bonds may since have broken, which would change the step).
  dt_ = scene::time_step(scene_, world_);
  signature_ = body_signature(world_);
  const scene::VelocityGridSettings& grid_settings = scene_.output.velocity_grid;
  if (grid_settings.enabled && (scene_.output.vtk || scene_.output.hdf5))
    grid_geometry_ = velocity_grid_geometry(grid_settings, world_);  // may refuse before any output exists
  if (!restart) return;

  const Checkpoint& c = *restart;
  const std::string where = "checkpoint " + restart_file.string() + ": ";
  check_restart(c, restart_file, world_);
  if (output_block(c.scene_resolved) != output_block(scene::resolved_yaml(scene_)))
    throw CheckpointError(where +
                          "the scene's output settings differ from those of the interrupted run; a restart "
                          "continues its output series, so they must be the same (output.checkpoint may change)");
  const fs::path dir = options_.output_dir;
  std::error_code ec;
  const int frames = c.frames;
  if (scene_.output.hdf5) {
    // The interrupted run's frames: from the file a killed restart left aside, else results.h5, else the copy
    // taken with the checkpoints (for a results.h5 the kill left unreadable).
    std::string why;
    for (const fs::path& previous : {dir / kInterruptedResults, dir / "results.h5", dir / kResultsSnapshot}) {
      if (!fs::exists(previous, ec)) continue;
      try {
        const io::hdf5::File f(previous, io::hdf5::File::Mode::read_only);
        const io::hdf5::Dataset t = f.root().open_dataset("time");
        if (t.rows() < static_cast<std::uint64_t>(frames)) {
          why += "; " + previous.string() + " has " + std::to_string(t.rows()) +
                 " frames, the checkpoint follows frame " + std::to_string(frames - 1);
          continue;
        }
        const std::vector<double> last = t.read_rows<double>(static_cast<std::uint64_t>(frames - 1), 1);
        if (last[0] != c.frame_times.back())
          throw CheckpointError(where + previous.string() + " has frame " + std::to_string(frames - 1) +
                                " at t = " + std::to_string(last[0]) + " s, the checkpoint at t = " +
                                std::to_string(c.frame_times.back()) + " s: they belong to different runs");
        readable_frames(f.root(), static_cast<std::uint64_t>(frames));  // every series, as the copy will read it
        restart_results_ = previous;
        break;
      } catch (const io::IoError& e) {
        why += "; " + previous.string() + " cannot be read (" + e.what() + ")";
      }
    }
    if (restart_results_.empty()) {
      if (why.empty())
        throw CheckpointError(where + "the interrupted run's results are not in " + dir.string() +
                              " (no results.h5); give its output folder with -o");
      throw CheckpointError(where + "no copy of the interrupted run's results holds the checkpoint's frames" + why +
                            "; restart into a new folder with -o to rerun from the start");
    }
  }
  if (scene_.output.vtk) {
    char name[32];
    std::snprintf(name, sizeof name, "floes/floes_%06d.vtp", frames - 1);
    if (!fs::exists(dir / name, ec))
      throw CheckpointError(where + "the interrupted run's frame " + (dir / name).string() + " is missing");
  }
  try {
    world_.restore(c.world);
  } catch (const std::invalid_argument& e) {
    throw CheckpointError(where + e.what());
  }
  if (scene_.channel && !c.channel)
    throw CheckpointError(where + "has no channel monitor state; the scene has a channel");
  if (grid_geometry_ && !c.next_sample)
    throw CheckpointError(where + "has no velocity grid state; the scene has a grid");
  restart_ = std::move(restart);
}

namespace {

// Where the step's time went (polyfloe run --profile), on stderr.
void print_profile(const dynamics::World& world) {
  const dynamics::StepProfile& p = world.profile();
  const double total = p.integrate + p.shapes + p.broad + p.narrow_and_law + p.forcing + p.bonds;
  const double per = 1e6 / (static_cast<double>(std::max<std::uint64_t>(p.steps, 1)) * world.size());
  std::fprintf(stderr,
               "profile (us per body-step): integrate %.3f, shapes + prediction %.3f, broad phase %.3f, "
               "narrow phase + law %.3f, drift forces %.3f, bonds %.3f; total %.3f (%zu bodies, %llu steps)\n",
               p.integrate * per, p.shapes * per, p.broad * per, p.narrow_and_law * per, p.forcing * per, p.bonds * per,
               total * per, world.size(), static_cast<unsigned long long>(p.steps));
  const std::uint64_t builds = world.neighbour_list_builds();
  const double body_steps = static_cast<double>(std::max<std::uint64_t>(p.steps, 1)) * world.size();
  std::fprintf(stderr,
               "contact search: %.2f candidate pairs and %.2f contacts per body-step (%.1f %% of them built from "
               "the overlap's topology of the step before); neighbour lists built %llu times (every %.0f steps; "
               "contact.broad_phase_skin)\n",
               static_cast<double>(p.candidates) / body_steps, static_cast<double>(p.contacts) / body_steps,
               100.0 * static_cast<double>(p.reused) / static_cast<double>(std::max<std::uint64_t>(p.contacts, 1)),
               static_cast<unsigned long long>(builds),
               static_cast<double>(p.steps) / static_cast<double>(std::max<std::uint64_t>(builds, 1)));
}

}  // namespace

RunSummary Simulation::run() {
  using clock = std::chrono::steady_clock;
  const auto wall0 = clock::now();
  const double v_ref = scene::reference_speed(scene_);
  RunOutputs outputs(scene_, world_, options_, dt_, signature_, grid_geometry_, restart_, restart_results_);
  outputs.start(world_, restart_);
  const std::uint64_t first_step = world_.step_count();
  io::Progress progress(scene_.time.duration, options_.interactive, stderr, first_step);
  const double start_time = world_.time();

  // Steps of dt, landing on every frame time and on the end time (FrameClock).
  try {
    while (!outputs.at_end(world_.time())) {
      world_.step(outputs.step(world_.time()));
      // Every step: a contact can start and end, and unstable drag can overflow, within a few steps. The check
      // costs a few ns per body against ~200 ns per body for the step.
      check_stability(world_, dt_, v_ref);
      outputs.after_step(world_);
      progress.update(world_.time(), world_.step_count());
    }
  } catch (const InstabilityError& e) {
    throw InstabilityError(e.what() + outputs.save_unstable(world_));
  }
  progress.finish(world_.time(), world_.step_count());
  outputs.finish();

  RunSummary s;
  s.steps = world_.step_count() - first_step;
  s.start_time = start_time;
  s.simulated = world_.time();
  s.wall = std::chrono::duration<double>(clock::now() - wall0).count();
  s.dt = dt_;
  s.frames = outputs.frames();
  if (const ChannelMonitor* channel = outputs.channel()) {
    s.channel_area_passed = channel->area_passed();
    s.channel_jam_time = channel->jam_time();
  }
  s.output_dir = outputs.path();
  if (options_.profile) print_profile(world_);
  return s;
}

}  // namespace polyfloe::run
