// The driver of a spatial scene: steps a SpatialWorld to the end, writing VTK (bodies.pvd, contacts.pvd) and
// results.h5 (io/spatial_hdf5_writer.h) on the output schedule, and stopping an unstable run (exit 3) with what to
// change. Spatial runs write no checkpoints (restart is for the long planar runs).
#pragma once

#include "dynamics/spatial_world.h"
#include "run/simulation.h"
#include "scene/scene.h"

namespace polyfloe::run {

// Non-finite state, a contact resolved by fewer than dynamics::kMinStepsPerContact steps, or an overlap deeper than
// a quarter of the smaller body's equivalent radius: throws InstabilityError naming the bodies, the time and the
// step to use.
void check_stability(const dynamics::SpatialWorld& world, double dt);

RunSummary run_spatial(const scene::Scene& scene, dynamics::SpatialWorld& world, const RunOptions& options);

}  // namespace polyfloe::run
