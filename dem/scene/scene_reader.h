// Reads a YAML scene (schema: docs/scene-reference.md) into a validated Scene.
//
// Every error is a SceneError whose message starts with where the bad value is and the full dotted key path:
//   channel.yaml:12:5: key 'contact.restitution': 1.5 is outside the allowed range (0, 1] [-]
//   --set contact.restitution: key 'contact.restitution': 1.5 is outside the allowed range (0, 1] [-]
// Unknown keys (listing the allowed ones), wrong types, out-of-range and non-finite numbers, YAML syntax errors and
// a scene without any dynamic body are all reported this way.
//
// Overrides are "key.path=value" strings (the command line's --set), applied to the YAML tree before validation.
// The value is parsed as YAML (so "forcing.ocean.current=[0.5, 0]" sets a list); list items are addressed by
// index ("floes.0.position=[1, 2]"); missing blocks on the way are created.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "scene/scene.h"

namespace polyfloe::scene {

// Reads and validates `file`; a missing or unreadable file is a SceneError naming it. Records source_path (the
// path as given), source_text and overrides in the Scene. The default name is the file's stem.
Scene read_scene(const std::filesystem::path& file, const std::vector<std::string>& overrides = {});

// Same from text; `display_name` is used in messages and as source_path, and its stem is the default name.
Scene parse_scene(const std::string& text, const std::string& display_name,
                  const std::vector<std::string>& overrides = {});

// Every resolved setting as YAML, with its unit in a comment; parse_scene() of this text gives the same settings.
// Explicit bodies given as 'regular' or 'rectangle' appear as their polygon; yaw_deg appears as yaw [rad].
std::string resolved_yaml(const Scene& scene);

// One key of the scene schema, as the settings' declaration gives it (for the check of docs/scene-reference.md
// and the tests' comparison of scenes).
struct SchemaKey {
  std::string path;                  // dotted: "output.velocity_grid.cell"
  std::string kind;                  // number, integer, boolean, text, vec2, vec3, choice, block, flow, custom
  std::string unit;                  // "m", "-", ...; empty where the key has none
  std::vector<std::string> choices;  // the words a choice takes
  std::string value;                 // its value in the scene, as the resolved scene writes it (blocks: empty)
  std::string comment;               // the resolved scene's comment
};
// Every key of `scene` in the declared order. An optional block the scene lacks is listed with its defaults when
// `with_absent` (the whole schema: schema_keys(Scene{}, true)), else left out.
std::vector<SchemaKey> schema_keys(const Scene& scene, bool with_absent);

}  // namespace polyfloe::scene
