#include "dynamics/body.h"

#include <algorithm>
#include <numeric>

namespace polyfloe::dynamics {

std::string_view to_string(Motion m) {
  switch (m) {
    case Motion::dynamic: return "dynamic";
    case Motion::fixed: return "fixed";
    case Motion::kinematic: return "kinematic";
  }
  return "unknown";
}

void sort_by_id(std::span<const BodyId> ids, std::vector<int>& order) {
  order.resize(ids.size());
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(), [ids](int a, int b) { return ids[a] < ids[b]; });
}

}  // namespace polyfloe::dynamics
