// Scene -> World: explicit bodies first (their own ids, or the next free ones in order), then the channel walls, the
// ice sheet (cells touching each other, clear of the bodies above), then the generated floe field, which keeps clear
// of all of them.
#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <memory>
#include <optional>
#include <sstream>
#include <utility>
#include <vector>

#include "contact/broad_phase.h"
#include "forcing/drift.h"
#include "forcing/gridded_field.h"
#include "geometry/space_order.h"
#include "scene/body_ids.h"
#include "scene/channel.h"
#include "scene/field_statistics.h"
#include "scene/floe_field.h"
#include "scene/ice_sheet.h"
#include "scene/scene.h"

namespace polyfloe::scene {

namespace {

using dynamics::BodyDesc;
using dynamics::BodyId;
using dynamics::Motion;

// A body placed before the floe field, for the initial-overlap checks and as an obstacle for the generator.
struct PlacedBody {
  std::string source;          // "channel.yaml:20:5 (floes.1)" for messages
  std::vector<Vec2> vertices;  // world frame, counter-clockwise [m]
  geometry::Aabb box;          // [m]
  bool dynamic = false;
};

PlacedBody placed(std::string source, const geometry::ConvexPolygon& shape, const Vec2& position, double yaw,
                  bool dynamic) {
  PlacedBody p{std::move(source), {}, {}, dynamic};
  const double c = std::cos(yaw), s = std::sin(yaw);
  for (const Vec2& v : shape.vertices()) p.vertices.push_back(position + geometry::rotate(v, c, s));
  p.box.lo = p.box.hi = p.vertices.front();
  for (const Vec2& v : p.vertices) {
    p.box.lo = p.box.lo.cwiseMin(v);
    p.box.hi = p.box.hi.cwiseMax(v);
  }
  return p;
}

// True when the interiors overlap by more than round-off (touching edges are fine).
bool overlapping(const PlacedBody& a, const PlacedBody& b) {
  if (!a.box.overlaps(b.box)) return false;
  const double scale = std::max((a.box.hi - a.box.lo).maxCoeff(), (b.box.hi - b.box.lo).maxCoeff());
  return polygon_separation(a.vertices, b.vertices) < -1e-9 * scale;
}

// The overlapping pair (a < b) among bodies[0, end) that `counts(a, b)` accepts with the smallest (b, a): the pair a
// check in list order would report first. Candidates come from the broad phase's grid, so the check stays
// O(N log N) for any number of bodies; pairs of two fixed bodies are not candidates.
template <class Counts>
std::optional<std::pair<std::size_t, std::size_t>> first_overlap(const std::vector<PlacedBody>& bodies, std::size_t end,
                                                                 Counts counts) {
  std::vector<geometry::Aabb> boxes(end);
  std::vector<std::uint8_t> dynamic(end);
  for (std::size_t i = 0; i < end; ++i) {
    boxes[i] = bodies[i].box;
    dynamic[i] = bodies[i].dynamic ? 1 : 0;
  }
  std::vector<contact::CandidatePair> pairs;
  contact::GridBroadPhase grid;
  grid.find_pairs(boxes, dynamic, pairs);
  std::optional<std::pair<std::size_t, std::size_t>> first;
  for (const contact::CandidatePair& c : pairs) {
    const auto a = static_cast<std::size_t>(std::min(c.a, c.b)), b = static_cast<std::size_t>(std::max(c.a, c.b));
    if (first && std::make_pair(b, a) >= std::make_pair(first->second, first->first)) continue;
    if (counts(a, b) && overlapping(bodies[a], bodies[b])) first = std::make_pair(a, b);
  }
  return first;
}

std::string body_source(const BodySpec& b, std::size_t i) {
  const std::string name = "floes." + std::to_string(i);
  return b.source.where.empty() ? name : b.source.where + " (" + name + ")";
}

void add_checked(dynamics::World& world, const BodyDesc& desc, const std::string& source) {
  try {
    world.add_body(desc);
  } catch (const std::invalid_argument& e) {
    throw SceneError(source + ": " + e.what());
  }
}

}  // namespace

double reference_speed(const Scene& scene) {
  if (scene.time.reference_speed) return *scene.time.reference_speed;
  if (scene.spatial) {   // the fastest body at t = 0 (set run.reference_speed when gravity speeds bodies up)
    double speed = 1.0;  // [m/s]
    for (const SpatialBodySpec& b : scene.spatial->bodies) speed = std::max(speed, b.velocity.norm());
    return speed;
  }
  // The fastest of the current, and the skin/air free drift, at t = 0 at the explicit bodies and over the floe
  // field's region (5 x 5 points): impacts rarely exceed the speed floes drift at.
  const forcing::DriftSettings& d = scene.world.drift;
  std::vector<Vec2> where;
  for (const BodySpec& b : scene.bodies) where.push_back(b.position);
  auto sample_region = [&](const Vec2& lo, const Vec2& hi) {
    for (int i = 0; i < 5; ++i)
      for (int j = 0; j < 5; ++j) where.push_back(lo + (hi - lo).cwiseProduct(Vec2(i / 4.0, j / 4.0)));
  };
  if (const auto& f = scene.floe_field) sample_region(f->region_min, f->region_max);
  if (const auto& sh = scene.ice_sheet) sample_region(sh->region_min, sh->region_max);
  if (where.empty()) where.emplace_back(0.0, 0.0);
  double speed = 1.0;  // [m/s]
  for (const Vec2& p : where) {
    try {
      const Vec2 current = d.ocean ? d.ocean->at({p.x(), p.y(), 0.0}, 0.0) : Vec2{0.0, 0.0};
      const Vec2 wind = d.wind ? d.wind->at({p.x(), p.y(), 0.0}, 0.0) : Vec2{0.0, 0.0};
      const double v = std::max(current.norm(), forcing::free_drift_velocity(d, current, wind).norm());
      if (std::isfinite(v)) speed = std::max(speed, v);
    } catch (const forcing::FieldError&) {
      // outside the field's domain: that point does not count
    }
  }
  return speed;
}

double bond_time_step(const dynamics::World& world) {
  const bonds::BondSet* b = world.bonds();
  if (!b) return std::numeric_limits<double>::infinity();
  std::vector<double> mass(world.size()), inertia(world.size());
  for (std::size_t i = 0; i < world.size(); ++i) {
    const int k = static_cast<int>(i);
    mass[i] = world.motion(k) == Motion::dynamic ? world.mass(k) : std::numeric_limits<double>::infinity();
    inertia[i] = world.inertia(k);
  }
  return kBondStepFraction * b->critical_time_step(mass, inertia);
}

void check_run_length(const Scene& scene, double dt) {
  // The step counter is an integer; beyond this a run could not finish anyway (a microsecond per step is 11 days).
  const double steps = std::ceil(scene.time.duration / dt);
  if (!(steps <= kMaxSteps)) {
    std::ostringstream msg;
    msg << scene.source_path << ": run.duration " << scene.time.duration << " s at the time step " << dt << " s"
        << (scene.time.dt ? " (run.dt)" : " (automatic)") << " is " << steps << " steps, more than the " << kMaxSteps
        << " a run may take; shorten run.duration" << (scene.time.dt ? " or raise run.dt" : "");
    throw SceneError(msg.str());
  }
  // A frame at most every step (FrameClock): the frames are those of the interval or of the steps, whichever are
  // fewer.
  const double frames = std::min(std::floor(scene.time.duration / scene.output.interval), steps) + 1.0;
  if ((scene.output.vtk || scene.output.hdf5) && !(frames <= OutputSettings::kMaxFrames)) {
    std::ostringstream msg;
    msg << scene.source_path << ": output.interval " << scene.output.interval << " s over run.duration "
        << scene.time.duration << " s is " << frames << " frames, each a file per series (at most "
        << OutputSettings::kMaxFrames << "); raise output.interval";
    throw SceneError(msg.str());
  }
}

double time_step(const Scene& scene, const dynamics::World& world) {
  double dt = 0.0;
  if (scene.time.dt) {
    dt = *scene.time.dt;
  } else {
    // The Hertz contacts at the reference speed and (foundation model) the flat faces, each by its own steps.
    const double hertz = world.shortest_hertz_contact_duration(reference_speed(scene));  // [s]
    const double flat = world.shortest_flat_contact_duration();                          // [s], infinite: none
    const double duration = std::min(hertz, flat);
    if (!(duration > 0.0) || !std::isfinite(duration))
      throw SceneError(scene.source_path + ": cannot choose an automatic time step (shortest contact duration " +
                       std::to_string(duration) + " s); set run.dt");
    const double flat_steps = scene.time.steps_per_flat_contact.value_or(scene.time.steps_per_contact);
    dt = std::min({hertz / scene.time.steps_per_contact, flat / flat_steps, bond_time_step(world)});
  }
  check_run_length(scene, dt);
  return dt;
}

namespace {

// A floe that starts where a field file has no water (no_water: error) would stop the run at its first step:
// say so now, before any output. Only the side-face samples are checked: they surround the bottom's.
void check_bodies_in_water(const dynamics::World& world) {
  const forcing::DriftSettings& d = world.settings().drift;
  if (!d.ocean || d.ocean->uniform_in_space() || !(d.form_drag || d.moment_drag || d.skin_drag)) return;
  std::vector<forcing::Vec3> points;
  std::vector<Vec2> water;
  for (int i = 0; i < static_cast<int>(world.size()); ++i) {
    if (world.motion(i) != dynamics::Motion::dynamic) continue;
    const std::span<const Vec2> v = world.world_vertices(i);
    points.resize(v.size());
    water.resize(v.size());
    forcing::side_sample_points(v, world.draft(i), points);
    try {
      d.ocean->sample(0.0, points, water);
    } catch (const forcing::FieldError& e) {
      throw SceneError("body " + std::to_string(world.id(i)) +
                       " starts where the ocean field has no water: " + e.what());
    }
  }
}

// The World as it is built, part by part, with what the parts placed so far (for the overlap checks and the floe
// field's obstacles) and the next free id.
class WorldBuilder {
 public:
  explicit WorldBuilder(const Scene& scene) : scene_(scene), world_(settings_of(scene)) {}

  // Explicit bodies: their own ids, or the next free ones in list order.
  void add_bodies() {
    std::vector<std::optional<std::uint64_t>> given;
    for (const BodySpec& b : scene_.bodies) given.push_back(b.id);
    const std::vector<BodyId> ids =
        detail::assign_ids(given, [&](std::size_t i) { return body_source(scene_.bodies[i], i); });
    for (BodyId id : ids) next_ = std::max(next_, id + 1);
    for (std::size_t i = 0; i < scene_.bodies.size(); ++i) {
      const BodySpec& b = scene_.bodies[i];
      const std::string source = body_source(b, i);
      std::shared_ptr<const geometry::ConvexPolygon> shape;
      try {
        shape = std::make_shared<const geometry::ConvexPolygon>(geometry::ConvexPolygon::from_vertices(b.polygon));
      } catch (const geometry::GeometryError& e) {
        throw SceneError(source + ": polygon: " + e.what());
      }
      const bool dynamic = b.motion == Motion::dynamic;
      if (dynamic) max_thickness_ = std::max(max_thickness_, b.thickness);
      bodies_.push_back(placed(source, *shape, b.position, b.yaw, dynamic));

      BodyDesc desc;
      desc.id = ids[i];
      desc.shape = shape;
      desc.position = b.position;
      desc.yaw = b.yaw;
      desc.velocity = b.velocity;
      desc.angular_velocity = b.angular_velocity;
      desc.thickness = b.thickness;
      desc.density = scene_.ice_density;
      desc.motion = b.motion;
      desc.external_force = b.external_force;
      desc.external_torque = b.external_torque;
      add(desc, source);
    }
    if (const auto pair = first_overlap(bodies_, bodies_.size(), [](std::size_t, std::size_t) { return true; }))
      throw SceneError(bodies_[pair->second].source + ": overlaps " + bodies_[pair->first].source +
                       " initially; move them apart");
    if (scene_.floe_field) max_thickness_ = std::max(max_thickness_, scene_.floe_field->thickness);
    if (scene_.ice_sheet) max_thickness_ = std::max(max_thickness_, scene_.ice_sheet->thickness);
    if (!(max_thickness_ > 0.0)) max_thickness_ = 1.0;
  }

  // Channel walls.
  void add_channel() {
    if (!scene_.channel) return;
    const std::string where = scene_.channel->source.where.empty() ? "channel" : scene_.channel->source.where;
    for (const WallPolygon& wall : channel_walls(*scene_.channel)) {
      const std::string source = where + " (channel " + wall.name + ")";
      add_wall(wall.vertices, source,
               [&](const PlacedBody& q) { return q.source + ": overlaps " + source + " initially"; });
    }
  }

  // The ocean field file's land: fixed walls (land: walls), as thick as the thickest floe; without them, an
  // obstacle only for the floe field, which never places floes on land.
  void add_land() {
    const forcing::FieldSpec& f = scene_.ocean_field;
    if (f.kind != forcing::FieldKind::file || !f.grid) return;
    const std::string source = "the land of " + f.path;
    for (const forcing::LandRectangle& r : forcing::land_rectangles(*f.grid)) {
      const Vec2 lo = r.lo + f.offset, hi = r.hi + f.offset;
      const std::vector<Vec2> box{lo, {hi.x(), lo.y()}, hi, {lo.x(), hi.y()}};
      if (!f.land_walls) {
        land_.push_back(box);
        continue;
      }
      add_wall(box, source + " (land: walls)", [&](const PlacedBody& q) {
        return q.source + ": lies on " + source + " (the wall [" + std::to_string(lo.x()) + ", " +
               std::to_string(hi.x()) + "] x [" + std::to_string(lo.y()) + ", " + std::to_string(hi.y()) +
               "] m); move it into the water";
      });
    }
  }

  // The ice sheet's cells: touching each other, overlapping nothing placed above; bonded where it says so.
  void add_ice_sheet() {
    const auto& sheet = scene_.ice_sheet;
    if (!sheet) return;
    const std::string where = sheet->source.where.empty() ? "ice_sheet" : sheet->source.where;
    const std::size_t placed_before = bodies_.size();
    const SheetElementsOut elements = ice_sheet_elements(*sheet);
    const std::vector<BodyDesc> descs = ice_sheet_bodies(*sheet, scene_.ice_density, next_);
    std::vector<int> index(descs.size());
    for (std::size_t e = 0; e < descs.size(); ++e) {
      const BodyDesc& desc = descs[e];
      bodies_.push_back(
          placed(where + " (ice_sheet element " + std::to_string(e) + ")", *desc.shape, desc.position, 0.0, true));
      add(desc, where);
      index[e] = world_.index_of(desc.id);
    }
    const auto pair = first_overlap(bodies_, bodies_.size(), [&](std::size_t a, std::size_t b) {
      return a < placed_before && b >= placed_before;  // the sheet's cells against what was placed before it
    });
    if (pair)
      throw SceneError(bodies_[pair->second].source + ": overlaps " + bodies_[pair->first].source +
                       " initially; move the body or the sheet");
    next_ += static_cast<BodyId>(descs.size());
    if (sheet->bonds) add_sheet_bonds(*sheet, where, elements, descs, index);
  }

  // Generated floes, clear of everything above, added in space order (the World's own, geometry/space_order.h, on
  // cells of 4 x the floes' mean equivalent radius) with the generator's ids (largest first): neighbours in the ice
  // are neighbours in the World's arrays, so each thread of the step works on one stretch of the ice in every loop.
  void add_floe_field(FieldStatistics* field_report) {
    if (!scene_.floe_field) return;
    std::vector<std::vector<Vec2>> obstacles;
    obstacles.reserve(bodies_.size() + land_.size());
    for (const PlacedBody& p : bodies_) obstacles.push_back(p.vertices);
    obstacles.insert(obstacles.end(), land_.begin(), land_.end());
    const FloeField field = generate_floe_field(*scene_.floe_field, scene_.ice_density, next_, obstacles);
    const std::string where = scene_.floe_field->source.where.empty() ? "floe_field" : scene_.floe_field->source.where;
    double radius_sum = 0.0;
    for (const BodyDesc& desc : field.floes) radius_sum += desc.shape->equivalent_radius();
    const double cell =
        geometry::space_order_cell(radius_sum / static_cast<double>(std::max<std::size_t>(field.floes.size(), 1)));
    std::vector<std::pair<std::uint64_t, std::size_t>> order;
    order.reserve(field.floes.size());
    for (std::size_t k = 0; k < field.floes.size(); ++k)
      order.emplace_back(geometry::space_key(field.floes[k].position, cell), k);
    std::sort(order.begin(), order.end());
    for (const auto& [key, k] : order) add(field.floes[k], where);
    if (field_report)
      *field_report =
          field_statistics(field.floes, field.region_area, scene_.floe_field->size_min, scene_.floe_field->size_max);
  }

  dynamics::World take() { return std::move(world_); }
  // Where every body's description goes as it is added (none: nowhere).
  void record_into(std::vector<BodyDesc>* descs) { record_ = descs; }

 private:
  void add(const BodyDesc& desc, const std::string& source) {
    add_checked(world_, desc, source);
    if (record_) record_->push_back(desc);
  }

  static dynamics::WorldSettings settings_of(const Scene& scene) {
    dynamics::WorldSettings settings = scene.world;
    settings.contact.reference_speed = reference_speed(scene);
    settings.store_in_space_order = true;  // (every result the same; the run's outputs follow the ids)
    return settings;
  }

  // A fixed wall (world-frame vertices), as thick as the thickest floe (its mass never enters the dynamics); a
  // dynamic body placed before that overlaps it is an error, in `overlap_message(that body)`'s words.
  template <class Message>
  void add_wall(const std::vector<Vec2>& vertices, const std::string& source, const Message& overlap_message) {
    Vec2 centre{0.0, 0.0};
    auto shape =
        std::make_shared<const geometry::ConvexPolygon>(geometry::ConvexPolygon::from_vertices(vertices, &centre));
    PlacedBody p = placed(source, *shape, centre, 0.0, false);
    for (const PlacedBody& q : bodies_)
      if (q.dynamic && overlapping(p, q)) throw SceneError(overlap_message(q));
    bodies_.push_back(std::move(p));
    BodyDesc desc;
    desc.id = next_++;
    desc.shape = shape;
    desc.position = centre;
    desc.thickness = max_thickness_;
    desc.density = scene_.ice_density;
    desc.motion = Motion::fixed;
    add(desc, source);
  }

  // The bonds between the sheet's elements (descs, World indices `index`) across its faces and at its corners.
  void add_sheet_bonds(const IceSheetSpec& sheet, const std::string& where, const SheetElementsOut& elements,
                       const std::vector<BodyDesc>& descs, const std::vector<int>& index) {
    const auto& b = sheet.bonds;
    bonds::BondMaterial m;
    m.youngs_modulus = scene_.world.contact.youngs_modulus;
    m.poisson_ratio = scene_.world.contact.poisson_ratio;
    m.tensile_strength = b->tensile_strength;
    m.shear_strength = b->shear_strength;
    m.friction_angle = b->friction_angle;
    m.points_per_face = b->points_per_face;
    m.damping_ratio = b->damping_ratio;
    try {
      bonds::BondSet set(m);
      for (const SheetFace& f : elements.faces) {
        const BodyDesc &da = descs[static_cast<std::size_t>(f.a)], &db = descs[static_cast<std::size_t>(f.b)];
        set.add_face({.a = index[static_cast<std::size_t>(f.a)],
                      .b = index[static_cast<std::size_t>(f.b)],
                      .id_a = da.id,
                      .id_b = db.id,
                      .p0 = f.p0,
                      .p1 = f.p1,
                      .thickness = sheet.thickness,
                      .centre_a = da.position,
                      .centre_b = db.position,
                      .yaw_a = 0.0,
                      .yaw_b = 0.0});
      }
      for (const SheetCorner& c : elements.corners) {
        if (c.faces.empty()) continue;  // a corner on the region's boundary with no face at it
        set.add_corner_pair(index[static_cast<std::size_t>(c.a)], index[static_cast<std::size_t>(c.b)], c.faces);
      }
      world_.set_bonds(std::move(set));
    } catch (const std::invalid_argument& e) {
      throw SceneError(where + ": ice_sheet.bonds: " + e.what());
    }
  }

  const Scene& scene_;
  dynamics::World world_;
  std::vector<PlacedBody> bodies_;       // placed so far
  std::vector<std::vector<Vec2>> land_;  // land that is no wall: an obstacle for the floe field only
  BodyId next_ = 0;                      // the next free id
  std::vector<BodyDesc>* record_ = nullptr;
  double max_thickness_ = 0.0;  // of the dynamic bodies, for the walls' thickness [m]
};

}  // namespace

dynamics::World build_world(const Scene& scene, FieldStatistics* field_report, std::vector<BodyDesc>* descs) {
  WorldBuilder b(scene);
  b.record_into(descs);
  b.add_bodies();
  b.add_channel();
  b.add_land();
  b.add_ice_sheet();
  b.add_floe_field(field_report);
  dynamics::World world = b.take();
  check_bodies_in_water(world);
  return world;
}

}  // namespace polyfloe::scene
