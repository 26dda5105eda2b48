// The scene schema's declaration against its reference: every declared key is documented in
// docs/scene-reference.md with its unit, default and choices, and every key the reference's tables list is declared.
#include <gtest/gtest.h>
#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "scene/scene_reader.h"

namespace polyfloe::scene {
namespace {

// The first table of each top-level section of the reference: section ("" = the top level) -> key -> cells.
using Table = std::map<std::string, std::vector<std::string>>;

std::string trim(const std::string& s) {
  const auto a = s.find_first_not_of(" \t");
  const auto b = s.find_last_not_of(" \t");
  return a == std::string::npos ? "" : s.substr(a, b - a + 1);
}

std::string unquote(std::string s) {
  s.erase(std::remove(s.begin(), s.end(), '`'), s.end());
  return trim(s);
}

std::map<std::string, Table> reference_tables() {
  std::ifstream in(std::string(POLYFLOE_SOURCE_DIR) + "/docs/scene-reference.md");
  EXPECT_TRUE(in) << "cannot read docs/scene-reference.md";
  std::map<std::string, Table> tables;
  std::string section, line;
  bool open = false, done = true;  // in the section's first table; that table read
  while (std::getline(in, line)) {
    if (line.rfind("## ", 0) == 0) {
      const auto a = line.find('`');
      section = line == "## Top level"   ? ""
                : a == std::string::npos ? "(other)"
                                         : line.substr(a + 1, line.find('`', a + 1) - a - 1);
      open = false;
      done = false;
      continue;
    }
    if (line.rfind("###", 0) == 0) done = true;
    const bool row = line.rfind("|", 0) == 0;
    if (!row) {
      if (open) done = true;
      open = false;
      continue;
    }
    if (done) continue;
    open = true;
    std::vector<std::string> cells;
    std::string cell;
    for (std::size_t i = 1; i < line.size(); ++i) {
      if (line[i] == '|' && line[i - 1] != '\\') {
        cells.push_back(trim(cell));
        cell.clear();
      } else {
        cell += line[i];
      }
    }
    if (cells.empty() || cells[0] == "key" || cells[0].rfind("---", 0) == 0) continue;
    tables[section][unquote(cells[0])] = cells;
  }
  return tables;
}

// Two YAML texts with the same value (numbers compared as numbers: 1.0e9 = 1e9).
bool same_value(const YAML::Node& a, const YAML::Node& b) {
  if (a.IsScalar() && b.IsScalar()) {
    double x = 0, y = 0;
    if (YAML::convert<double>::decode(a, x) && YAML::convert<double>::decode(b, y)) return x == y;
    return a.Scalar() == b.Scalar();
  }
  if (a.Type() != b.Type() || a.size() != b.size()) return false;
  if (a.IsSequence()) {
    for (std::size_t i = 0; i < a.size(); ++i)
      if (!same_value(a[i], b[i])) return false;
    return true;
  }
  if (a.IsMap()) {
    for (auto it = a.begin(); it != a.end(); ++it)
      if (!b[it->first.Scalar()] || !same_value(it->second, b[it->first.Scalar()])) return false;
    return true;
  }
  return false;
}

std::string unit_text(std::string u) { return u == "–" || u.empty() ? "-" : u; }

struct Where {
  std::string section, key;  // the key relative to its section
};
Where locate(const std::string& path) {
  const auto dot = path.find('.');
  if (dot == std::string::npos) return {"", path};
  return {path.substr(0, dot), path.substr(dot + 1)};
}

TEST(SceneSchema, EveryDeclaredKeyIsInTheReferenceWithItsUnitDefaultAndChoices) {
  const auto tables = reference_tables();
  const std::vector<SchemaKey> keys = schema_keys(Scene{}, true);
  std::map<std::string, const SchemaKey*> by_path;
  for (const SchemaKey& k : keys) by_path[k.path] = &k;
  int checked = 0;
  for (const SchemaKey& k : keys) {
    SCOPED_TRACE(k.path);
    const Where w = locate(k.path);
    const bool nested_block = k.kind == "block" && !w.section.empty();
    if (nested_block) continue;  // documented through its keys
    const auto t = tables.find(w.section);
    ASSERT_NE(t, tables.end()) << "docs/scene-reference.md has no table under '## `" << w.section << "`'";
    auto row = t->second.find(w.key);
    if (row == t->second.end()) {
      // A key of a block written on one line may be documented in its block's row.
      const auto parent = by_path.find(k.path.substr(0, k.path.rfind('.')));
      const bool in_flow = parent != by_path.end() && parent->second->kind == "flow";
      const auto flow_row = in_flow ? t->second.find(locate(parent->first).key) : t->second.end();
      if (flow_row != t->second.end()) {
        std::string text;
        for (const std::string& c : flow_row->second) text += c + " ";
        const std::string name = k.path.substr(k.path.rfind('.') + 1);
        EXPECT_NE(text.find(name), std::string::npos) << "the row of '" << parent->first << "' does not name it";
        ++checked;
        continue;
      }
      if (k.kind == "flow") continue;  // documented through its keys (checked one by one)
      ADD_FAILURE() << "not documented: no row `" << w.key << "` under '## `" << w.section << "`'";
      continue;
    }
    const std::vector<std::string>& cells = row->second;
    ASSERT_GE(cells.size(), 4u);
    if (!k.unit.empty()) {
      EXPECT_EQ(unit_text(cells[1]), unit_text(k.unit)) << "unit";
    }
    std::string text;
    for (const std::string& c : cells) text += c + " ";
    for (const std::string& word : k.choices) EXPECT_NE(text.find(word), std::string::npos) << "choice " << word;
    if (k.kind != "custom" && k.kind != "block" && k.kind != "flow" && !k.value.empty() && !cells[2].empty() &&
        k.path != "name") {
      YAML::Node documented;
      try {
        documented = YAML::Load(unquote(cells[2]));
      } catch (const YAML::Exception&) {
        ADD_FAILURE() << "default '" << cells[2] << "' is not a value";
        continue;
      }
      EXPECT_TRUE(same_value(documented, YAML::Load(k.value)))
          << "default: the reference says " << cells[2] << ", the code has " << k.value;
    }
    ++checked;
  }
  EXPECT_GT(checked, 80);
}

TEST(SceneSchema, EveryKeyInTheReferenceTablesIsDeclared) {
  std::map<std::string, std::string> declared;  // path -> kind
  for (const SchemaKey& k : schema_keys(Scene{}, true)) declared[k.path] = k.kind;
  int rows = 0;
  for (const auto& [section, table] : reference_tables()) {
    // (a list's section documents the keys of its items, which their own reader reads)
    if (section == "(other)" || (!section.empty() && declared[section] != "block")) continue;
    for (const auto& [key, cells] : table) {
      const std::string path = section.empty() ? key : section + "." + key;
      EXPECT_TRUE(declared.count(path)) << "docs/scene-reference.md documents '" << path << "', which no reader reads";
      ++rows;
    }
  }
  EXPECT_GT(rows, 80);
}

TEST(SceneSchema, EachKeyIsListedOnceWithAKnownKind) {
  const std::vector<SchemaKey> keys = schema_keys(Scene{}, true);
  std::map<std::string, int> seen;
  for (const SchemaKey& k : keys) {
    EXPECT_EQ(++seen[k.path], 1) << k.path;
    EXPECT_NE(std::string("number integer boolean text vec2 vec3 choice block flow custom").find(k.kind),
              std::string::npos)
        << k.path << ": " << k.kind;
    if (k.kind == "number" || k.kind == "vec2" || k.kind == "vec3") {
      EXPECT_FALSE(k.unit.empty()) << k.path;
    }
    if (k.kind == "choice") {
      EXPECT_GE(k.choices.size(), 2u) << k.path;
    }
  }
  // A scene without its optional blocks lists none of their keys.
  for (const SchemaKey& k : schema_keys(Scene{}, false))
    for (const char* block : {"floe_field", "ice_sheet", "channel", "spatial"})
      EXPECT_NE(k.path.rfind(block, 0), 0u) << k.path;
}

}  // namespace
}  // namespace polyfloe::scene
