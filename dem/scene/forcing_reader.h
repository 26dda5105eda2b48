// The 'forcing' block of a scene (internal to dem/scene): drag terms, Coriolis, and the ocean and wind fields.
#pragma once

#include "scene/schema.h"

namespace polyfloe::scene::detail {

// Reads forcing.* into s.world.drift, s.ocean_field and s.wind_field (and builds the fields).
void read_forcing(MapReader m, Scene& s);

// Scene-wide checks that need other blocks (run.duration, ice.density); throws SceneError.
void check_forcing(const Context& ctx, const Field& root, const Scene& s);

}  // namespace polyfloe::scene::detail
