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
#include <type_traits>

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

// The value of `key` in the top-level block `block` of a resolved scene, its comment and spaces cut off ("" where
// it has none).
std::string resolved_value(const std::string& resolved, const std::string& block, const std::string& key) {
  auto trimmed = [](std::string v) {
    v = v.substr(0, v.find('#'));
    const auto first = v.find_first_not_of(" \t'\""), last = v.find_last_not_of(" \t'\"");
    return first == std::string::npos ? std::string() : v.substr(first, last - first + 1);
  };
  std::istringstream in(resolved);
  bool inside = false;
  for (std::string line; std::getline(in, line);) {
    if (!line.empty() && line[0] != ' ' && line[0] != '#') inside = trimmed(line) == block + ":";
    if (inside && line.rfind("  " + key + ":", 0) == 0) return trimmed(line.substr(key.size() + 3));
  }
  return "";
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

template <class W>
constexpr bool kPlanar = std::is_same_v<W, dynamics::World>;

template <class W>
BasicSimulation<W>::BasicSimulation(const scene::Scene& scene, W world, const RunOptions& options,
                                    std::optional<Checkpoint> restart, const std::filesystem::path& restart_file)
    : scene_(scene), world_(std::move(world)), options_(options) {
  world_.set_threads(options_.threads);
  // From the world as the scene builds it (a restart's bonds may since have broken, which would change the step).
  dt_ = scene::time_step(scene_, world_);
  reference_speed_ = scene::reference_speed(scene_);
  signature_ = body_signature(world_);
  if constexpr (kPlanar<W>) {
    const scene::VelocityGridSettings& grid_settings = scene_.output.velocity_grid;
    if (grid_settings.enabled && (scene_.output.vtk || scene_.output.hdf5))
      grid_geometry_ = velocity_grid_geometry(grid_settings, world_);  // may refuse before any output exists
  }
  if (!restart) return;
  restart_results_ =
      take_checkpoint(scene_, world_, *restart, restart_file, options_.output_dir, grid_geometry_.has_value());
  restart_ = std::move(restart);
}

namespace {

// The interrupted run's outputs that a restart continues: the results holding the checkpoint's frames (the file a
// killed restart left aside, else results.h5, else the copy taken with the checkpoints, for a results.h5 the kill
// left unreadable), which it returns, and the VTK frame of the checkpoint.
std::filesystem::path check_restart_outputs(const scene::Scene& scene_, const Checkpoint& c,
                                            const std::filesystem::path& restart_file, const std::filesystem::path& dir,
                                            bool planar) {
  namespace fs = std::filesystem;
  const std::string where = "checkpoint " + restart_file.string() + ": ";
  std::error_code ec;
  const int frames = c.frames;
  fs::path restart_results_;
  if (scene_.output.hdf5) {
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
    char name[40];
    std::snprintf(name, sizeof name, planar ? "floes/floes_%06d.%s" : "bodies/bodies_%06d.%s", frames - 1,
                  scene_.output.vtk_pieces ? "pvtp" : "vtp");  // (in pieces: their list)
    if (!fs::exists(dir / name, ec))
      throw CheckpointError(where + "the interrupted run's frame " + (dir / name).string() + " is missing");
  }
  return restart_results_;
}

}  // namespace

template <class W>
std::filesystem::path take_checkpoint(const scene::Scene& scene, W& world, const Checkpoint& c,
                                      const std::filesystem::path& file, const std::filesystem::path& dir, bool grid) {
  const std::string where = "checkpoint " + file.string() + ": ";
  check_restart(c, file, world);
  if (output_block(c.scene_resolved) != output_block(scene::resolved_yaml(scene)))
    throw CheckpointError(where +
                          "the scene's output settings differ from those of the interrupted run; a restart "
                          "continues its output series, so they must be the same (output.checkpoint may change)");
  // The contact law of level floes stays: the contacts' history (springs, last normal forces) is its own. (A
  // checkpoint's scene text without the key: the model then had no choice, the centroid law.)
  auto model = [](const std::string& resolved) {
    const std::string m = resolved_value(resolved, "contact", "force_model");
    return m.empty() ? std::string(contact::force_model_name(contact::ForceModel::centroid)) : m;
  };
  const std::string was = model(c.scene_resolved), now = model(scene::resolved_yaml(scene));
  if (kPlanar<W> && was != now)
    throw CheckpointError(where + "the interrupted run's contacts followed contact.force_model '" + was +
                          "', the scene gives '" + now +
                          "'; a restart keeps the contact law (the contacts' history is its own): set "
                          "contact.force_model: " +
                          was + ", or run the scene anew into another folder (-o)");
  try {  // the state first: what is wrong with it is wrong whatever folder the restart is given
    if constexpr (kPlanar<W>)
      world.restore(c.world);
    else
      world.restore(*c.spatial);
  } catch (const std::invalid_argument& e) {
    throw CheckpointError(where + e.what());
  }
  std::filesystem::path results = check_restart_outputs(scene, c, file, dir, kPlanar<W>);
  if (scene.channel && !c.channel)
    throw CheckpointError(where + "has no channel monitor state; the scene has a channel");
  if (grid && !c.next_sample) throw CheckpointError(where + "has no velocity grid state; the scene has a grid");
  return results;
}

template std::filesystem::path take_checkpoint(const scene::Scene&, dynamics::World&, const Checkpoint&,
                                               const std::filesystem::path&, const std::filesystem::path&, bool);
template std::filesystem::path take_checkpoint(const scene::Scene&, dynamics::SpatialWorld&, const Checkpoint&,
                                               const std::filesystem::path&, const std::filesystem::path&, bool);

namespace {

// Where the step's time went (polyfloe run --profile), on stderr.
void print_profile(const dynamics::StepProfile& p, std::size_t bodies, bool planar) {
  const double total = p.integrate + p.shapes + p.broad + p.narrow_and_law + p.forcing + p.bonds;
  const double per = 1e6 / (static_cast<double>(std::max<std::uint64_t>(p.steps, 1)) * static_cast<double>(bodies));
  if (planar)
    std::fprintf(stderr,
                 "profile (us per body-step): integrate %.3f, shapes + prediction %.3f, broad phase %.3f, "
                 "narrow phase + law %.3f, drift forces %.3f, bonds %.3f; total %.3f (%zu bodies, %llu steps)\n",
                 p.integrate * per, p.shapes * per, p.broad * per, p.narrow_and_law * per, p.forcing * per,
                 p.bonds * per, total * per, bodies, static_cast<unsigned long long>(p.steps));
  else
    std::fprintf(stderr,
                 "profile (us per body-step): integrate (kicks, move, world vertices) %.3f, broad phase %.3f, "
                 "narrow phase + law %.3f, gravity and buoyancy %.3f; total %.3f (%zu bodies, %llu steps)\n",
                 p.integrate * per, p.broad * per, p.narrow_and_law * per, p.forcing * per, total * per, bodies,
                 static_cast<unsigned long long>(p.steps));
}

void print_contact_search(const dynamics::World& world) {
  const dynamics::StepProfile& p = world.profile();
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

template <class W>
void BasicSimulation<W>::guard(const dynamics::StepReport& report) {
  // Every step: a contact can start and end, and unstable drag can overflow, within a few steps. The check reads
  // the step's report (O(1)); only a step it does not clear is searched body by body.
  check_stability(world_, report, dt_, reference_speed_);
  if constexpr (!kPlanar<W>) {
    if (!world_.contacts().empty()) {
      if (!summary_.first_contact) summary_.first_contact = world_.time();
      ++summary_.contact_steps;
    }
  }
}

template <class W>
RunSummary BasicSimulation<W>::run() {
  using clock = std::chrono::steady_clock;
  const auto wall0 = clock::now();
  BasicRunOutputs<W> outputs(scene_, world_, options_, dt_, signature_, grid_geometry_, restart_, restart_results_);
  outputs.start(world_, restart_);
  const std::uint64_t first_step = world_.step_count();
  io::Progress progress(scene_.time.duration, options_.interactive, stderr, first_step);
  summary_ = RunSummary{};
  summary_.start_time = world_.time();

  // Steps of dt, landing on every frame time and on the end time (FrameClock).
  try {
    while (!outputs.at_end(world_.time())) {
      guard(world_.step(outputs.step(world_.time())));
      outputs.after_step(world_);
      progress.update(world_.time(), world_.step_count());
    }
  } catch (const InstabilityError& e) {
    throw InstabilityError(e.what() + outputs.save_unstable(world_));
  }
  progress.finish(world_.time(), world_.step_count());
  outputs.finish();

  RunSummary& s = summary_;
  s.steps = world_.step_count() - first_step;
  s.simulated = world_.time();
  s.wall = std::chrono::duration<double>(clock::now() - wall0).count();
  s.dt = dt_;
  s.frames = outputs.frames();
  if (const ChannelMonitor* channel = outputs.channel()) {
    s.channel_area_passed = channel->area_passed();
    s.channel_jam_time = channel->jam_time();
  }
  s.output_dir = outputs.path();
  if (options_.profile) {
    print_profile(world_.profile(), world_.size(), kPlanar<W>);
    if constexpr (kPlanar<W>) print_contact_search(world_);
  }
  return s;
}

template class BasicSimulation<dynamics::World>;
template class BasicSimulation<dynamics::SpatialWorld>;

}  // namespace polyfloe::run
