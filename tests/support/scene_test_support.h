// Helpers of the scene-reader tests: the example-scene folder, a one-floe scene, and the message of a SceneError.
#pragma once

#include <string>
#include <vector>

#include "scene/scene_reader.h"

namespace polyfloe::scene {

inline const std::string kSceneDir = std::string(POLYFLOE_SOURCE_DIR) + "/dem/scenes/";

// The smallest valid scene: one floe, everything else default.
inline const char* kOneFloe =
    "floes:\n"
    "  - regular: {sides: 6, radius: 5}\n";

// The message of the exception of type E (a SceneError unless said) that `f` throws ("" if none).
template <class E = SceneError, class F>
std::string error_of(F&& f) {
  try {
    f();
  } catch (const E& e) {
    return e.what();
  }
  return "";
}

inline std::string parse_error(const std::string& text, const std::vector<std::string>& overrides = {}) {
  return error_of([&] { parse_scene(text, "t.yaml", overrides); });
}

inline bool starts_with(const std::string& s, const std::string& prefix) { return s.rfind(prefix, 0) == 0; }
inline bool contains(const std::string& s, const std::string& part) { return s.find(part) != std::string::npos; }

}  // namespace polyfloe::scene
