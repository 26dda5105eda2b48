#include "io/spatial_hdf5_writer.h"

#include <cmath>
#include <cstdint>
#include <vector>

#include "dynamics/spatial_world.h"

namespace polyfloe::io {

using hdf5::Dataset;
using hdf5::Dims;
using hdf5::DType;

namespace {

constexpr std::uint64_t kSeriesChunk = 256;

Dataset series(hdf5::Group& g, const char* name, DType type, const Dims& row, std::uint64_t chunk, const char* units,
               const char* description = nullptr) {
  Dataset s = g.create_series(name, type, row, chunk);
  s.set_attribute("units", units);
  if (description) s.set_attribute("description", description);
  return s;
}

}  // namespace

struct SpatialHdf5Writer::Impl {
  hdf5::File file;
  std::uint64_t bodies = 0;
  int frames = 0;
  Dataset time, position, orientation, velocity, angular_velocity;
  Dataset kinetic_energy, contact_energy, contact_count, linear_momentum, angular_momentum, failures;
  std::vector<double> row3, row4;
  bool swmr = false;

  Impl(const std::filesystem::path& path, const dynamics::SpatialWorld& world, const RunInfo& info)
      : file(path, hdf5::File::Mode::truncate), bodies(world.size()) {
    auto& root = file.root();
    write_run_attributes(root, info);
    root.set_attribute("mode", "spatial");
    const auto n = static_cast<int>(bodies);
    std::vector<std::uint64_t> ids(bodies);
    std::vector<double> mass(bodies), inertia(9 * bodies), verts;
    std::vector<std::int8_t> motion(bodies);
    std::vector<std::int64_t> offsets{0};
    for (int i = 0; i < n; ++i) {
      const auto k = static_cast<std::size_t>(i);
      ids[k] = world.id(i);
      mass[k] = world.mass(i);
      for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 3; ++c) inertia[9 * k + 3 * r + c] = world.body_inertia(i)(r, c);
      motion[k] = static_cast<std::int8_t>(world.motion(i));
      for (const auto& v : world.shape(i).vertices()) verts.insert(verts.end(), {v.x(), v.y(), v.z()});
      offsets.push_back(static_cast<std::int64_t>(verts.size() / 3));
    }
    auto g = root.create_group("bodies");
    g.write_dataset<std::uint64_t>("id", ids).set_attribute("units", "1");
    g.write_dataset<double>("mass", mass).set_attribute("units", "kg");
    g.write_dataset<double>("inertia", inertia, Dims{bodies, 3, 3}).set_attribute("units", "kg m^2");
    g.write_dataset<std::int8_t>("motion", motion).set_attribute("units", "1");
    g.write_dataset<std::int64_t>("vertex_offsets", offsets).set_attribute("units", "1");
    g.write_dataset<double>("vertices", verts, Dims{verts.size() / 3, 3}).set_attribute("units", "m");
    time = series(root, "time", DType::f64, {}, kSeriesChunk, "s");
    auto state = root.create_group("state");
    position = series(state, "position", DType::f64, {bodies, 3}, 1, "m", "centre of mass");
    orientation = series(state, "orientation", DType::f64, {bodies, 4}, 1, "1", "unit quaternion (w, x, y, z)");
    velocity = series(state, "velocity", DType::f64, {bodies, 3}, 1, "m/s");
    angular_velocity = series(state, "angular_velocity", DType::f64, {bodies, 3}, 1, "rad/s", "world frame");
    auto diag = root.create_group("diagnostics");
    kinetic_energy = series(diag, "kinetic_energy", DType::f64, {}, kSeriesChunk, "J");
    contact_energy = series(diag, "contact_energy", DType::f64, {}, kSeriesChunk, "J", "2/5 k_n d^2.5 summed");
    contact_count = series(diag, "contact_count", DType::i64, {}, kSeriesChunk, "1");
    linear_momentum = series(diag, "linear_momentum", DType::f64, {3}, kSeriesChunk, "kg m/s");
    angular_momentum = series(diag, "angular_momentum", DType::f64, {3}, kSeriesChunk, "kg m^2/s", "about the origin");
    failures = series(diag, "narrow_phase_failures", DType::i64, {}, kSeriesChunk, "1",
                      "queries the chosen narrow phase failed and sat answered (cumulative)");
    file.flush();
  }

  void start_swmr() {
    if (swmr) return;
    file.flush();
    file.start_swmr_write();
    swmr = true;
  }

  void write_frame(const dynamics::SpatialWorld& w) {
    start_swmr();
    if (w.size() != bodies) throw IoError(file.path().string() + ": the number of bodies changed");
    const double t = w.time();
    time.append_rows<double>({&t, 1}, 1);
    auto put3 = [&](Dataset& d, auto get) {
      row3.assign(3 * bodies, 0.0);
      for (std::size_t k = 0; k < bodies; ++k) {
        const geometry::Vec3 v = get(static_cast<int>(k));
        for (int c = 0; c < 3; ++c) row3[3 * k + c] = v[c];
      }
      d.append_rows<double>(row3, 1);
    };
    put3(position, [&](int i) { return w.position(i); });
    put3(velocity, [&](int i) { return w.velocity(i); });
    put3(angular_velocity, [&](int i) { return w.angular_velocity(i); });
    row4.assign(4 * bodies, 0.0);
    for (std::size_t k = 0; k < bodies; ++k) {
      const auto& q = w.orientation(static_cast<int>(k));
      row4[4 * k] = q.w();
      row4[4 * k + 1] = q.x();
      row4[4 * k + 2] = q.y();
      row4[4 * k + 3] = q.z();
    }
    orientation.append_rows<double>(row4, 1);
    const double ke = w.kinetic_energy(), ce = w.contact_energy();
    kinetic_energy.append_rows<double>({&ke, 1}, 1);
    contact_energy.append_rows<double>({&ce, 1}, 1);
    const auto count = static_cast<std::int64_t>(w.contacts().size());
    contact_count.append_rows<std::int64_t>({&count, 1}, 1);
    const geometry::Vec3 p = w.linear_momentum(), l = w.angular_momentum();
    linear_momentum.append_rows<double>({p.data(), 3}, 1);
    angular_momentum.append_rows<double>({l.data(), 3}, 1);
    const auto f = static_cast<std::int64_t>(w.narrow_phase_stats().primary_failures);
    failures.append_rows<std::int64_t>({&f, 1}, 1);
    file.flush();
    ++frames;
  }
};

SpatialHdf5Writer::SpatialHdf5Writer(const std::filesystem::path& file, const dynamics::SpatialWorld& world,
                                     const RunInfo& info)
    : impl_(std::make_unique<Impl>(file, world, info)) {}
SpatialHdf5Writer::~SpatialHdf5Writer() = default;
void SpatialHdf5Writer::write_frame(const dynamics::SpatialWorld& world) { impl_->write_frame(world); }
int SpatialHdf5Writer::frames() const { return impl_->frames; }
void SpatialHdf5Writer::flush() { impl_->file.flush(); }
void SpatialHdf5Writer::start_swmr() { impl_->start_swmr(); }

void SpatialHdf5Writer::adopt_frames(const std::filesystem::path& previous, int frames) {
  if (impl_->frames != 0) throw IoError(impl_->file.path().string() + ": frames can only be adopted into a new file");
  const hdf5::File old(previous, hdf5::File::Mode::read_only);
  impl_->file.root().append_series_rows_from(old.root(), static_cast<std::uint64_t>(frames));
  impl_->frames = frames;
  impl_->file.flush();
}

}  // namespace polyfloe::io
