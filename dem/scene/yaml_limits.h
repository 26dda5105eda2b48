// The limits that make reading a scene safe on any input (internal to dem/scene): the file is checked before it is
// read (a regular file of at most kMaxSceneBytes; a device, FIFO or folder is refused), and the YAML tree is walked
// once, before anything else reads it, so that no later walk can loop or explode:
//   - an alias that refers to a block containing it (`a: &x [*x]`) is refused: the tree would be infinite;
//   - every use of an alias copies its block, so a small file can stand for a huge tree ("billion laughs": ten
//     levels of ten aliases is 10^10 values): the values, counted with every alias expanded, are capped at
//     kMaxYamlValues;
//   - blocks nested deeper than kMaxYamlDepth are refused (scenes nest five deep).
#pragma once

#include <yaml-cpp/yaml.h>

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <string>

namespace polyfloe::scene::detail {

constexpr std::uintmax_t kMaxSceneBytes = 16u << 20;  // [bytes] 16 MiB: some 200,000 explicit floes
constexpr std::size_t kMaxYamlValues = 4'000'000;     // [-] nodes with aliases expanded
constexpr int kMaxYamlDepth = 64;                     // [-] nested blocks

// The whole of `file`, a regular file of at most `max_bytes`; a SceneError naming it (and `what` it was meant to
// be) otherwise. The size is checked before reading, and again while reading (a file that grows is cut off).
std::string read_text_file(const std::filesystem::path& file, std::uintmax_t max_bytes, const std::string& what);

// Walks `root` once with aliases expanded and throws SceneError, starting with `where` (a file name or a --set
// key), on a recursive alias, a tree of more than kMaxYamlValues values or deeper than kMaxYamlDepth.
void check_tree_limits(const YAML::Node& root, const std::string& where);

}  // namespace polyfloe::scene::detail
