#include "run/checkpoint.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <limits>
#include <system_error>
#include <type_traits>

#include "formats/atomic_file.h"
#include "formats/hdf5_file.h"
#include "scene/scene.h"

namespace polyfloe::run {

namespace fs = std::filesystem;
using geometry::Vec2;
using io::hdf5::Dataset;
using io::hdf5::Dims;
using io::hdf5::File;
using io::hdf5::Group;

namespace {

constexpr const char* kFormat = "polyfloe-checkpoint";
constexpr std::int64_t kFormatVersion = 1;
constexpr double kNone = std::numeric_limits<double>::quiet_NaN();

class Fnv {
 public:
  template <class T>
  void add(const T& v) {
    unsigned char bytes[sizeof(T)];
    std::memcpy(bytes, &v, sizeof(T));
    for (unsigned char b : bytes) h_ = (h_ ^ b) * 0x100000001b3ull;
  }
  std::string hex() const {
    char buf[20];
    std::snprintf(buf, sizeof buf, "%016llx", static_cast<unsigned long long>(h_));
    return buf;
  }

 private:
  std::uint64_t h_ = 0xcbf29ce484222325ull;
};

std::vector<double> flat(const std::vector<Vec2>& v) {
  std::vector<double> out(2 * v.size());
  for (std::size_t i = 0; i < v.size(); ++i) {
    out[2 * i] = v[i].x();
    out[2 * i + 1] = v[i].y();
  }
  return out;
}

std::vector<Vec2> unflat(const std::vector<double>& v) {
  std::vector<Vec2> out(v.size() / 2);
  for (std::size_t i = 0; i < out.size(); ++i) out[i] = {v[2 * i], v[2 * i + 1]};
  return out;
}

template <class T>
void put(Group& g, const char* name, const std::vector<T>& v) {
  g.write_dataset<T>(name, std::span<const T>(v));
}
void put2(Group& g, const char* name, const std::vector<Vec2>& v) {
  const std::vector<double> f = flat(v);
  g.write_dataset<double>(name, std::span<const double>(f), Dims{v.size(), 2});
}

// Reads a dataset of `rows` rows (any row shape; `width` values per row) into a flat vector.
template <class T>
std::vector<T> get(const Group& g, const char* name, std::size_t rows, std::size_t width = 1) {
  const Dataset d = g.open_dataset(name);
  const Dims dims = d.dims();
  const std::uint64_t expected_rank = width == 1 ? 1 : 2;
  if (dims.size() != expected_rank || dims[0] != rows || (width > 1 && dims[1] != width)) {
    std::string shape;
    for (auto x : dims) shape += (shape.empty() ? "" : " x ") + std::to_string(x);
    throw CheckpointError("checkpoint " + d.where() + ": has shape [" + shape + "], expected [" + std::to_string(rows) +
                          (width > 1 ? " x " + std::to_string(width) : std::string()) +
                          "] (the arrays of one checkpoint must agree)");
  }
  return d.read<T>();
}

// Rows of a dataset whose length is not known in advance (rank 1, or rank 2 with `width` columns).
std::size_t rows_of(const Group& g, const char* name) {
  const Dims dims = g.open_dataset(name).dims();
  return dims.empty() ? 0 : static_cast<std::size_t>(dims[0]);
}

std::optional<double> maybe(double v) { return std::isnan(v) ? std::nullopt : std::optional<double>(v); }

}  // namespace

std::string body_signature(const dynamics::World& w) {
  Fnv h;
  h.add(static_cast<std::uint64_t>(w.size()));
  for (std::size_t k = 0; k < w.size(); ++k) {
    const int i = static_cast<int>(k);
    h.add(w.id(i));
    h.add(static_cast<int>(w.motion(i)));
    h.add(w.thickness(i));
    h.add(w.mass(i));
    for (const Vec2& v : w.shape(i).vertices()) {
      h.add(v.x());
      h.add(v.y());
    }
  }
  if (const bonds::BondSet* b = w.bonds()) {
    h.add(static_cast<std::uint64_t>(b->faces()));
    h.add(static_cast<std::uint64_t>(b->points()));
  }
  return h.hex();
}

fs::path checkpoint_path(const fs::path& output_dir, int frames) {
  char buf[40];
  std::snprintf(buf, sizeof buf, "checkpoint_%06d.h5", frames);
  return output_dir / "checkpoints" / buf;
}

void write_checkpoint(const fs::path& file, const Checkpoint& c) {
  std::error_code ec;
  fs::create_directories(file.parent_path(), ec);
  if (ec) throw io::IoError("cannot create the checkpoint folder " + file.parent_path().string() + ": " + ec.message());
  const fs::path tmp = io::temporary_sibling(file);
  try {
    File f(tmp, File::Mode::exclusive);
    Group& root = f.root();
    const dynamics::WorldState& w = c.world;
    root.set_attribute("format", kFormat);
    root.set_attribute("format_version", kFormatVersion);
    root.set_attribute("kind", c.kind);
    root.set_attribute("code_version", c.code_version);
    root.set_attribute("scene_resolved", c.scene_resolved);
    root.set_attribute("body_signature", c.body_signature);
    root.set_attribute("dt", c.dt);
    root.set_attribute("time", w.time);
    root.set_attribute("steps", static_cast<std::int64_t>(w.steps));
    root.set_attribute("frames", static_cast<std::int64_t>(c.frames));
    root.set_attribute("next_frame", c.next_frame);
    root.set_attribute("forces_ready", static_cast<std::int64_t>(w.forces_ready ? 1 : 0));
    root.set_attribute("bonds_failed_last", static_cast<std::int64_t>(w.bonds_failed_last));
    put(root, "frame_times", c.frame_times);

    Group g = root.create_group("world");
    put(g, "ids", w.ids);
    put2(g, "position", w.position);
    put(g, "yaw", w.yaw);
    put2(g, "velocity", w.velocity);
    put(g, "omega", w.omega);
    put2(g, "force", w.force);
    put(g, "torque", w.torque);
    put2(g, "external_force", w.external_force);
    put(g, "external_torque", w.external_torque);
    std::vector<double> loads;
    loads.reserve(10 * w.drift_load.size());
    for (const forcing::DriftLoad& d : w.drift_load)
      for (double v : {d.force.x(), d.force.y(), d.torque, d.dxx, d.dxy, d.dyy, d.dxw, d.dyw, d.dww, d.mf})
        loads.push_back(v);
    g.write_dataset<double>("drift_load", std::span<const double>(loads), Dims{w.drift_load.size(), 10});
    put2(g, "lin_force", w.lin_force);
    put(g, "lin_torque", w.lin_torque);

    Group cg = root.create_group("contacts");
    std::vector<std::uint64_t> lo, hi;
    std::vector<double> spring, normal_force;
    for (const auto& [key, value] : w.contact_history) {
      lo.push_back(key.lo);
      hi.push_back(key.hi);
      spring.push_back(value.spring);
      normal_force.push_back(value.normal_force);
    }
    put(cg, "lo", lo);
    put(cg, "hi", hi);
    put(cg, "spring", spring);
    put(cg, "normal_force", normal_force);

    if (w.bonds) {
      Group b = root.create_group("bonds");
      put(b, "face_intact", w.bonds->face_intact);
      put(b, "face_points_left", w.bonds->face_points_left);
      put(b, "face_broken_time", w.bonds->face_broken_time);
      put(b, "point_intact", w.bonds->point_intact);
      put(b, "point_sigma", w.bonds->point_sigma);
      put(b, "point_tau", w.bonds->point_tau);
      b.set_attribute("max_sigma", w.bonds->max_sigma);
      b.set_attribute("max_tau", w.bonds->max_tau);
    }
    if (c.channel) {
      Group ch = root.create_group("channel");
      put(ch, "through", c.channel->through);
      ch.set_attribute("last_time", c.channel->last_time);
      ch.set_attribute("last_flow_time", c.channel->last_flow_time);
      ch.set_attribute("passed", c.channel->passed);
      ch.set_attribute("stalled_since", c.channel->stalled_since.value_or(kNone));
      ch.set_attribute("jam_time", c.channel->jam_time.value_or(kNone));
    }
    if (c.next_sample) root.create_group("velocity_grid").set_attribute("next_sample", *c.next_sample);
    f.close();
  } catch (...) {
    fs::remove(tmp, ec);
    throw;
  }
  io::commit_file_atomic(tmp, file);
}

Checkpoint read_checkpoint(const fs::path& file) {
  std::error_code ec;
  if (!fs::is_regular_file(file, ec)) throw CheckpointError("checkpoint " + file.string() + ": no such file");
  Checkpoint c;
  try {
    const File f(file, File::Mode::read_only);
    const Group& root = f.root();
    if (!root.has_attribute("format") || root.string_attribute("format") != kFormat)
      throw CheckpointError("checkpoint " + file.string() + ": not a PolyFloe checkpoint (no format = '" +
                            std::string(kFormat) + "' attribute)");
    const std::int64_t version = root.int_attribute("format_version");
    if (version != kFormatVersion)
      throw CheckpointError("checkpoint " + file.string() + ": format version " + std::to_string(version) +
                            "; this program reads version " + std::to_string(kFormatVersion));
    c.kind = root.string_attribute("kind");
    c.code_version = root.string_attribute("code_version");
    c.scene_resolved = root.string_attribute("scene_resolved");
    c.body_signature = root.string_attribute("body_signature");
    c.dt = root.double_attribute("dt");
    c.frames = static_cast<int>(root.int_attribute("frames"));
    c.next_frame = root.double_attribute("next_frame");
    // Counts are checked before anything is sized by them: a checkpoint is input like any other.
    const std::int64_t frames = root.int_attribute("frames");
    if (frames < 0 || static_cast<double>(frames) > scene::OutputSettings::kMaxFrames)
      throw CheckpointError("checkpoint " + file.string() + ": frame count " + std::to_string(frames) +
                            " is outside [0, " +
                            std::to_string(static_cast<long long>(scene::OutputSettings::kMaxFrames)) + "]");
    c.frames = static_cast<int>(frames);
    c.frame_times = get<double>(root, "frame_times", static_cast<std::size_t>(c.frames));
    dynamics::WorldState& w = c.world;
    w.time = root.double_attribute("time");
    const std::int64_t steps = root.int_attribute("steps");
    if (steps < 0 || static_cast<double>(steps) > scene::kMaxSteps)
      throw CheckpointError("checkpoint " + file.string() + ": step count " + std::to_string(steps) +
                            " is outside [0, 1e12]");
    w.steps = static_cast<std::uint64_t>(steps);
    if (!(w.time >= 0.0) || !std::isfinite(w.time))
      throw CheckpointError("checkpoint " + file.string() + ": time " + std::to_string(w.time) + " s is not a time");
    w.forces_ready = root.int_attribute("forces_ready") != 0;
    w.bonds_failed_last = static_cast<int>(root.int_attribute("bonds_failed_last"));

    const Group g = root.open_group("world");
    const std::size_t n = rows_of(g, "ids");
    w.ids = get<std::uint64_t>(g, "ids", n);
    w.position = unflat(get<double>(g, "position", n, 2));
    w.yaw = get<double>(g, "yaw", n);
    w.velocity = unflat(get<double>(g, "velocity", n, 2));
    w.omega = get<double>(g, "omega", n);
    w.force = unflat(get<double>(g, "force", n, 2));
    w.torque = get<double>(g, "torque", n);
    w.external_force = unflat(get<double>(g, "external_force", n, 2));
    w.external_torque = get<double>(g, "external_torque", n);
    const std::size_t nd = rows_of(g, "drift_load");
    const std::vector<double> loads = get<double>(g, "drift_load", nd, 10);
    w.drift_load.resize(nd);
    for (std::size_t i = 0; i < nd; ++i) {
      const double* v = loads.data() + 10 * i;
      forcing::DriftLoad& d = w.drift_load[i];
      d.force = {v[0], v[1]};
      d.torque = v[2];
      d.dxx = v[3];
      d.dxy = v[4];
      d.dyy = v[5];
      d.dxw = v[6];
      d.dyw = v[7];
      d.dww = v[8];
      d.mf = v[9];
    }
    const std::size_t nl = rows_of(g, "lin_force");
    w.lin_force = unflat(get<double>(g, "lin_force", nl, 2));
    w.lin_torque = get<double>(g, "lin_torque", nl);

    const Group cg = root.open_group("contacts");
    const std::size_t nc = rows_of(cg, "lo");
    const auto lo = get<std::uint64_t>(cg, "lo", nc), hi = get<std::uint64_t>(cg, "hi", nc);
    const auto spring = get<double>(cg, "spring", nc);
    // The pairs' last normal forces (absent from checkpoints written before they were kept: NaN, which the
    // contact stage reads as unknown, falling back to the plain velocity prediction for that one step).
    const auto normal_force = cg.exists("normal_force")
                                  ? get<double>(cg, "normal_force", nc)
                                  : std::vector<double>(nc, std::numeric_limits<double>::quiet_NaN());
    w.contact_history.reserve(nc);
    for (std::size_t k = 0; k < nc; ++k)
      w.contact_history.push_back({contact::PairKey{lo[k], hi[k]}, {spring[k], normal_force[k]}});

    if (root.exists("bonds")) {
      const Group b = root.open_group("bonds");
      bonds::BondState s;
      const std::size_t nf = rows_of(b, "face_intact"), np = rows_of(b, "point_intact");
      s.face_intact = get<std::uint8_t>(b, "face_intact", nf);
      s.face_points_left = get<std::int32_t>(b, "face_points_left", nf);
      s.face_broken_time = get<double>(b, "face_broken_time", nf);
      s.point_intact = get<std::uint8_t>(b, "point_intact", np);
      s.point_sigma = get<double>(b, "point_sigma", np);
      s.point_tau = get<double>(b, "point_tau", np);
      s.max_sigma = b.double_attribute("max_sigma");
      s.max_tau = b.double_attribute("max_tau");
      w.bonds = std::move(s);
    }
    if (root.exists("channel")) {
      const Group ch = root.open_group("channel");
      ChannelMonitor::State s;
      s.through = get<std::uint8_t>(ch, "through", n);
      s.last_time = ch.double_attribute("last_time");
      s.last_flow_time = ch.double_attribute("last_flow_time");
      s.passed = ch.double_attribute("passed");
      s.stalled_since = maybe(ch.double_attribute("stalled_since"));
      s.jam_time = maybe(ch.double_attribute("jam_time"));
      c.channel = std::move(s);
    }
    if (root.exists("velocity_grid")) c.next_sample = root.open_group("velocity_grid").double_attribute("next_sample");
  } catch (const CheckpointError&) {
    throw;
  } catch (const io::IoError& e) {
    throw CheckpointError("checkpoint " + file.string() + ": cannot be read: " + e.what());
  }
  return c;
}

fs::path find_checkpoint(const fs::path& path) {
  std::error_code ec;
  if (fs::is_regular_file(path, ec)) return path;
  if (!fs::is_directory(path, ec)) throw CheckpointError("checkpoint " + path.string() + ": no such file or folder");
  const fs::path dir = fs::is_directory(path / "checkpoints", ec) ? path / "checkpoints" : path;
  fs::path best;
  for (const auto& entry : fs::directory_iterator(dir, ec)) {
    const std::string name = entry.path().filename().string();
    // checkpoint_NNNNNN.h5: zero-padded, so the name order is the frame order
    if (name.size() == 20 && name.rfind("checkpoint_", 0) == 0 && entry.path().extension() == ".h5" &&
        (best.empty() || name > best.filename().string()))
      best = entry.path();
  }
  if (best.empty())
    throw CheckpointError("no checkpoint (checkpoint_NNNNNN.h5) in " + dir.string() +
                          ": checkpoints are written every output.checkpoint.every frames");
  return best;
}

void check_restart(const Checkpoint& c, const fs::path& file, const dynamics::World& world) {
  const std::string where = "checkpoint " + file.string() + ": ";
  if (c.kind == "unstable")
    throw CheckpointError(where +
                          "holds the state at which the run became unstable (for inspection); restart "
                          "from an earlier checkpoint_NNNNNN.h5 in the same folder, with a smaller time step");
  if (c.kind != "frame" && c.kind != "final") throw CheckpointError(where + "unknown kind '" + c.kind + "'");
  const std::string sig = body_signature(world);
  if (c.body_signature != sig)
    throw CheckpointError(where + "was written for other bodies than the scene builds (signature " + c.body_signature +
                          ", the scene's " + sig +
                          ": a different floe field, seed, sheet or "
                          "body list); restart with the scene and --set options of the interrupted run");
  if (c.frames < 1 || c.frame_times.size() != static_cast<std::size_t>(c.frames))
    throw CheckpointError(where + "has no output frame to continue from");
  if (!(c.dt > 0.0) || !std::isfinite(c.dt)) throw CheckpointError(where + "has an invalid time step");
  if (!std::isfinite(c.next_frame)) throw CheckpointError(where + "has an invalid next frame time");
  for (std::size_t k = 0; k < c.frame_times.size(); ++k)
    if (!std::isfinite(c.frame_times[k]) || (k > 0 && !(c.frame_times[k] > c.frame_times[k - 1])) ||
        c.frame_times[k] > c.world.time)
      throw CheckpointError(where + "its frame times are not increasing times up to the checkpoint's " +
                            std::to_string(c.world.time) + " s (frame " + std::to_string(k) + ")");
  const dynamics::WorldState& w = c.world;
  auto finite = [](const auto& v) {
    return std::all_of(v.begin(), v.end(), [](const auto& x) {
      if constexpr (std::is_arithmetic_v<std::decay_t<decltype(x)>>)
        return std::isfinite(x);
      else
        return x.allFinite();
    });
  };
  if (!finite(w.position) || !finite(w.yaw) || !finite(w.velocity) || !finite(w.omega) || !finite(w.force) ||
      !finite(w.torque))
    throw CheckpointError(where +
                          "holds a body state that is not finite (NaN or infinite position, velocity or "
                          "force); restart from an earlier checkpoint");
  // Beyond 10^10 m the floes' own extent rounds away against their position: no run gets there.
  for (const Vec2& p : w.position)
    if (!(p.cwiseAbs().maxCoeff() <= 1e10))
      throw CheckpointError(where + "holds a body at " + std::to_string(p.x()) + ", " + std::to_string(p.y()) +
                            " m, beyond the 1e10 m any run reaches");
}

}  // namespace polyfloe::run
