#include "dynamics/body.h"

namespace polyfloe::dynamics {

std::string_view to_string(Motion m) {
  switch (m) {
    case Motion::dynamic: return "dynamic";
    case Motion::fixed: return "fixed";
    case Motion::kinematic: return "kinematic";
  }
  return "unknown";
}

}  // namespace polyfloe::dynamics
