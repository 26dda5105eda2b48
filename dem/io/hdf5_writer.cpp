#include "io/hdf5_writer.h"

#include <algorithm>
#include <cmath>
#include <optional>
#include <sstream>
#include <string>
#include <system_error>
#include <vector>

#include "formats/atomic_file.h"

#include "dynamics/world.h"
#include "formats/hdf5_file.h"
#include "io/xdmf_frames.h"

namespace polyfloe::io {

using hdf5::Dataset;
using hdf5::Dims;
using hdf5::DType;
using hdf5::units;

namespace {

constexpr std::uint64_t kSeriesChunk = 256;  // rows per chunk of the 1-D and small series

// Creates the file's folder if needed; returns the path unchanged.
const std::filesystem::path& with_parent_folder(const std::filesystem::path& path) {
  std::error_code ec;
  if (!path.parent_path().empty()) std::filesystem::create_directories(path.parent_path(), ec);
  if (ec) throw IoError("cannot create the folder of " + path.string() + ": " + ec.message());
  return path;
}

}  // namespace

void write_run_attributes(hdf5::Group& root, const RunInfo& info) {
  root.set_attribute("created_by", "PolyFloe");
  root.set_attribute("code_version", info.version);
  root.set_attribute("scene_path", info.scene_path);
  root.set_attribute("scene_text", info.scene_text);
  root.set_attribute("overrides", info.overrides);
  root.set_attribute("dt", info.dt);
}

struct Hdf5Writer::Impl {
  hdf5::File file;
  std::uint64_t bodies = 0;
  std::vector<dynamics::BodyId> ids;
  std::vector<double> centre_z;  // height of each body's centre of mass: h/2 - draft [m]
  int frames = 0;
  Dataset time;
  hdf5::Group diagnostics;
  Dataset position, orientation, velocity, angular_velocity;
  Dataset vertices_xy;                // [T, V, 2] float32: the polygons where they are (for results.xmf)
  std::vector<double> body_xy;        // body-frame vertices, as floes/polygon_xy
  std::vector<std::int64_t> offsets;  // as floes/polygon_offsets
  std::optional<XdmfFrames> xdmf;     // results.xmf and the files of its frames
  std::vector<float> row_xy;
  Dataset kinetic_energy, contact_count, max_speed, mean_speed, max_overlap_depth, linear_momentum, angular_momentum;
  std::vector<Dataset> extra;
  // loads on walls and plates
  std::vector<std::uint64_t> boundary;  // ids of the fixed and kinematic bodies, increasing
  Dataset boundary_force;
  // bonds (a World with a BondSet)
  Dataset intact_faces, intact_points, face_intact, point_intact, max_tension, max_shear;
  std::vector<std::uint8_t> flags;
  // scratch rows
  std::vector<double> row3, row4;

  Impl(const std::filesystem::path& path, const dynamics::World& world, const RunInfo& info, double water_density,
       const std::vector<ExtraSeries>& extra_series)
      : file(with_parent_folder(path), hdf5::File::Mode::truncate), bodies(world.size()) {
    if (!(water_density > 0.0) || !std::isfinite(water_density)) {
      throw IoError("HDF5 output " + path.string() + ": water density must be positive");
    }
    auto& root = file.root();
    write_run_attributes(root, info);
    root.set_attribute("water_density", water_density);
    write_floes(root, world, water_density);
    create_state_series(root);
    create_boundary_series(world);
    if (const bonds::BondSet* b = world.bonds()) create_bond_series(root, *b);
    create_extra_series(extra_series);
    file.flush();
  }

  // A series (one row per frame) with its units and description.
  static Dataset series(hdf5::Group& g, const char* name, DType type, const Dims& row, std::uint64_t chunk,
                        const char* u, const char* description = nullptr) {
    Dataset s = g.create_series(name, type, row, chunk);
    units(s, u, description);
    return s;
  }

  // floes/: what does not change (ids, thickness, mass, inertia, motion, the body-frame polygons, the XDMF
  // topology), and the per-body data the frames need.
  void write_floes(hdf5::Group& root, const dynamics::World& world, double water_density) {
    ids.resize(bodies);
    centre_z.resize(bodies);
    std::vector<double> thickness(bodies), mass(bodies), inertia(bodies), xy;
    std::vector<std::int8_t> motion(bodies);
    offsets.assign(1, 0);
    const std::span<const int> order = world.id_order();  // every per-body row in id order
    for (std::size_t k = 0; k < bodies; ++k) {
      const int i = order[k];
      ids[k] = world.id(i);
      thickness[k] = world.thickness(i);
      mass[k] = world.mass(i);
      inertia[k] = world.inertia(i);
      motion[k] = static_cast<std::int8_t>(world.motion(i));
      const auto& shape = world.shape(i);
      for (const auto& v : shape.vertices()) {
        xy.push_back(v.x());
        xy.push_back(v.y());
      }
      offsets.push_back(offsets.back() + shape.size());
      const double volume = shape.area() * thickness[k];             // [m^3]
      const double density = volume > 0.0 ? mass[k] / volume : 0.0;  // [kg/m^3]
      double draft = thickness[k] * density / water_density;         // [m]
      if (!std::isfinite(draft)) draft = 0.0;
      centre_z[k] = 0.5 * thickness[k] - draft;
    }
    auto floes = root.create_group("floes");
    auto d = floes.write_dataset<std::uint64_t>("id", ids);
    units(d, "1", "stable body id");
    d = floes.write_dataset<double>("thickness", thickness);
    units(d, "m");
    d = floes.write_dataset<double>("mass", mass);
    units(d, "kg");
    d = floes.write_dataset<double>("inertia", inertia);
    units(d, "kg m^2", "moment of inertia about the vertical axis through the centre of mass");
    d = floes.write_dataset<std::int8_t>("motion", motion);
    units(d, "1", "0 dynamic, 1 fixed, 2 kinematic");
    d = floes.write_dataset<std::int64_t>("polygon_offsets", offsets);
    units(d, "1", "body i has the vertex rows polygon_offsets[i] .. polygon_offsets[i+1]-1 of polygon_xy");
    d = floes.write_dataset<double>("polygon_xy", xy, Dims{xy.size() / 2, 2});
    units(d, "m", "body-frame vertices (centre of mass at the origin), counter-clockwise");
    // XDMF's mixed topology: per body 3 (polygon), its vertex count, its rows of state/vertices_xy.
    std::vector<std::int64_t> topology;
    for (std::size_t k = 0; k < bodies; ++k) {
      topology.push_back(3);
      topology.push_back(offsets[k + 1] - offsets[k]);
      for (std::int64_t v = offsets[k]; v < offsets[k + 1]; ++v) topology.push_back(v);
    }
    xdmf.emplace(XdmfFrames::Bodies{ids, std::move(thickness), std::move(motion), std::move(topology), xy.size() / 2});
    body_xy = std::move(xy);
  }

  // time, state/ and diagnostics/ series.
  void create_state_series(hdf5::Group& root) {
    time = series(root, "time", DType::f64, {}, kSeriesChunk, "s");
    auto state = root.create_group("state");
    position =
        series(state, "position", DType::f64, {bodies, 3}, 1, "m", "centre of mass (x, y, z); z = thickness/2 - draft");
    orientation =
        series(state, "orientation", DType::f64, {bodies, 4}, 1, "1", "unit quaternion (w, x, y, z) of the body frame");
    velocity = series(state, "velocity", DType::f64, {bodies, 3}, 1, "m/s");
    angular_velocity = series(state, "angular_velocity", DType::f64, {bodies, 3}, 1, "rad/s");
    vertices_xy = series(state, "vertices_xy", DType::f32, {body_xy.size() / 2, 2}, 1, "m",
                         "every body's polygon where it is (rows as floes/polygon_xy), single precision: for "
                         "viewing (results.xmf)");
    diagnostics = root.create_group("diagnostics");
    auto& diag = diagnostics;
    kinetic_energy =
        series(diag, "kinetic_energy", DType::f64, {}, kSeriesChunk, "J", "dynamic bodies, translation + rotation");
    contact_count = series(diag, "contact_count", DType::i64, {}, kSeriesChunk, "1");
    max_speed = series(diag, "max_speed", DType::f64, {}, kSeriesChunk, "m/s", "over dynamic bodies");
    mean_speed = series(diag, "mean_speed", DType::f64, {}, kSeriesChunk, "m/s", "over dynamic bodies");
    max_overlap_depth = series(diag, "max_overlap_depth", DType::f64, {}, kSeriesChunk, "m");
    linear_momentum = series(diag, "linear_momentum", DType::f64, {2}, kSeriesChunk, "kg m/s", "dynamic bodies");
    angular_momentum =
        series(diag, "angular_momentum", DType::f64, {}, kSeriesChunk, "kg m^2/s", "dynamic bodies, about the origin");
  }

  // The force on each fixed or kinematic body (walls, plates), where there are any.
  void create_boundary_series(const dynamics::World& world) {
    auto& diag = diagnostics;
    for (const int i : world.id_order())
      if (world.motion(i) != dynamics::Motion::dynamic) boundary.push_back(world.id(i));
    if (!boundary.empty()) {
      units(diag.write_dataset<std::uint64_t>("boundary_ids", boundary), "1",
            "ids of the fixed and kinematic bodies (walls, plates), in the order of boundary_force");
      boundary_force = series(diag, "boundary_force", DType::f64, {boundary.size(), 2}, kSeriesChunk, "N",
                              "force of the ice (contacts, bonds) on each fixed or kinematic body");
    }
  }

  // bonds/: the material, the faces as frozen, and the series of what holds.
  void create_bond_series(hdf5::Group& root, const bonds::BondSet& b) {
    auto g = root.create_group("bonds");
    const bonds::BondMaterial& m = b.material();
    g.set_attribute("points_per_face", static_cast<std::int64_t>(m.points_per_face));
    g.set_attribute("tensile_strength", m.tensile_strength);
    g.set_attribute("shear_strength", m.shear_strength);
    g.set_attribute("friction_angle", m.friction_angle);
    g.set_attribute("damping_ratio", m.damping_ratio);
    g.set_attribute("youngs_modulus", m.youngs_modulus);
    g.set_attribute("poisson_ratio", m.poisson_ratio);
    const std::size_t nf = b.faces();
    std::vector<std::uint64_t> ia(nf), ib(nf);
    std::vector<double> len(nf), normal(2 * nf), mid(2 * nf);
    for (std::size_t f = 0; f < nf; ++f) {
      ia[f] = b.face_id_a(f);
      ib[f] = b.face_id_b(f);
      len[f] = b.face_length(f);
      normal[2 * f] = b.face_normal0(f).x();
      normal[2 * f + 1] = b.face_normal0(f).y();
      mid[2 * f] = b.face_midpoint0(f).x();
      mid[2 * f + 1] = b.face_midpoint0(f).y();
    }
    units(g.write_dataset<std::uint64_t>("face_id_a", ia), "1", "body id of each face's first element");
    units(g.write_dataset<std::uint64_t>("face_id_b", ib), "1", "body id of each face's second element");
    units(g.write_dataset<double>("face_length", len), "m");
    units(g.write_dataset<double>("face_normal", normal, Dims{nf, 2}), "1",
          "unit normal from element a to b when frozen");
    units(g.write_dataset<double>("face_midpoint", mid, Dims{nf, 2}), "m", "midpoint of the face when frozen");
    intact_faces = series(g, "intact_faces", DType::i64, {}, kSeriesChunk, "1");
    intact_points = series(g, "intact_points", DType::i64, {}, kSeriesChunk, "1");
    max_tension = series(g, "max_tensile_stress", DType::f64, {}, kSeriesChunk, "Pa",
                         "largest normal (tensile) stress over intact bond points");
    max_shear = series(g, "max_shear_stress", DType::f64, {}, kSeriesChunk, "Pa",
                       "largest |shear stress| over intact bond points");
    face_intact = g.create_series("face_intact", DType::u8, {nf}, 1, 1);
    units(face_intact, "1", "[frame, face] 1 while the face holds");
    point_intact = g.create_series("point_intact", DType::u8, {b.points()}, 1, 1);
    units(point_intact, "1",
          "[frame, point] 1 while the bond point holds; face f has points_per_face points from "
          "f x points_per_face");
  }

  // The driver's own series (the channel monitor's), in diagnostics/<group>/.
  void create_extra_series(const std::vector<ExtraSeries>& extra_series) {
    std::vector<std::pair<std::string, hdf5::Group>> groups;
    for (const ExtraSeries& e : extra_series) {
      auto it = std::find_if(groups.begin(), groups.end(), [&](const auto& g) { return g.first == e.group; });
      if (it == groups.end()) {
        groups.emplace_back(e.group, diagnostics.create_group(e.group));
        it = groups.end() - 1;
      }
      extra.push_back(
          series(it->second, e.name.c_str(), DType::f64, {}, kSeriesChunk, e.units.c_str(), e.description.c_str()));
    }
  }

  bool swmr = false;
  void start_swmr() {
    if (swmr) return;
    file.flush();
    file.start_swmr_write();
    swmr = true;
  }

  void write_frame(const dynamics::World& world, std::span<const double> extra_values) {
    start_swmr();  // every object exists by the first frame (the driver's series too)
    check_frame(world, extra_values);
    const double t = world.time();
    time.append_rows<double>({&t, 1}, 1);
    append_state(world);
    append_diagnostics(world, extra_values);
    if (const bonds::BondSet* b = world.bonds()) append_bonds(*b);
    ++frames;
    file.flush();
  }

  // The world is the one the file was started with (bodies, ids), and the driver gives a value per extra series.
  void check_frame(const dynamics::World& world, std::span<const double> extra_values) const {
    if (extra_values.size() != extra.size())
      throw IoError(file.path().string() + ": " + std::to_string(extra_values.size()) + " extra values for " +
                    std::to_string(extra.size()) + " extra series");
    if (world.size() != bodies) {
      throw IoError(file.path().string() + ": the world has " + std::to_string(world.size()) +
                    " bodies, the file was started with " + std::to_string(bodies));
    }
    const std::span<const int> order = world.id_order();
    for (std::size_t k = 0; k < bodies; ++k) {
      if (world.id(order[k]) != ids[k]) {
        throw IoError(file.path().string() + ": the world's body " + std::to_string(k) + " in id order has id " +
                      std::to_string(world.id(order[k])) + ", the file was started with " + std::to_string(ids[k]));
      }
    }
  }

  // state/: positions, orientations, velocities and the polygons where they are.
  // (row k: the body k-th in id order)
  void append_state(const dynamics::World& world) {
    const std::span<const int> order = world.id_order();
    auto at = [&order](auto span, std::size_t k) { return span[static_cast<std::size_t>(order[k])]; };
    const auto pos = world.positions();
    const auto yaw = world.yaws();
    const auto vel = world.velocities();
    const auto omega = world.angular_velocities();
    row3.assign(3 * bodies, 0.0);
    for (std::size_t k = 0; k < bodies; ++k) {
      row3[3 * k] = at(pos, k).x();
      row3[3 * k + 1] = at(pos, k).y();
      row3[3 * k + 2] = centre_z[k];
    }
    position.append_rows<double>(row3, 1);
    row4.assign(4 * bodies, 0.0);
    for (std::size_t k = 0; k < bodies; ++k) {
      row4[4 * k] = std::cos(0.5 * at(yaw, k));
      row4[4 * k + 3] = std::sin(0.5 * at(yaw, k));
    }
    orientation.append_rows<double>(row4, 1);
    for (std::size_t k = 0; k < bodies; ++k) {
      row3[3 * k] = at(vel, k).x();
      row3[3 * k + 1] = at(vel, k).y();
      row3[3 * k + 2] = 0.0;
    }
    velocity.append_rows<double>(row3, 1);
    for (std::size_t k = 0; k < bodies; ++k) {
      row3[3 * k] = 0.0;
      row3[3 * k + 1] = 0.0;
      row3[3 * k + 2] = at(omega, k);
    }
    angular_velocity.append_rows<double>(row3, 1);
    row_xy.resize(body_xy.size());
    for (std::size_t k = 0; k < bodies; ++k) {
      const geometry::Vec2 p = at(pos, k);
      const double c = std::cos(at(yaw, k)), sn = std::sin(at(yaw, k));
      for (auto v = static_cast<std::size_t>(offsets[k]); v < static_cast<std::size_t>(offsets[k + 1]); ++v) {
        const double bx = body_xy[2 * v], by = body_xy[2 * v + 1];
        row_xy[2 * v] = static_cast<float>(p.x() + c * bx - sn * by);
        row_xy[2 * v + 1] = static_cast<float>(p.y() + sn * bx + c * by);
      }
    }
    vertices_xy.append_rows<float>(row_xy, 1);
  }

  // diagnostics/: speeds, deepest overlap, contacts, energy, momenta, the driver's series, the boundary forces.
  void append_diagnostics(const dynamics::World& world, std::span<const double> extra_values) {
    const auto vel = world.velocities();
    double speed_max = 0.0, speed_sum = 0.0;
    std::size_t dynamic = 0;
    for (const int i : world.id_order()) {
      if (world.motion(i) != dynamics::Motion::dynamic) continue;
      const double s = vel[static_cast<std::size_t>(i)].norm();
      speed_max = std::max(speed_max, s);
      speed_sum += s;
      ++dynamic;
    }
    const double speed_mean = dynamic > 0 ? speed_sum / static_cast<double>(dynamic) : 0.0;
    double depth_max = 0.0;
    for (const auto& c : world.contacts()) depth_max = std::max(depth_max, c.geometry.depth);
    const auto contacts = static_cast<std::int64_t>(world.contacts().size());
    const double ke = world.kinetic_energy();
    const auto p = world.linear_momentum();
    const double p2[2] = {p.x(), p.y()};
    const double l = world.angular_momentum();

    kinetic_energy.append_rows<double>({&ke, 1}, 1);
    contact_count.append_rows<std::int64_t>({&contacts, 1}, 1);
    max_speed.append_rows<double>({&speed_max, 1}, 1);
    mean_speed.append_rows<double>({&speed_mean, 1}, 1);
    max_overlap_depth.append_rows<double>({&depth_max, 1}, 1);
    linear_momentum.append_rows<double>(p2, 1);
    angular_momentum.append_rows<double>({&l, 1}, 1);
    for (std::size_t k = 0; k < extra.size(); ++k) extra[k].append_rows<double>({&extra_values[k], 1}, 1);
    if (!boundary.empty()) {
      row3.clear();
      for (const std::uint64_t id : boundary) {
        const geometry::Vec2& f = world.forces()[static_cast<std::size_t>(world.index_of(id))];
        row3.push_back(f.x());
        row3.push_back(f.y());
      }
      boundary_force.append_rows<double>(row3, 1);
    }
  }

  // bonds/: what holds.
  void append_bonds(const bonds::BondSet& b) {
    const auto nfaces = static_cast<std::int64_t>(b.intact_faces());
    const auto npoints = static_cast<std::int64_t>(b.intact_points());
    intact_faces.append_rows<std::int64_t>({&nfaces, 1}, 1);
    intact_points.append_rows<std::int64_t>({&npoints, 1}, 1);
    const double st = b.max_sigma(), ss = b.max_tau();
    max_tension.append_rows<double>({&st, 1}, 1);
    max_shear.append_rows<double>({&ss, 1}, 1);
    flags.resize(b.faces());
    for (std::size_t f = 0; f < b.faces(); ++f) flags[f] = b.face_intact(f) ? 1 : 0;
    face_intact.append_rows<std::uint8_t>(flags, 1);
    flags.resize(b.points());
    for (std::size_t q = 0; q < b.points(); ++q) flags[q] = b.point_intact(q) ? 1 : 0;
    point_intact.append_rows<std::uint8_t>(flags, 1);
  }
};

Hdf5Writer::Hdf5Writer(const std::filesystem::path& file, const dynamics::World& world, const RunInfo& info,
                       double water_density, const std::vector<ExtraSeries>& extra)
    : impl_(std::make_unique<Impl>(file, world, info, water_density, extra)) {}

Hdf5Writer::~Hdf5Writer() = default;
Hdf5Writer::Hdf5Writer(Hdf5Writer&&) noexcept = default;
Hdf5Writer& Hdf5Writer::operator=(Hdf5Writer&&) noexcept = default;

hdf5::Group& Hdf5Writer::diagnostics() { return impl_->diagnostics; }

void Hdf5Writer::write_frame(const dynamics::World& world, std::span<const double> extra) {
  impl_->write_frame(world, extra);
}
void Hdf5Writer::adopt_frames(const std::filesystem::path& previous, int frames) {
  if (impl_->frames != 0) throw IoError(path().string() + ": frames can only be adopted into a new file");
  const hdf5::File old(previous, hdf5::File::Mode::read_only);
  impl_->file.root().append_series_rows_from(old.root(), static_cast<std::uint64_t>(frames));
  impl_->frames = frames;
  impl_->xdmf->adopt(frames);
  impl_->file.flush();
}

void Hdf5Writer::write_xdmf(const std::filesystem::path& xmf, OutputManifest* manifest) {
  impl_->file.flush();
  impl_->xdmf->write(impl_->file.root(), impl_->file.path().filename().string(), xmf, manifest);
}

void Hdf5Writer::start_swmr() { impl_->start_swmr(); }
void Hdf5Writer::flush() { impl_->file.flush(); }
int Hdf5Writer::frames() const { return impl_->frames; }
const std::filesystem::path& Hdf5Writer::path() const { return impl_->file.path(); }

}  // namespace polyfloe::io
