// libFuzzer target: reading a checkpoint and restarting from it (run::read_checkpoint, run::check_restart,
// dynamics::World::restore), with the checkpoint's content chosen by the fuzzer.
//
// The input does not feed the HDF5 library raw bytes (its parser of damaged files is not ours to harden; a
// truncated or foreign file is a regression test). It edits a real checkpoint of a small scene (two floes, a
// bonded sheet of a few cells, or three spatial boxes on a plate) field by field: counts (frames, steps, negative and huge), times and the step
// (NaN, infinite, negative, subnormal), the kind, the signature, the lengths of every per-body and per-bond array
// (shorter, longer, empty), their values, contact springs between ids that exist or not, the channel and velocity
// grid states; of a spatial one its poses, quaternions, angular momenta, forces, springs and counts, and its mode.
// The edited checkpoint is written with run::write_checkpoint and read back.
//
// What must hold: read_checkpoint returns or throws CheckpointError; check_restart accepts or throws
// CheckpointError; World::restore (SpatialWorld::restore) of an accepted checkpoint succeeds or throws
// std::invalid_argument; a world
// restored from an accepted checkpoint steps without a sanitizer report. Anything else is a finding.
#include <fuzzer/FuzzedDataProvider.h>
#include <hdf5.h>
#include <unistd.h>

#include <bit>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <optional>
#include <string>
#include <type_traits>
#include <vector>

#include "dynamics/spatial_world.h"
#include "dynamics/world.h"
#include "formats/atomic_file.h"
#include "run/checkpoint.h"
#include "scene/scene.h"
#include "scene/scene_reader.h"

namespace {

using namespace polyfloe;

const char* const kFloes = R"(run: {duration: 1, dt: 1e-3}
floes:
  - {rectangle: {width: 10, height: 10}, position: [-6, 0], velocity: [1, 0]}
  - {rectangle: {width: 10, height: 10}, position: [6, 0], velocity: [-1, 0]}
  - {regular: {sides: 6, radius: 3}, position: [0, 20], motion: fixed}
)";
const char* const kSheet = R"(run: {duration: 1, dt: 1e-4}
ice_sheet:
  region: [0, 0, 30, 20]
  cell_size: 10
  thickness: 1
  seed: 1
  bonds: {tensile_strength: 1.0e6, shear_strength: 1.0e6, friction_angle: 0.6, points_per_face: 2}
)";

const char* const kSpatial = R"(run: {duration: 1, dt: 1e-4}
contact: {friction: 0.4}
spatial:
  gravity: [0, 0, -9.81]
  contact_point: manifold
  bodies:
    - {box: [10, 10, 1], position: [0, 0, -0.5], motion: fixed}
    - {box: [1, 1, 1], position: [0, 0, 0.501], velocity: [0.5, 0, -0.2], angular_velocity: [0, 0, 1]}
    - {box: [1, 1, 0.5], position: [1.2, 0, 0.45], rotation: {axis: [1, 1, 0], angle_deg: 10}, velocity: [-0.5, 0, 0]}
)";

struct Base {
  scene::Scene scene;
  std::optional<dynamics::World> world;
  std::optional<dynamics::SpatialWorld> spatial;
  run::Checkpoint checkpoint;
};

// A checkpoint of `world` after 20 steps of the scene `b.scene`.
template <class W>
void take_checkpoint(Base& b, W& world) {
  const double dt = scene::time_step(b.scene, world);
  world.compute_forces(std::is_same_v<W, dynamics::World> ? 0.0 : dt);  // as the driver does
  for (int i = 0; i < 20; ++i) world.step(dt);
  run::Checkpoint& c = b.checkpoint;
  c.kind = "frame";
  c.code_version = "fuzz";
  c.scene_resolved = scene::resolved_yaml(b.scene);
  c.body_signature = run::body_signature(world);
  c.dt = dt;
  c.frames = 2;
  c.frame_times = {0.0, world.time()};
  c.next_frame = world.time() + 0.05;
  if constexpr (std::is_same_v<W, dynamics::World>)
    c.world = world.state();
  else
    c.spatial = world.state();
}

Base make_base(const char* text) {
  Base b;
  b.scene = scene::parse_scene(text, "fuzz.yaml");
  if (b.scene.spatial) {
    b.spatial.emplace(scene::build_spatial_world(b.scene));
    take_checkpoint(b, *b.spatial);
  } else {
    b.world.emplace(scene::build_world(b.scene));
    take_checkpoint(b, *b.world);
  }
  return b;
}

double any_double(FuzzedDataProvider& in) {
  switch (in.ConsumeIntegralInRange<int>(0, 3)) {
    case 0: return std::bit_cast<double>(in.ConsumeIntegral<std::uint64_t>());  // NaN, inf, subnormal, anything
    case 1: return in.ConsumeFloatingPointInRange<double>(-1e3, 1e3);
    case 2: return in.PickValueInArray<double>({0.0, -0.0, 1e-300, -1.0, 1e300, 5e-324});
    default: return in.ConsumeFloatingPoint<double>();
  }
}

template <class T, class Make>
void edit_vector(FuzzedDataProvider& in, std::vector<T>& v, Make make) {
  switch (in.ConsumeIntegralInRange<int>(0, 3)) {
    case 0: v.resize(in.ConsumeIntegralInRange<std::size_t>(0, v.size() + 3)); break;
    case 1: v.clear(); break;
    default:
      if (!v.empty()) v[in.ConsumeIntegralInRange<std::size_t>(0, v.size() - 1)] = make();
  }
}

void edit(FuzzedDataProvider& in, run::Checkpoint& c) {
  dynamics::WorldState& w = c.world;
  auto vec2 = [&] { return geometry::Vec2(any_double(in), any_double(in)); };
  auto num = [&] { return any_double(in); };
  switch (in.ConsumeIntegralInRange<int>(0, 19)) {
    case 0: c.frames = in.ConsumeIntegral<int>(); break;
    case 1: w.steps = in.ConsumeIntegral<std::uint64_t>(); break;
    case 2: w.time = num(); break;
    case 3: c.dt = num(); break;
    case 4: c.next_frame = num(); break;
    case 5: c.kind = in.PickValueInArray<const char*>({"frame", "final", "unstable", "", "x"}); break;
    case 6: edit_vector(in, c.frame_times, num); break;
    case 7: edit_vector(in, w.ids, [&] { return in.ConsumeIntegral<std::uint64_t>(); }); break;
    case 8: edit_vector(in, w.position, vec2); break;
    case 9: edit_vector(in, w.velocity, vec2); break;
    case 10: edit_vector(in, w.yaw, num); break;
    case 11: edit_vector(in, w.omega, num); break;
    case 12: edit_vector(in, w.force, vec2); break;
    case 13: edit_vector(in, w.drift_load, [&] { return forcing::DriftLoad{}; }); break;
    case 14: edit_vector(in, w.lin_force, vec2); break;
    case 15:
      w.contact_history.emplace_back(contact::PairKey{in.ConsumeIntegralInRange<std::uint64_t>(0, 5),
                                                      in.ConsumeIntegralInRange<std::uint64_t>(0, 5)},
                                     contact::PlanarHistory{num(), num()});
      break;
    case 16:
      if (w.bonds) {
        bonds::BondState& s = *w.bonds;
        switch (in.ConsumeIntegralInRange<int>(0, 4)) {
          case 0: edit_vector(in, s.face_intact, [&] { return in.ConsumeIntegral<std::uint8_t>(); }); break;
          case 1: edit_vector(in, s.face_points_left, [&] { return in.ConsumeIntegral<std::int32_t>(); }); break;
          case 2: edit_vector(in, s.point_intact, [&] { return in.ConsumeIntegral<std::uint8_t>(); }); break;
          case 3: edit_vector(in, s.point_sigma, num); break;
          default: edit_vector(in, s.face_broken_time, num);
        }
      } else {
        w.bonds = bonds::BondState{};
      }
      break;
    case 17: c.body_signature = in.ConsumeRandomLengthString(24); break;
    case 18: c.next_sample = num(); break;
    default: w.bonds_failed_last = in.ConsumeIntegral<int>();
  }
}

void edit_spatial(FuzzedDataProvider& in, run::Checkpoint& c) {
  dynamics::SpatialWorldState& w = *c.spatial;
  auto num = [&] { return any_double(in); };
  auto vec3 = [&] { return geometry::Vec3(num(), num(), num()); };
  auto quat = [&] { return dynamics::Quat(num(), num(), num(), num()); };
  switch (in.ConsumeIntegralInRange<int>(0, 13)) {
    case 0: w.steps = in.ConsumeIntegral<std::uint64_t>(); break;
    case 1: w.time = num(); break;
    case 2: edit_vector(in, w.ids, [&] { return in.ConsumeIntegral<std::uint64_t>(); }); break;
    case 3: edit_vector(in, w.position, vec3); break;
    case 4: edit_vector(in, w.orientation, quat); break;
    case 5: edit_vector(in, w.velocity, vec3); break;
    case 6: edit_vector(in, w.angular_momentum, vec3); break;
    case 7: edit_vector(in, w.force, vec3); break;
    case 8: edit_vector(in, w.torque, vec3); break;
    case 9:
      w.contact_history.emplace_back(contact::PairKey{in.ConsumeIntegralInRange<std::uint64_t>(0, 4),
                                                      in.ConsumeIntegralInRange<std::uint64_t>(0, 4)},
                                     vec3());
      break;
    case 10: w.narrow_phase_failures = in.ConsumeIntegral<std::uint64_t>(); break;
    case 11: w.forces_ready = in.ConsumeBool(); break;
    case 12: c.spatial.reset(); break;  // a planar checkpoint (of no bodies) for the spatial scene
    default: edit(in, c);               // the header's fields (and a planar state beside the spatial one)
  }
}

}  // namespace

// HDF5 keeps freed blocks on free lists of at most 1 MB each; a file's metadata cache is larger, so every file
// opened used to map fresh pages and clear them (three quarters of the run time under AddressSanitizer). Unlimited
// lists reuse the blocks: the same code runs, several times faster.
extern "C" int LLVMFuzzerInitialize(int*, char***) {
  H5set_free_list_limits(-1, -1, -1, -1, -1, -1);
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static Base floes = make_base(kFloes);
  static Base sheet = make_base(kSheet);
  static Base spatial = make_base(kSpatial);
  static const std::filesystem::path file = std::filesystem::path(access("/dev/shm", W_OK) == 0 ? "/dev/shm" : "/tmp") /
                                            ("polyfloe_fuzz_checkpoint_" + std::to_string(getpid()) + ".h5");
  FuzzedDataProvider in(data, size);
  const int which = in.ConsumeIntegralInRange<int>(0, 2);
  const Base& base = which == 0 ? floes : which == 1 ? sheet : spatial;
  run::Checkpoint c = base.checkpoint;
  const int edits = in.ConsumeIntegralInRange<int>(0, 8);
  for (int i = 0; i < edits && in.remaining_bytes() > 0; ++i) {
    if (c.spatial)
      edit_spatial(in, c);
    else
      edit(in, c);
  }
  try {
    run::write_checkpoint(file, c);
  } catch (const io::IoError&) {
    return 0;  // the writer refused what it was given: nothing to read
  }
  try {
    const run::Checkpoint back = run::read_checkpoint(file);
    const double dt = back.dt > 0.0 && back.dt < 1e-3 ? back.dt : 1e-4;
    if (base.spatial) {
      run::check_restart(back, file, *base.spatial);
      dynamics::SpatialWorld world = *base.spatial;  // a copy: restore() may fail half-way
      world.restore(*back.spatial);
      for (int i = 0; i < 3; ++i) world.step(dt);
    } else {
      run::check_restart(back, file, *base.world);
      dynamics::World world = *base.world;
      world.restore(back.world);
      for (int i = 0; i < 3; ++i) world.step(dt);
    }
  } catch (const run::CheckpointError&) {
  } catch (const std::invalid_argument&) {
  } catch (const std::exception& e) {
    std::fprintf(stderr, "fuzz_checkpoint: threw %s\n", e.what());
    std::abort();
  }
  return 0;
}
