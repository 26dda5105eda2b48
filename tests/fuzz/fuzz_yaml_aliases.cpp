// libFuzzer target: YAML anchors and aliases (scene::parse_scene's alias layer, scene/yaml_limits.h).
//
// The input is a program, not text: each byte pair picks one of a few YAML fragments built around anchors &a0..&a7
// and aliases *a0..*a7 (lists and maps of aliases, an alias inside the block it anchors, blocks nested in blocks,
// aliases standing for whole scene blocks such as run: or floes:), so that libFuzzer explores the shapes that once
// crashed or hung the reader (a recursive alias, "billion laughs") instead of spending its time on YAML syntax.
// The text is parsed as a scene, with the last fragments also given as --set overrides.
//
// What must hold: parse_scene returns or throws SceneError (it reports recursive aliases, trees of more than
// kMaxYamlValues values with aliases expanded and blocks nested too deep as bad input); an execution stays within
// libFuzzer's time limit (the script's -timeout=10) whatever the aliases multiply to. Any other exception, a crash,
// a sanitizer report or a time-out is a finding.
#include <fuzzer/FuzzedDataProvider.h>

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <string>
#include <vector>

#include "scene/scene.h"
#include "scene/scene_reader.h"

namespace {

std::string anchor(int k) { return "&a" + std::to_string(k); }
std::string alias(int k) { return "*a" + std::to_string(k); }

// One fragment: a top-level key with a value built from anchors and aliases.
std::string fragment(FuzzedDataProvider& in, int& next_anchor) {
  const int op = in.ConsumeIntegralInRange<int>(0, 11);
  const int k = next_anchor;
  const int used = next_anchor > 0 ? in.ConsumeIntegralInRange<int>(0, next_anchor - 1) : 0;
  const int fan = in.ConsumeIntegralInRange<int>(1, 12);
  auto list_of = [&](const std::string& item) {
    std::string s = "[";
    for (int i = 0; i < fan; ++i) s += (i ? ", " : "") + item;
    return s + "]";
  };
  const std::string key = "k" + std::to_string(in.ConsumeIntegralInRange<int>(0, 40));
  switch (op) {
    case 0: next_anchor += next_anchor < 8; return key + ": " + anchor(k % 8) + " [lol, 1, 2.5]";
    case 1:
      next_anchor += next_anchor < 8;
      return key + ": " + anchor(k % 8) + " " + list_of(next_anchor > 1 ? alias(used) : "x");
    case 2: next_anchor += next_anchor < 8; return key + ": " + anchor(k % 8) + " [" + alias(k % 8) + "]";  // recursive
    case 3:
      next_anchor += next_anchor < 8;
      return key + ": " + anchor(k % 8) + " {a: " + alias(used) + ", b: [" + alias(k % 8) + "]}";
    case 4: return "run: " + alias(used);
    case 5: return "floes: " + list_of(alias(used));
    case 6: next_anchor += next_anchor < 8; return "run: " + anchor(k % 8) + " {duration: " + alias(k % 8) + "}";
    case 7: next_anchor += next_anchor < 8; return "floes: " + anchor(k % 8) + " [" + alias(k % 8) + "]";
    case 8:
      next_anchor += next_anchor < 8;
      return key + ": " + anchor(k % 8) + " " + std::string(static_cast<std::size_t>(fan) * 3, '[') + alias(used) +
             std::string(static_cast<std::size_t>(fan) * 3, ']');
    case 9: return key + ": {" + alias(used) + ": 1}";  // an alias as a key
    case 10: return "<<: " + alias(used);
    default: return key + ": " + alias(in.ConsumeIntegralInRange<int>(0, 9));  // perhaps undefined
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  FuzzedDataProvider in(data, size);
  std::string text = "run: {duration: 1}\nfloes:\n  - rectangle: {width: 10, height: 10}\n";
  std::vector<std::string> overrides;
  int anchors = 0;
  const int n = in.ConsumeIntegralInRange<int>(1, 24);
  for (int i = 0; i < n && in.remaining_bytes() > 0; ++i) {
    const std::string f = fragment(in, anchors);
    if (in.ConsumeBool() && f.find(": ") != std::string::npos) {
      const std::size_t colon = f.find(": ");
      overrides.push_back(f.substr(0, colon) + "=" + f.substr(colon + 2));
    } else {
      text += f + "\n";
    }
  }
  try {
    (void)polyfloe::scene::parse_scene(text, "fuzz.yaml", overrides);
  } catch (const polyfloe::scene::SceneError&) {
    // bad input, reported
  } catch (const std::exception& e) {
    std::fprintf(stderr, "fuzz_yaml_aliases: parse_scene threw %s\n--- scene:\n%s\n", e.what(), text.c_str());
    std::abort();
  }
  return 0;
}
