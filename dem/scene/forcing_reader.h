// The 'forcing' block's checks across blocks (internal to dem/scene); its keys are declared in settings_schema.h.
#pragma once

#include "scene/schema.h"

namespace polyfloe::scene::detail {

// Scene-wide checks that need other blocks (run.duration, ice.density); throws SceneError.
void check_forcing(const Context& ctx, const Field& root, const Scene& s);

}  // namespace polyfloe::scene::detail
