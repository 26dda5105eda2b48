// Ids of a scene's explicit bodies (internal to dem/scene): the given ones, which must be unique, then the smallest
// free ones in list order. Shared by the planar and the spatial world builders.
#pragma once

#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "scene/scene.h"

namespace polyfloe::scene::detail {

// `given[i]`: body i's id if the scene gives one; `where(i)` names body i in the error (SceneError) of a duplicate.
template <class Where>
std::vector<dynamics::BodyId> assign_ids(const std::vector<std::optional<std::uint64_t>>& given, Where where) {
  std::map<dynamics::BodyId, std::size_t> taken;
  for (std::size_t i = 0; i < given.size(); ++i) {
    if (!given[i]) continue;
    if (auto [it, fresh] = taken.emplace(*given[i], i); !fresh)
      throw SceneError(where(i) + ": id " + std::to_string(*given[i]) + " is already used by " + where(it->second));
  }
  std::vector<dynamics::BodyId> ids(given.size());
  dynamics::BodyId next = 0;
  for (std::size_t i = 0; i < given.size(); ++i) {
    if (given[i]) {
      ids[i] = *given[i];
      continue;
    }
    while (taken.count(next)) ++next;
    ids[i] = next++;
  }
  return ids;
}

}  // namespace polyfloe::scene::detail
