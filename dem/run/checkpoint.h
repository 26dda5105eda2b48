// Checkpoints: the full state of a run in one HDF5 file, from which it continues bitwise as if never stopped.
//
// A checkpoint is taken right after an output frame has been written (so nothing is half-accumulated): the World's
// state (run/../dynamics/world.h WorldState: poses, velocities, the forces and drift loads of the last evaluation,
// the tangential-spring history, the bonds' state), the driver's schedule (frames written and their times, next
// frame), the channel monitor's and the velocity grid's state, the time step, and the resolved scene. Shapes,
// masses, quadrature points and bond geometry are rebuilt from the scene; a signature of the bodies (ids, motion,
// thickness, mass, vertices) checks that the scene builds the same bodies. No random numbers are drawn after the
// world is built (the generators' seeds are in the scene), so there is no generator state to store.
//
// Layout (all SI):
//   / attributes: format = "polyfloe-checkpoint", format_version, kind ("frame" | "final" | "unstable"),
//       code_version, scene_resolved, dt [s], time [s], steps, frames, next_frame [s], forces_ready,
//       body_signature (hex), bonds_failed_last
//   /frame_times [F] [s]
//   /world/ids [N], position [N,2] [m], yaw [N] [rad], velocity [N,2] [m/s], omega [N] [rad/s], force [N,2] [N],
//       torque [N] [N m], external_force [N,2], external_torque [N], drift_load [N or 0, 10]
//       (force x, y, torque, dxx, dxy, dyy, dxw, dyw, dww, m f), lin_force [N or 0, 2], lin_torque [N or 0]
//   /contacts/lo, hi [C] (body ids of each pair), spring [C] [m], normal_force [C] [N]
//   /bonds (worlds with bonds): face_intact, face_points_left, face_broken_time [F], point_intact, point_sigma,
//       point_tau [P]; attributes max_sigma, max_tau [Pa]
//   /channel (scenes with a channel): through [N]; attributes last_time, last_flow_time, passed, stalled_since,
//       jam_time (NaN = none)
//   /velocity_grid (when on): attribute next_sample [s]
// A spatial run's checkpoint (root attribute mode = "spatial") holds its SpatialWorldState in the same places:
//   / attributes as above less bonds_failed_last, plus narrow_phase_queries, narrow_phase_failures
//   /world/ids [N], position [N,3] [m], orientation [N,4] (w, x, y, z), velocity [N,3] [m/s],
//       angular_momentum [N,3] [kg m^2/s], force [N,3] [N], torque [N,3] [N m]
//   /contacts/lo, hi [C], spring [C,3] [m]
// Both lists come from the states' visit_fields (dynamics/state_fields.h): one list, written and read alike.
//
// Files are written to a temporary sibling and renamed into place, so a checkpoint on disk is always complete.
#pragma once

#include <cstdint>
#include <filesystem>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "dynamics/spatial_world.h"
#include "dynamics/world.h"
#include "run/channel_monitor.h"

namespace polyfloe::run {

// A checkpoint that is missing, unreadable, not a checkpoint, or does not belong to the scene (exit code 2).
class CheckpointError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct Checkpoint {
  std::string kind = "frame";  // "frame": at an output frame (a restart point); "final": at the end of the
                               // run; "unstable": where the instability guard stopped it (inspection only)
  std::string code_version;
  std::string scene_resolved;                                           // scene::resolved_yaml of the run's scene
  std::string body_signature;                                           // body_signature() of the world
  double dt = 0.0;                                                      // the run's time step [s]
  int frames = 0;                                                       // output frames written (0 .. frames-1)
  std::vector<double> frame_times;                                      // [frames] [s]
  double next_frame = 0.0;                                              // time of the next frame [s]
  dynamics::WorldState world;                                           // a planar run's state
  std::optional<dynamics::SpatialWorldState> spatial;                   // a spatial run's state (`world` is then empty)
  double time() const { return spatial ? spatial->time : world.time; }  // [s]
  std::optional<ChannelMonitor::State> channel;
  std::optional<double> next_sample;  // the velocity grid's next sample [s]
};

// A fingerprint of the bodies a scene builds (ids, order, motion, thickness, mass, body-frame vertices), in hex.
std::string body_signature(const dynamics::World& world);
std::string body_signature(const dynamics::SpatialWorld& world);

// Writes `c` to `file` atomically (temporary sibling + rename). Throws io::IoError naming the file.
void write_checkpoint(const std::filesystem::path& file, const Checkpoint& c);

// Reads a checkpoint. Throws CheckpointError naming the file when it is missing, unreadable or malformed.
Checkpoint read_checkpoint(const std::filesystem::path& file);

// `path` itself if it is a file; for a run's output folder (or its checkpoints/ folder) the newest restartable
// checkpoint in it. Throws CheckpointError when there is none.
std::filesystem::path find_checkpoint(const std::filesystem::path& path);

// The checkpoint file of a run in `output_dir` after `frames` frames.
std::filesystem::path checkpoint_path(const std::filesystem::path& output_dir, int frames);

// Checks that `c` can restart `world` (built from the scene): restartable kind, same bodies (signature), frames.
// (World::restore checks the state arrays.) Throws CheckpointError naming `file` and the mismatch.
void check_restart(const Checkpoint& c, const std::filesystem::path& file, const dynamics::World& world);
void check_restart(const Checkpoint& c, const std::filesystem::path& file, const dynamics::SpatialWorld& world);

}  // namespace polyfloe::run
