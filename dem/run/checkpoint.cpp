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

template <class T>
void put(Group& g, const char* name, const std::vector<T>& v) {
  g.write_dataset<T>(name, std::span<const T>(v));
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
// At most 10^8 rows (a checkpoint of 10^8 bodies or pairs is gigabytes; a larger count is a damaged file, refused
// before anything is allocated for it).
std::size_t rows_of(const Group& g, const char* name) {
  const Dataset d = g.open_dataset(name);
  const Dims dims = d.dims();
  const std::uint64_t rows = dims.empty() ? 0 : dims[0];
  if (rows > 100'000'000)
    throw CheckpointError("checkpoint " + d.where() + ": " + std::to_string(rows) +
                          " rows, more than the 1e8 any "
                          "run writes");
  return static_cast<std::size_t>(rows);
}

std::optional<double> maybe(double v) { return std::isnan(v) ? std::nullopt : std::optional<double>(v); }

// "x, y" or "x, y, z" [m].
template <class V>
std::string position_text(const V& p) {
  std::string out;
  for (Eigen::Index c = 0; c < p.size(); ++c) out += (c ? ", " : "") + std::to_string(p[c]);
  return out;
}

// "1e12" for 10^12.
std::string power_of_ten(double x) { return "1e" + std::to_string(static_cast<int>(std::lround(std::log10(x)))); }

// Writes a world state's fields (dynamics/state_fields.h) into a checkpoint: scalars as attributes, arrays as
// datasets of [rows] or [rows, width].
class StateWriter {
 public:
  explicit StateWriter(Group& root) : g_(&root) {}
  template <class T>
  void attribute(const char* name, const T& x) {
    if constexpr (std::is_floating_point_v<T>)
      g_->set_attribute(name, x);
    else
      g_->set_attribute(name, static_cast<std::int64_t>(x));
  }
  void count(const char* name, const char*, const std::uint64_t& x, double) {
    g_->set_attribute(name, static_cast<std::int64_t>(x));
  }
  template <class T>
  void bodies(const char* name, const std::vector<T>& rows) {
    put_rows(name, rows);
  }
  template <class T>
  void bodies_or_none(const char* name, const std::vector<T>& rows) {
    put_rows(name, rows);
  }
  template <class T>
  void rows(const char* name, const std::vector<T>& rows) {
    put_rows(name, rows);
  }
  template <class Value>
  void history(const std::vector<std::pair<contact::PairKey, Value>>& entries) {
    std::vector<std::uint64_t> lo, hi;
    for (const auto& e : entries) {
      lo.push_back(e.first.lo);
      hi.push_back(e.first.hi);
    }
    put(*g_, "lo", lo);
    put(*g_, "hi", hi);
    if constexpr (std::is_same_v<Value, contact::PlanarHistory>) {
      std::vector<double> spring, normal_force;
      for (const auto& e : entries) {
        spring.push_back(e.second.spring);
        normal_force.push_back(e.second.normal_force);
      }
      put(*g_, "spring", spring);
      put(*g_, "normal_force", normal_force);
    } else {
      std::vector<Value> spring;
      for (const auto& e : entries) spring.push_back(e.second);
      put_rows("spring", spring);
    }
  }
  template <class F>
  void group(const char* name, F&& fields) {
    Group sub = g_->create_group(name);
    Group* up = std::exchange(g_, &sub);
    fields();
    g_ = up;
  }
  template <class T, class F>
  void optional_group(const char* name, const std::optional<T>& value, F&& fields) {
    if (!value) return;
    group(name, [&] { fields(*value); });
  }

 private:
  template <class T>
  void put_rows(const char* name, const std::vector<T>& rows) {
    using Row = dynamics::StateRow<T>;
    const std::vector<typename Row::Scalar> flat = dynamics::pack_rows(rows);
    const std::span<const typename Row::Scalar> data(flat);
    if constexpr (Row::width == 1)
      g_->write_dataset<typename Row::Scalar>(name, data);
    else
      g_->write_dataset<typename Row::Scalar>(name, data, Dims{rows.size(), static_cast<std::uint64_t>(Row::width)});
  }
  Group* g_;
};

// Reads a world state's fields from a checkpoint, checking every array's shape (the per-body ones have as many
// rows as `ids`) and every count's range before anything is sized by it. Throws CheckpointError.
class StateReader {
 public:
  StateReader(const Group& root, const fs::path& file) : g_(&root), file_(file) {}
  template <class T>
  void attribute(const char* name, T& x) {
    if constexpr (std::is_floating_point_v<T>)
      x = g_->double_attribute(name);
    else if constexpr (std::is_same_v<T, bool>)
      x = g_->int_attribute(name) != 0;
    else
      x = static_cast<T>(g_->int_attribute(name));
  }
  void count(const char* name, const char* what, std::uint64_t& x, double max) {
    const std::int64_t v = g_->int_attribute(name);
    if (v < 0 || static_cast<double>(v) > max)
      throw CheckpointError("checkpoint " + file_.string() + ": " + what + " " + std::to_string(v) +
                            " is outside [0, " + power_of_ten(max) + "]");
    x = static_cast<std::uint64_t>(v);
  }
  template <class T>
  void bodies(const char* name, std::vector<T>& rows) {
    if (!bodies_) {  // the ids: their count is the number of bodies
      rows = get_rows<T>(name, rows_of(*g_, name));
      bodies_ = rows.size();
    } else {
      rows = get_rows<T>(name, *bodies_);
    }
  }
  template <class T>
  void bodies_or_none(const char* name, std::vector<T>& rows) {
    rows = get_rows<T>(name, rows_of(*g_, name) == 0 ? 0 : bodies_.value_or(0));
  }
  template <class T>
  void rows(const char* name, std::vector<T>& rows) {
    rows = get_rows<T>(name, rows_of(*g_, name));
  }
  template <class Value>
  void history(std::vector<std::pair<contact::PairKey, Value>>& entries) {
    const std::size_t nc = rows_of(*g_, "lo");
    const auto lo = get<std::uint64_t>(*g_, "lo", nc), hi = get<std::uint64_t>(*g_, "hi", nc);
    entries.clear();
    entries.reserve(nc);
    if constexpr (std::is_same_v<Value, contact::PlanarHistory>) {
      const auto spring = get<double>(*g_, "spring", nc);
      // The pairs' last normal forces (absent from checkpoints written before they were kept: NaN, which the
      // contact stage reads as unknown, falling back to the plain velocity prediction for that one step).
      const auto normal_force = g_->exists("normal_force")
                                    ? get<double>(*g_, "normal_force", nc)
                                    : std::vector<double>(nc, std::numeric_limits<double>::quiet_NaN());
      for (std::size_t k = 0; k < nc; ++k)
        entries.push_back({contact::PairKey{lo[k], hi[k]}, {spring[k], normal_force[k]}});
    } else {
      const auto spring = get_rows<Value>("spring", nc);
      for (std::size_t k = 0; k < nc; ++k) entries.push_back({contact::PairKey{lo[k], hi[k]}, spring[k]});
    }
  }
  template <class F>
  void group(const char* name, F&& fields) {
    const Group sub = g_->open_group(name);
    const Group* up = std::exchange(g_, &sub);
    fields();
    g_ = up;
  }
  template <class T, class F>
  void optional_group(const char* name, std::optional<T>& value, F&& fields) {
    value.reset();
    if (!g_->exists(name)) return;
    value.emplace();
    group(name, [&] { fields(*value); });
  }

 private:
  template <class T>
  std::vector<T> get_rows(const char* name, std::size_t rows) {
    using Row = dynamics::StateRow<T>;
    return dynamics::unpack_rows<T>(get<typename Row::Scalar>(*g_, name, rows, Row::width));
  }
  const Group* g_;
  fs::path file_;
  std::optional<std::size_t> bodies_;
};

}  // namespace

namespace {

// The signature of either world: per body its id, motion, (a level floe's thickness,) mass and body-frame vertices.
template <class W>
Fnv body_hash(const W& w) {
  Fnv h;
  h.add(static_cast<std::uint64_t>(w.size()));
  for (const int i : w.id_order()) {
    h.add(w.id(i));
    h.add(static_cast<int>(w.motion(i)));
    if constexpr (std::is_same_v<W, dynamics::World>) h.add(w.thickness(i));
    h.add(w.mass(i));
    for (const auto& v : w.shape(i).vertices())
      for (Eigen::Index c = 0; c < v.size(); ++c) h.add(v[c]);
  }
  return h;
}

}  // namespace

std::string body_signature(const dynamics::World& w) {
  Fnv h = body_hash(w);
  if (const bonds::BondSet* b = w.bonds()) {
    h.add(static_cast<std::uint64_t>(b->faces()));
    h.add(static_cast<std::uint64_t>(b->points()));
  }
  return h.hex();
}

std::string body_signature(const dynamics::SpatialWorld& w) { return body_hash(w).hex(); }

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
    root.set_attribute("format", kFormat);
    root.set_attribute("format_version", kFormatVersion);
    if (c.spatial) root.set_attribute("mode", "spatial");
    root.set_attribute("kind", c.kind);
    root.set_attribute("code_version", c.code_version);
    root.set_attribute("scene_resolved", c.scene_resolved);
    root.set_attribute("body_signature", c.body_signature);
    root.set_attribute("dt", c.dt);
    root.set_attribute("frames", static_cast<std::int64_t>(c.frames));
    root.set_attribute("next_frame", c.next_frame);
    put(root, "frame_times", c.frame_times);
    StateWriter state(root);
    if (c.spatial)
      visit_fields(state, *c.spatial);
    else
      visit_fields(state, c.world);
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

namespace {

// The header of a checkpoint: what it is, its kind, scene and schedule (every count checked before anything is
// sized by it: a checkpoint is input like any other).
void read_header(const Group& root, const fs::path& file, Checkpoint& c) {
  if (!root.has_attribute("format") || root.string_attribute("format") != kFormat)
    throw CheckpointError("checkpoint " + file.string() + ": not a PolyFloe checkpoint (no format = '" +
                          std::string(kFormat) + "' attribute)");
  const std::int64_t version = root.int_attribute("format_version");
  if (version != kFormatVersion)
    throw CheckpointError("checkpoint " + file.string() + ": format version " + std::to_string(version) +
                          "; this program reads version " + std::to_string(kFormatVersion));
  const std::string mode = root.has_attribute("mode") ? root.string_attribute("mode") : "planar";
  if (mode != "planar" && mode != "spatial")
    throw CheckpointError("checkpoint " + file.string() + ": unknown mode '" + mode + "' (planar or spatial)");
  if (mode == "spatial") c.spatial.emplace();
  c.kind = root.string_attribute("kind");
  c.code_version = root.string_attribute("code_version");
  c.scene_resolved = root.string_attribute("scene_resolved");
  c.body_signature = root.string_attribute("body_signature");
  c.dt = root.double_attribute("dt");
  c.next_frame = root.double_attribute("next_frame");
  const std::int64_t frames = root.int_attribute("frames");
  if (frames < 0 || static_cast<double>(frames) > scene::OutputSettings::kMaxFrames)
    throw CheckpointError("checkpoint " + file.string() + ": frame count " + std::to_string(frames) +
                          " is outside [0, " +
                          std::to_string(static_cast<long long>(scene::OutputSettings::kMaxFrames)) + "]");
  c.frames = static_cast<int>(frames);
  c.frame_times = get<double>(root, "frame_times", static_cast<std::size_t>(c.frames));
}

}  // namespace

Checkpoint read_checkpoint(const fs::path& file) {
  std::error_code ec;
  if (!fs::is_regular_file(file, ec)) throw CheckpointError("checkpoint " + file.string() + ": no such file");
  Checkpoint c;
  try {
    const File f(file, File::Mode::read_only);
    const Group& root = f.root();
    read_header(root, file, c);
    StateReader state(root, file);
    if (c.spatial)
      visit_fields(state, *c.spatial);
    else
      visit_fields(state, c.world);
    if (!(c.time() >= 0.0) || !std::isfinite(c.time()))
      throw CheckpointError("checkpoint " + file.string() + ": time " + std::to_string(c.time()) + " s is not a time");
    if (root.exists("channel")) {
      const Group ch = root.open_group("channel");
      ChannelMonitor::State s;
      s.through = get<std::uint8_t>(ch, "through", c.world.ids.size());
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

namespace {

// check_restart for a world whose signature is `sig` and whose kind (planar or spatial) is `spatial`.
void check_restart(const Checkpoint& c, const fs::path& file, const std::string& sig, bool spatial) {
  const std::string where = "checkpoint " + file.string() + ": ";
  if (c.kind == "unstable")
    throw CheckpointError(where +
                          "holds the state at which the run became unstable (for inspection); restart "
                          "from an earlier checkpoint_NNNNNN.h5 in the same folder, with a smaller time step");
  if (c.kind != "frame" && c.kind != "final") throw CheckpointError(where + "unknown kind '" + c.kind + "'");
  if (c.spatial.has_value() != spatial)
    throw CheckpointError(where + "is the checkpoint of a " + (c.spatial ? "spatial" : "planar") +
                          " run; the scene is " + (spatial ? "spatial" : "planar"));
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
        c.frame_times[k] > c.time())
      throw CheckpointError(where + "its frame times are not increasing times up to the checkpoint's " +
                            std::to_string(c.time()) + " s (frame " + std::to_string(k) + ")");
  auto bodies = [&](const auto& state) {
    if (const std::string problem = dynamics::body_row_problem(state, true); !problem.empty())
      throw CheckpointError(where + "holds a body state that is not finite or not one per body (" + problem +
                            "); restart from an earlier checkpoint");
    // Beyond 10^10 m the floes' own extent rounds away against their position: no run gets there.
    for (const auto& p : state.position)
      if (!(p.cwiseAbs().maxCoeff() <= 1e10))
        throw CheckpointError(where + "holds a body at " + position_text(p) + " m, beyond the 1e10 m any run reaches");
  };
  if (c.spatial)
    bodies(*c.spatial);
  else
    bodies(c.world);
}

}  // namespace

void check_restart(const Checkpoint& c, const fs::path& file, const dynamics::World& world) {
  check_restart(c, file, body_signature(world), false);
}

void check_restart(const Checkpoint& c, const fs::path& file, const dynamics::SpatialWorld& world) {
  check_restart(c, file, body_signature(world), true);
}

}  // namespace polyfloe::run
