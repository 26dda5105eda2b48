// The blocks of a scene that make bodies (internal to dem/scene): explicit floes, the floe field, the channel, the
// ice sheet and the spatial bodies.
#pragma once

#include <array>
#include <vector>

#include "scene/schema.h"

namespace polyfloe::scene::detail {

// A rectangle [xmin, ymin, xmax, ymax] [m] with xmax > xmin and ymax > ymin.
std::array<double, 4> to_box(const Context& ctx, const Field& f);

void read_floes(const Context& ctx, const Field& f, std::vector<BodySpec>& bodies);
FloeFieldSpec read_floe_field(MapReader m);
ChannelSpec read_channel(MapReader m);
IceSheetSpec read_ice_sheet(MapReader m);
SpatialSpec read_spatial(MapReader m);

}  // namespace polyfloe::scene::detail
