// The scene schema, one read_*() function per block, on the schema walker of schema.h (the bodies' blocks in
// body_reader.cpp, the forcing block in forcing_reader.cpp); --set overrides.
#include "scene/scene_reader.h"

#include <yaml-cpp/depthguard.h>
#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cerrno>
#include <charconv>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <limits>
#include <map>
#include <optional>
#include <iomanip>
#include <sstream>
#include <utility>

#include "contact/narrow_phase_planar.h"
#include "scene/channel.h"
#include "scene/forcing_reader.h"
#include "scene/settings_schema.h"
#include "scene/yaml_format.h"
#include "scene/yaml_limits.h"

namespace polyfloe::scene {

using detail::fmt;
using detail::quoted;

namespace {

using namespace detail;

// run.steps_per_flat_contact sets the foundation force model's step for flat faces: a value is refused where it
// would be ignored (`why`: the scene's other contact law).
void check_flat_steps(const Context& ctx, const YAML::Node& root, const std::string& why) {
  const YAML::Node& tree = root;  // (const: looking up a key adds no node)
  const YAML::Node run = tree.IsMap() ? tree["run"] : YAML::Node();
  if (!run || !run.IsMap()) return;
  const YAML::Node& run_tree = run;
  if (const YAML::Node value = run_tree["steps_per_flat_contact"];
      value && !(value.IsScalar() && value.Scalar() == "auto"))  // (a resolved scene's text says auto)
    ctx.fail({value, YAML::Node(), "run.steps_per_flat_contact"},
             "applies to level floes under contact.force_model: foundation only (" + why +
                 "): remove it, or set contact.force_model: foundation");
}

void read_scene_tree(const Context& ctx, const YAML::Node& root, Scene& s) {
  MapReader top(ctx, {root, YAML::Node(), ""});
  scene_keys(top, s);
  const bool has_forcing = top.has("forcing");
  top.finish();
  if (s.spatial) {
    // Spatial scenes have polyhedra, gravity and buoyancy; level-floe content would be silently ignored.
    const char* planar_only = !s.bodies.empty()                ? "floes"
                              : s.floe_field                   ? "floe_field"
                              : s.ice_sheet                    ? "ice_sheet"
                              : s.channel                      ? "channel"
                              : has_forcing                    ? "forcing"
                              : s.output.velocity_grid.enabled ? "output.velocity_grid"
                              : s.output.vtk_pieces            ? "output.vtk_pieces"
                                                               : nullptr;
    if (planar_only)
      throw SceneError(s.spatial->source.where +
                       ": a spatial scene takes its bodies from 'spatial.bodies' and has "
                       "no drift forcing: remove '" +
                       planar_only + "' (or remove 'spatial' for a planar scene)");
    // How level floes touch (the overlap polygon's narrow phase and force model) does not apply to polyhedra,
    // whose contacts have one law (docs/model.md): a key naming it would be silently ignored.
    const YAML::Node& tree = root;  // (const: looking up a key adds no node)
    if (const YAML::Node contact = tree.IsMap() ? tree["contact"] : YAML::Node(); contact && contact.IsMap())
      for (const char* key : {"force_model", "narrow_phase"})
        if (const YAML::Node value = contact[key]; value)
          ctx.fail({value, YAML::Node(), std::string("contact.") + key},
                   "applies to level floes only; a spatial scene's polyhedra have one contact law (the Hertz law "
                   "at each contact point of their overlap, docs/model.md): remove it (or remove 'spatial' for a "
                   "planar scene)");
    check_flat_steps(ctx, root, "a spatial scene's polyhedra have one contact law (the Hertz law)");
    return;
  }
  check_forcing(ctx, top.self(), s);
  if (s.world.contact.force_model != contact::ForceModel::foundation)
    check_flat_steps(ctx, root,
                     std::string("this scene's contact.force_model is ") +
                         contact::force_model_name(s.world.contact.force_model) +
                         ", whose automatic step does not resolve flat faces apart");

  const bool dynamic_body = std::any_of(s.bodies.begin(), s.bodies.end(),
                                        [](const BodySpec& b) { return b.motion == dynamics::Motion::dynamic; });
  if (!dynamic_body && !s.floe_field && !s.ice_sheet) {
    throw SceneError(ctx.file() +
                     ":1:1: the scene has no dynamic body: list floes under 'floes' (motion: dynamic) "
                     "or generate them with 'floe_field' or 'ice_sheet'");
  }
}

// ---------------------------------------------------------------------------------------------------------------
// Overrides

bool is_index(const std::string& s) {
  return !s.empty() && s.size() < 10 &&
         std::all_of(s.begin(), s.end(), [](unsigned char c) { return std::isdigit(c); });
}

// Sets the value at keys[i..] below `node` (whose path is `path`), creating missing blocks.
void set_path(Context& ctx, YAML::Node node, const std::vector<std::string>& keys, std::size_t i,
              const std::string& path, const YAML::Node& value, const std::string& key) {
  const std::string& k = keys[i];
  const std::string child_path = join(path, k);
  const bool last = i + 1 == keys.size();
  const std::string where = "--set " + key + ": ";
  if (node.IsSequence()) {
    if (!is_index(k) || std::stoul(k) >= node.size())
      throw SceneError(where + "'" + path + "' is a list of " + std::to_string(node.size()) + " items; '" + k +
                       "' is not one of its indices 0.." + std::to_string(node.size()) + "-1");
    const std::size_t idx = std::stoul(k);
    if (last) {
      node[idx] = value;
      ctx.set_origin(child_path, key);
      return;
    }
    YAML::Node child = node[idx];
    set_path(ctx, child, keys, i + 1, child_path, value, key);
    return;
  }
  if (!node.IsMap())
    throw SceneError(where + "'" + path + "' is a single value, not a block of keys, so '" + child_path +
                     "' cannot be set");
  if (last) {
    node[k] = value;
    ctx.set_origin(child_path, key);
    return;
  }
  YAML::Node child;
  for (auto it = node.begin(); it != node.end(); ++it)
    if (it->first.IsScalar() && it->first.Scalar() == k) child.reset(it->second);
  if (!child.IsDefined() || child.IsNull()) {
    if (is_index(keys[i + 1]))
      throw SceneError(where + "there is no list '" + child_path + "' to take item " + keys[i + 1] + " from");
    node[k] = YAML::Node(YAML::NodeType::Map);
    child.reset(node[k]);
    ctx.set_origin(child_path, key);
  }
  set_path(ctx, child, keys, i + 1, child_path, value, key);
}

void apply_override(Context& ctx, YAML::Node& root, const std::string& arg) {
  const std::size_t eq = arg.find('=');
  if (eq == std::string::npos || eq == 0)
    throw SceneError("--set '" + arg + "': expected key.path=value (for example --set run.duration=60)");
  const std::string key = arg.substr(0, eq);
  const std::string text = arg.substr(eq + 1);
  std::vector<std::string> keys;
  for (std::size_t start = 0;;) {
    const std::size_t dot = key.find('.', start);
    keys.push_back(key.substr(start, dot == std::string::npos ? std::string::npos : dot - start));
    if (keys.back().empty()) throw SceneError("--set " + key + ": empty name in the key path");
    if (dot == std::string::npos) break;
    start = dot + 1;
  }
  YAML::Node value;
  try {
    value = YAML::Load(text);
  } catch (const YAML::Exception& e) {
    throw SceneError("--set " + key + ": cannot read the value '" + text + "' as YAML: " + e.msg);
  }
  check_tree_limits(value, "--set " + key);
  if (!root.IsMap()) root.reset(YAML::Node(YAML::NodeType::Map));
  set_path(ctx, root, keys, 0, "", value, key);
}

// yaml-cpp 0.7 accepts a quoted scalar left open at the end of the text (it folds the rest of the file into it):
// where the first quote that is never closed starts, if any.
std::optional<YAML::Mark> unclosed_quote(const std::string& text, const YAML::Node& n) {
  if (!n.IsDefined()) return std::nullopt;
  if (n.IsScalar()) {
    const int pos = n.Mark().pos;
    if (n.Mark().is_null() || pos < 0 || static_cast<std::size_t>(pos) >= text.size()) return std::nullopt;
    const char q = text[static_cast<std::size_t>(pos)];
    if (q != '"' && q != '\'') return std::nullopt;
    for (std::size_t i = static_cast<std::size_t>(pos) + 1; i < text.size(); ++i) {
      if (q == '"' && text[i] == '\\')
        ++i;  // an escape: skip the escaped character
      else if (q == '\'' && text.compare(i, 2, "''") == 0)
        ++i;  // '' is a quote inside a single-quoted string
      else if (text[i] == q)
        return std::nullopt;
    }
    return n.Mark();
  }
  for (auto it = n.begin(); it != n.end(); ++it) {
    const bool map = n.IsMap();
    for (const YAML::Node& child : map ? std::vector<YAML::Node>{it->first, it->second} : std::vector<YAML::Node>{*it})
      if (auto m = unclosed_quote(text, child)) return m;
  }
  return std::nullopt;
}

}  // namespace

// ---------------------------------------------------------------------------------------------------------------

Scene parse_scene(const std::string& text, const std::string& display_name, const std::vector<std::string>& overrides) {
  Context ctx(display_name);
  // A binary file (or one in UTF-16) would otherwise meet the YAML parser's escape or indentation errors.
  for (std::size_t i = 0, line = 1, column = 1; i < text.size(); ++i, ++column) {
    const auto c = static_cast<unsigned char>(text[i]);
    if (c == '\n') {
      ++line;
      column = 0;
    } else if ((c < 0x20 && c != '\t' && c != '\r') || c == 0x7f) {
      std::ostringstream msg;
      msg << display_name << ":" << line << ":" << column << ": not a text file: control byte 0x" << std::hex
          << std::setw(2) << std::setfill('0') << static_cast<int>(c) << " (a scene is YAML text, UTF-8)";
      throw SceneError(msg.str());
    }
  }
  YAML::Node root;
  try {
    root = YAML::Load(text);
  } catch (const YAML::DeepRecursion& e) {
    throw SceneError(display_name + ":" + std::to_string(e.mark.line + 1) + ":" + std::to_string(e.mark.column + 1) +
                     ": blocks nested more than " + std::to_string(e.depth()) + " levels deep (a scene nests some 5)");
  } catch (const YAML::ParserException& e) {
    throw SceneError(display_name + ":" + std::to_string(e.mark.line + 1) + ":" + std::to_string(e.mark.column + 1) +
                     ": YAML syntax error: " + e.msg);
  } catch (const YAML::Exception& e) {
    throw SceneError(display_name + ": cannot read YAML: " + e.msg);
  }
  check_tree_limits(root, display_name);  // before any other walk of the tree
  if (const auto open = unclosed_quote(text, root))
    throw SceneError(display_name + ":" + std::to_string(open->line + 1) + ":" + std::to_string(open->column + 1) +
                     ": YAML syntax error: the quoted string that starts here is never closed");
  if (root.IsDefined() && !root.IsNull() && !root.IsMap())
    throw SceneError(ctx.where({root, YAML::Node(), ""}) + ": a scene is a block of keys (name, run, ...), got " +
                     describe(root));
  for (const std::string& o : overrides) apply_override(ctx, root, o);
  if (!overrides.empty()) check_tree_limits(root, display_name);  // an override may use a block twice

  Scene s;
  // The default name is the file's stem, under the rule 'name:' follows (results/<name> must be a folder below
  // results/): a stem such as '..' (from '...yaml') or '.' falls back to "scene".
  s.name = std::filesystem::path(display_name).stem().string();
  if (s.name.empty() || s.name == "." || s.name == ".." || s.name.size() > 200) s.name = "scene";
  s.source_path = display_name;
  s.source_text = text;
  s.overrides = overrides;
  try {
    read_scene_tree(ctx, root, s);
  } catch (const YAML::Exception& e) {  // should not happen: every access above is checked
    throw SceneError(display_name + ": " + e.what());
  }
  return s;
}

Scene read_scene(const std::filesystem::path& file, const std::vector<std::string>& overrides) {
  return parse_scene(read_text_file(file, kMaxSceneBytes, "scene file"), file.string(), overrides);
}

}  // namespace polyfloe::scene
