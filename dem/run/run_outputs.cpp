// A run's outputs on their schedule (run/run_outputs.h).
#include "run/run_outputs.h"

#include <algorithm>
#include <cstdio>
#include <exception>

#include "formats/atomic_file.h"
#include "scene/scene_reader.h"

namespace polyfloe::run {

namespace fs = std::filesystem;

namespace {

std::string join(const std::vector<std::string>& v, const char* sep) {
  std::string out;
  for (std::size_t i = 0; i < v.size(); ++i) out += (i ? sep : "") + v[i];
  return out;
}

// Keeps the newest `keep` of the numbered checkpoints this run's folder lists (io::OutputManifest), removing the
// older ones; a file it does not list is never touched.
void prune_checkpoints(const io::OutputManifest& manifest, int keep) {
  std::vector<std::string> files;
  for (const std::string& e : manifest.entries())
    if (e.size() == 32 && e.rfind("checkpoints/checkpoint_", 0) == 0 && e.compare(e.size() - 3, 3, ".h5") == 0 &&
        std::filesystem::exists(manifest.directory() / e))
      files.push_back(e);
  std::sort(files.begin(), files.end());
  for (std::size_t k = 0; k + static_cast<std::size_t>(keep) < files.size(); ++k) manifest.remove_file(files[k]);
}

// The channel monitor's series in results.h5.
std::vector<io::ExtraSeries> channel_series() {
  return {{"channel", "area_flux", "m^2/s", "net ice area through the strait entrance since the last frame / time"},
          {"channel", "area_passed", "m^2", "net ice area through the strait entrance since the start"},
          {"channel", "upstream_area", "m^2", "ice area with centroids before the strait entrance"},
          {"channel", "funnel_area", "m^2", "of which in the funnel, waiting to enter the strait"},
          {"channel", "funnel_mean_speed", "m/s", "mean speed of the floes in the funnel"},
          {"channel", "strait_floes", "1", "floes with centroids in the strait"},
          {"channel", "strait_mean_speed", "m/s", "mean speed of the floes in the strait"},
          {"channel", "jammed", "1",
           "1 while no ice has passed for channel.jam_window and the funnel's ice is slower than channel.jam_speed"}};
}

}  // namespace

template <class W>
BasicRunOutputs<W>::BasicRunOutputs(const scene::Scene& scene, const W& world, const RunOptions& options, double dt,
                                    const std::string& signature, const std::optional<io::ImageGrid>& grid,
                                    const std::optional<Checkpoint>& restart, const fs::path& restart_results)
    : scene_(scene),
      options_(options),
      dt_(dt),
      signature_(signature),
      // The folder contract (run/output_folder.h): locked for the run, every file listed before it is written.
      folder_(options.output_dir, restart ? OutputFolder::Mode::resume : OutputFolder::Mode::fresh) {
  const fs::path& out = folder_.path();
  io::OutputManifest& manifest = folder_.manifest();
  if (restart) {  // what the interrupted writers left half-made (the frame folders: VtkSeriesWriter::resume)
    manifest.remove_temporaries("");
    manifest.remove_temporaries("checkpoints/");
    manifest.remove_temporaries("xdmf/");
  }
  manifest.record("scene.resolved.yaml");
  io::write_file_atomic(out / "scene.resolved.yaml", scene::resolved_yaml(scene_));

  const double rho_w = scene_.world.drift.water_density;
  std::vector<io::ExtraSeries> extra;
  if constexpr (kPlanar) {
    if (scene_.output.vtk)
      vtk_ = std::make_unique<VtkWriter>(out, scene_.output.contacts, rho_w, &manifest,
                                         scene_.output.vtk_pieces ? std::max(1, options_.vtk_piece_writers) : 0);
    if (scene_.channel) {
      channel_.emplace(*scene_.channel, world);
      extra = channel_series();
    }
  } else {
    if (scene_.output.vtk) vtk_ = std::make_unique<VtkWriter>(out, scene_.output.contacts, &manifest);
  }
  if (restart && scene_.output.hdf5) {
    adopt_from_ = restart_results;
    if (adopt_from_ == out / "results.h5") {  // moved aside while its frames are copied into a new results.h5
      adopt_from_ = out / kInterruptedResults;
      manifest.record(kInterruptedResults);
      fs::rename(out / "results.h5", adopt_from_);
    }
  }
  if (scene_.output.hdf5) {
    io::RunInfo info{scene_.source_path, scene_.source_text, options_.version, join(scene_.overrides, "\n"), dt};
    manifest.record("results.h5");
    if constexpr (kPlanar) {
      manifest.record("results.xmf");
      h5_ = std::make_unique<Hdf5Writer>(out / "results.h5", world, info, rho_w, extra);
    } else {
      h5_ = std::make_unique<Hdf5Writer>(out / "results.h5", world, info);
    }
  }
  const double interval = scene_.output.interval;
  if constexpr (kPlanar)
    if (grid)
      velocity_grid_.emplace(*grid, interval / scene_.output.velocity_grid.samples_per_frame,
                             scene_.output.vtk ? out : fs::path(), h5_.get(), &manifest);
  schedule_ = FrameClock::make(interval, scene_.time.duration, dt);
  if (schedule_.every_step) std::fprintf(stderr, "%s\n", schedule_.note(dt).c_str());
}

template <class W>
BasicRunOutputs<W>::~BasicRunOutputs() {
  // results.xmf describes the frames results.h5 holds: written with each checkpoint and at the end, and also when
  // the run stops on an exception (unstable, the ice left a field, ...).
  if (!started_ || h5_ == nullptr || std::uncaught_exceptions() == 0) return;
  try {
    write_xdmf();
  } catch (const std::exception&) {
    // the run's own error is the one to report
  }
}

template <class W>
void BasicRunOutputs<W>::write_xdmf() {
  if constexpr (kPlanar) h5_->write_xdmf(folder_.path() / "results.xmf", &folder_.manifest());
}

template <class W>
void BasicRunOutputs<W>::start(W& world, const std::optional<Checkpoint>& restart) {
  if (restart) {
    const Checkpoint& c = *restart;
    frames_ = c.frames;
    frame_times_ = c.frame_times;
    schedule_.next = c.next_frame;
    if (h5_) {
      h5_->adopt_frames(adopt_from_, frames_);
      h5_->start_swmr();  // consistent on disk from here on ...
      std::error_code ec;
      fs::remove(folder_.path() / kInterruptedResults, ec);  // ... so the interrupted run's file can go
    }
    if constexpr (kPlanar) {
      if (vtk_) vtk_->resume(frame_times_, world.bonds() != nullptr);
      if (velocity_grid_) velocity_grid_->resume(*c.next_sample, frame_times_);
      if (channel_) channel_->restore(*c.channel);
    } else {
      if (vtk_) vtk_->resume(frame_times_);
    }
  } else {
    if (h5_) h5_->start_swmr();
    // the first frame's forces and contacts (a spatial world's contact law reads the step)
    world.compute_forces(kPlanar ? 0.0 : dt_);
    write_frame(world);
  }
  started_ = true;
}

template <class W>
void BasicRunOutputs<W>::write_frame(const W& world) {
  if constexpr (kPlanar) {
    extra_values_.clear();
    if (channel_) {
      const ChannelSample c = channel_->sample(world);
      extra_values_ = {c.area_flux,         c.area_passed,       c.upstream_area,
                       c.funnel_area,       c.funnel_mean_speed, static_cast<double>(c.strait_floes),
                       c.strait_mean_speed, c.jammed ? 1.0 : 0.0};
    }
    if (vtk_ && vtk_->pieces() > 0 && options_.vtk_piece_writers == 0) {  // one process: its one piece
      begin_vtk_pieces(world);
      io::write_vtk_piece(folder_.path(), world, vtk_->frames(), 0, scene_.output.contacts,
                          scene_.world.drift.water_density);
    }
    if (vtk_) vtk_->write_frame(world);
    if (velocity_grid_) velocity_grid_->write_frame(world);
    if (h5_) h5_->write_frame(world, extra_values_);
  } else {
    if (vtk_) vtk_->write_frame(world);
    if (h5_) h5_->write_frame(world);
  }
  ++frames_;
  frame_times_.push_back(world.time());
}

// Frames land on every multiple of the output interval and on the end time (FrameClock); checkpoints at every
// `checkpoint.every`-th frame and at the end.
template <class W>
void BasicRunOutputs<W>::after_step(const W& world) {
  const bool last = schedule_.at_end(world.time());
  if constexpr (kPlanar)
    if (velocity_grid_) velocity_grid_->after_step(world);
  if (!schedule_.frame_due(world.time())) return;
  schedule_.frame_written(world.time());
  write_frame(world);
  const scene::CheckpointSettings& checkpoints = scene_.output.checkpoint;
  if (checkpoints.every > 0 && (last || frames_ % checkpoints.every == 0)) {
    checkpoint(world, last ? "final" : "frame", checkpoint_path(folder_.path(), frames_));
    prune_checkpoints(folder_.manifest(), checkpoints.keep);
  }
}

template <class W>
void BasicRunOutputs<W>::snapshot_results() {
  const fs::path& out = folder_.path();
  h5_->flush();
  write_xdmf();
  const fs::path snapshot = out / kResultsSnapshot;
  folder_.manifest().record("checkpoints/");
  folder_.manifest().record(kResultsSnapshot);
  fs::create_directories(snapshot.parent_path());
  const fs::path tmp = io::temporary_sibling(snapshot);
  fs::copy_file(out / "results.h5", tmp, fs::copy_options::overwrite_existing);
  io::commit_file_atomic(tmp, snapshot);
}

template <class W>
void BasicRunOutputs<W>::checkpoint(const W& world, const char* kind, const fs::path& file) {
  if (h5_) snapshot_results();  // first: it then holds at least the frames of every checkpoint on disk
  Checkpoint c;
  c.kind = kind;
  c.code_version = options_.version;
  c.scene_resolved = scene::resolved_yaml(scene_);
  c.body_signature = signature_;
  c.dt = dt_;
  c.frames = frames_;
  c.frame_times = frame_times_;
  c.next_frame = schedule_.next;
  if constexpr (kPlanar)
    c.world = world.state();
  else
    c.spatial = world.state();
  if (channel_) c.channel = channel_->state();
  if (velocity_grid_) c.next_sample = velocity_grid_->next_sample();
  folder_.manifest().record("checkpoints/");
  folder_.manifest().record(file.lexically_relative(folder_.path()).string());
  write_checkpoint(file, c);
}

template <class W>
std::string BasicRunOutputs<W>::save_unstable(const W& world) {
  if (scene_.output.checkpoint.every <= 0) return "";
  const fs::path file = folder_.path() / "checkpoints" / "unstable.h5";
  std::string message;
  try {
    checkpoint(world, "unstable", file);
    message += " The state at that moment is in " + file.string() + " (for inspection)";
    fs::path last;
    try {
      last = find_checkpoint(folder_.path());
    } catch (const CheckpointError&) {
      // none yet: the run failed before its first checkpoint
    }
    message += last.empty() ? "."
                            : "; to continue with the change above, restart from the last checkpoint: "
                              "polyfloe run SCENE --restart " +
                                  last.string() + ".";
  } catch (const std::exception& w) {
    message += std::string(" (the state could not be saved: ") + w.what() + ")";
  }
  return message;
}

template <class W>
void BasicRunOutputs<W>::finish() {
  if (h5_) write_xdmf();
}

template class BasicRunOutputs<dynamics::World>;
template class BasicRunOutputs<dynamics::SpatialWorld>;

}  // namespace polyfloe::run
