// A scene: everything a run needs, resolved and validated, in SI units. The YAML reader (scene_reader.h) makes
// one from a file plus --set overrides; build_world() turns it into a World. Defaults live here and are listed
// with their units and ranges in docs/scene-reference.md.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "dynamics/spatial_world.h"
#include "dynamics/world.h"
#include "forcing/analytic_fields.h"

namespace polyfloe::scene {

using geometry::Vec2;

// Where a value came from, for error messages: "channel.yaml:12:5" or "--set run.duration".
struct SourceRef {
  std::string where;
};

class SceneError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct TimeSettings {
  double duration = 300.0;          // simulated time [s], > 0
  std::optional<double> dt;         // fixed time step [s]; empty = automatic
  double steps_per_contact = 40.0;  // auto dt = shortest contact duration / this [-], >= dynamics::kMinStepsPerContact
  // The foundation force model's flat faces (a linear spring, whose contact lasts as long at any speed): the automatic
  // dt is also at most the shortest flat contact's duration / this [-], >= dynamics::kMinStepsPerContact; empty =
  // steps_per_contact. Only with contact.force_model: foundation (the scene reader refuses it otherwise).
  std::optional<double> steps_per_flat_contact;
  std::optional<double> reference_speed;  // impact speed for the automatic dt and the paper damping [m/s];
                                          // empty = max(1 m/s, steady free-drift speed)
};

// Ice velocity averaged on a grid of cells over each output interval (run/velocity_grid.h), written to results.h5
// (/diagnostics/velocity_grid) and as VTK image data (velocity.pvd, velocity/velocity_NNNNNN.vti).
struct VelocityGridSettings {
  static constexpr double kMaxCells = 4.0e6;  // a larger grid is refused (memory, file size)
  bool enabled = false;
  double cell = 10.0;                           // cell size [m], > 0
  std::optional<std::array<double, 4>> region;  // [m] xmin, ymin, xmax, ymax; empty = auto: every body at t = 0
  int samples_per_frame = 10;                   // samples per output interval, evenly spaced [-], 1..1000
};

// Checkpoints (run/checkpoint.h): the full state at an output frame, DIR/checkpoints/checkpoint_NNNNNN.h5 (NNNNNN =
// frames written), from which `polyfloe run SCENE --restart` continues bitwise as the uninterrupted run would.
struct CheckpointSettings {
  int every = 10;  // frames between checkpoints [-], 0..100000; 0 = none (the final and the instability
                   // checkpoints are still written unless every = 0)
  int keep = 2;    // newest checkpoints kept [-], 1..1000
};

struct OutputSettings {
  // Frames a run may write (a frame per interval, at most one per step): each is a file per series, so a typo in
  // the interval's unit would otherwise fill the disk.
  static constexpr double kMaxFrames = 1.0e6;
  double interval = 5.0;  // simulated time between frames [s], > 0
  bool vtk = true;        // VTK .vtp frames + .pvd series
  bool contacts = true;   // contact series (.vtp + .pvd) alongside the floes
  // Each VTK frame as a .pvtp listing pieces (ParaView's parallel convention), one per MPI rank: the floes it owns,
  // the contacts it evaluated, the bonded faces of its elements, each piece written by its rank; one process writes
  // one piece. Planar scenes. false: one .vtp per frame, gathered (the same files on any number of ranks).
  bool vtk_pieces = false;
  bool hdf5 = true;  // results.h5
  VelocityGridSettings velocity_grid;
  CheckpointSettings checkpoint;
};

// A floe (or wall, or plate) listed explicitly.
struct BodySpec {
  std::vector<Vec2> polygon;      // vertices in the body's own frame [m]; recentred on their centroid
  Vec2 position{0.0, 0.0};        // where the centroid goes [m]
  double yaw = 0.0;               // [rad]
  Vec2 velocity{0.0, 0.0};        // [m/s]
  double angular_velocity = 0.0;  // [rad/s]
  double thickness = 1.0;         // [m]
  dynamics::Motion motion = dynamics::Motion::dynamic;
  std::optional<std::uint64_t> id;  // stable id; empty = next free
  Vec2 external_force{0.0, 0.0};    // constant load at the centroid [N]
  double external_torque = 0.0;     // constant torque about z [N m]
  SourceRef source;                 // for error messages
};

// How a generated floe's outline is made (scene/floe_field.h).
enum class FloeShape {
  ellipse,  // corners at random angles on a random ellipse (corner count uniform in the range; aspect_max)
  voronoi,  // an interior cell of a Poisson-Voronoi tessellation with a corner count in the range
};

// Random convex floes placed in a rectangle at a target concentration, without initial contact.
struct FloeFieldSpec {
  static constexpr double kMinSize = 0.01;  // allowed floe sizes [m]
  static constexpr double kMaxSize = 1e5;
  // Placement tries in all before the generator gives up, whatever max_attempts allows: kBaseAttempts plus
  // kAttemptsPerFloe per floe (a field that fills in time takes a few tries per floe; seconds of tries in all).
  static constexpr double kBaseAttempts = 1e7;
  static constexpr double kAttemptsPerFloe = 200.0;
  Vec2 region_min{0.0, 0.0};        // [m]
  Vec2 region_max{1000.0, 1000.0};  // [m]
  double concentration = 0.5;       // ice area / region area [-], (0, 0.7]
  double size_min = 5.0;            // floe size a: diameter of the area-equivalent circle [m]
  double size_max = 100.0;          // floe size b [m]
  double exponent = 2.0;            // power-law exponent alpha of the size pdf f(x) = c x^-alpha (Eq. 15-16) [-]
  int corners_min = 5;              // corners per floe, drawn uniformly in [min, max]
  int corners_max = 10;
  FloeShape shape = FloeShape::ellipse;
  double aspect_max = 2.5;  // ellipse shapes: semi-axis ratio uniform in [1, aspect_max] [-], [1, 10]
  double thickness = 1.0;   // [m]
  Vec2 velocity{0.0, 0.0};  // initial velocity [m/s]
  std::uint64_t seed = 1;
  int max_attempts = 20000;  // random placement tries per floe before giving up [-]
  SourceRef source;
};

// A straight-walled funnel and strait downstream (+x) of the ice region, as fixed wall polygons.
struct ChannelSpec {
  double basin_x_min = -100.0;  // upstream end of the basin walls [m]
  double basin_x_max = 1100.0;  // where the funnel starts [m]
  double basin_y_min = 0.0;     // basin wall lines [m]
  double basin_y_max = 1000.0;
  double funnel_length = 300.0;  // along x [m]
  double opening = 250.0;        // strait width [m]
  double strait_length = 600.0;  // [m]
  double wall_thickness = 50.0;  // [m]
  double jam_window = 20.0;      // jammed: no net ice through the strait entrance for this long [s] ...
  double jam_speed = 0.1;        // ... while the ice in the funnel moves slower than this on average [m/s]
  SourceRef source;
};

// Level ice as a sheet of Voronoi cells tiling a rectangle (scene/ice_sheet.h): the cells touch along shared edges,
// with no gap and no overlap. Unbonded, it is a fully packed field of broken ice; [bonds] freezes it.
// Bonds that freeze an ice sheet's elements together (bonds/bond_set.h; E and nu come from the ice block).
struct SheetBondSpec {
  double tensile_strength = 1.5e6;  // normal (tensile) bond strength [Pa], > 0
  double shear_strength = 1.5e6;    // Mohr-Coulomb cohesion [Pa], > 0
  double friction_angle = 0.0;      // Mohr-Coulomb friction angle [rad], [0, pi/2)
  int points_per_face = 4;          // bond points along each shared edge [-], 2..64
  double damping_ratio = 0.1;       // of each face's springs [-], [0, 10]
};

enum class SheetElements {
  cells,      // each Voronoi cell is one element
  triangles,  // each cell is split into triangles fanned from its centroid (the paper's triangular prisms)
};

struct IceSheetSpec {
  Vec2 region_min{0.0, 0.0};      // [m]
  Vec2 region_max{100.0, 100.0};  // [m]
  double cell_size = 10.0;        // mean cell size: diameter of the circle of the mean cell area [m], > 0
  int relaxation = 0;             // Lloyd iterations: 0 = Poisson-Voronoi cells, more = rounder, more even [-]
  double thickness = 1.0;         // [m]
  Vec2 velocity{0.0, 0.0};        // initial velocity [m/s]
  std::uint64_t seed = 1;
  SheetElements elements = SheetElements::cells;
  std::optional<SheetBondSpec> bonds;  // empty: unbonded (broken ice)
  static constexpr double kMaxCells = 2.0e6;
  static constexpr double kMinEdgeFraction = 0.1;  // shorter cell edges are collapsed (x cell_size)
  SourceRef source;
};

// A rigid convex body of a spatial scene (dynamics/spatial_world.h): a box, or a polygon extruded to a thickness.
struct SpatialBodySpec {
  std::optional<geometry::Vec3> box;               // edge lengths (lx, ly, lz) [m], each > 0
  std::vector<Vec2> polygon;                       // or a prism: the outline in the body frame [m] ...
  double thickness = 1.0;                          // ... extruded to this thickness, centred on z = 0 [m]
  geometry::Vec3 position{0.0, 0.0, 0.0};          // centroid [m]
  geometry::Vec3 rotation_axis{0.0, 0.0, 1.0};     // initial orientation: a turn about this axis (any length > 0) ...
  double rotation_angle = 0.0;                     // ... by this angle [rad]
  geometry::Vec3 velocity{0.0, 0.0, 0.0};          // [m/s]
  geometry::Vec3 angular_velocity{0.0, 0.0, 0.0};  // world frame [rad/s]
  std::optional<double> density;                   // [kg/m^3]; empty = ice.density
  dynamics::Motion motion = dynamics::Motion::dynamic;
  std::optional<std::uint64_t> id;  // stable id; empty = next free
  SourceRef source;
};
// A spatial scene: 6-DOF polyhedra instead of level floes (no drift forcing, no floe fields).
struct SpatialSpec {
  geometry::Vec3 gravity{0.0, 0.0, 0.0};  // [m/s^2]
  bool buoyancy = false;                  // Archimedes' force below z = water_level
  double water_level = 0.0;               // [m]
  double water_density = 1025.0;          // [kg/m^3]
  dynamics::SpatialNarrowPhase narrow_phase = dynamics::SpatialNarrowPhase::sat;
  dynamics::ContactPointModel contact_point = dynamics::ContactPointModel::witness;
  std::vector<SpatialBodySpec> bodies;
  SourceRef source;
};
struct Scene {
  std::string name = "scene";
  std::string source_path;             // the YAML file
  std::string source_text;             // its text (stored in the HDF5 output)
  std::vector<std::string> overrides;  // the --set arguments applied
  TimeSettings time;
  OutputSettings output;
  double ice_density = 920.0;      // [kg/m^3]
  dynamics::WorldSettings world;   // contact law + drift forcing + broad phase
  forcing::FieldSpec ocean_field;  // what world.drift.ocean was built from (default: still water)
  forcing::FieldSpec wind_field;   // what world.drift.wind was built from (default: calm)
  std::vector<BodySpec> bodies;
  std::optional<FloeFieldSpec> floe_field;
  std::optional<IceSheetSpec> ice_sheet;
  std::optional<ChannelSpec> channel;
  std::optional<SpatialSpec> spatial;  // present: a spatial scene (bodies are polyhedra; no floes, fields, forcing)
};

// The automatic time step with bonds: this fraction of the bonds' critical step (bonds/bond_set.h), itself a lower
// bound of the stable step.
inline constexpr double kBondStepFraction = 0.9;
// kBondStepFraction x the critical step of the world's intact bonds [s]; +inf without bonds.
double bond_time_step(const dynamics::World& world);

// Builds the World (explicit bodies, generated walls and floe field). Throws SceneError naming the source of a
// body that is invalid (non-convex polygon, overlaps, ...).
// When `field_report` is given and the scene has a floe field, it receives the field's realised statistics; when
// `descs` is given, every body's description in the order the World was given them (what a domain decomposition
// hands its ranks).
struct FieldStatistics;
dynamics::World build_world(const Scene& scene, FieldStatistics* field_report = nullptr,
                            std::vector<dynamics::BodyDesc>* descs = nullptr);

// The reference impact speed the scene uses (its own, or the automatic one) [m/s].
double reference_speed(const Scene& scene);
// The time step the scene uses for this world: fixed, or shortest contact duration / steps_per_contact [s].
// Throws SceneError when run.duration would take more than kMaxSteps steps.
inline constexpr double kMaxSteps = 1e12;
double time_step(const Scene& scene, const dynamics::World& world);
// Throws SceneError when the run at step `dt` [s] would take more than kMaxSteps steps or write more than
// OutputSettings::kMaxFrames frames.
void check_run_length(const Scene& scene, double dt);

// The SpatialWorld of a spatial scene (scene.spatial set). Throws SceneError naming the body that is invalid.
dynamics::SpatialWorld build_spatial_world(const Scene& scene);
// Fixed, or SpatialWorld::shortest_contact_duration at the reference speed over steps_per_contact [s].
double time_step(const Scene& scene, const dynamics::SpatialWorld& world);

}  // namespace polyfloe::scene
