#include "scene/yaml_limits.h"

#include <sys/stat.h>

#include <cerrno>
#include <cstring>
#include <fstream>
#include <vector>

#include "scene/scene.h"

namespace polyfloe::scene::detail {

namespace {

std::string mib(std::uintmax_t bytes) {
  const double m = static_cast<double>(bytes) / (1u << 20);
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.1f MiB", m);
  return buf;
}

std::string at(const std::string& where, const YAML::Node& n) {
  if (!n.IsDefined() || n.Mark().is_null()) return where;
  return where + ":" + std::to_string(n.Mark().line + 1) + ":" + std::to_string(n.Mark().column + 1);
}

class TreeWalk {
 public:
  explicit TreeWalk(const std::string& where) : where_(where) {}

  void visit(const YAML::Node& n) {
    if (++visited_ > kMaxYamlValues)
      throw SceneError(where_ + ": the YAML tree holds more than " + std::to_string(kMaxYamlValues) +
                       " values once its aliases are expanded (each use of an alias (*name) copies the block its "
                       "anchor (&name) marks); write the values out, or nest fewer aliases");
    for (const YAML::Node& ancestor : path_)
      if (ancestor.is(n))
        throw SceneError(at(where_, n) +
                         ": a recursive YAML alias: the block anchored here is used (*name) inside "
                         "itself, which makes the tree infinite; refer to a block only outside it");
    if (!n.IsMap() && !n.IsSequence()) return;
    if (static_cast<int>(path_.size()) >= kMaxYamlDepth)
      throw SceneError(at(where_, n) + ": blocks nested more than " + std::to_string(kMaxYamlDepth) +
                       " levels deep (a scene nests some 5)");
    path_.push_back(n);
    for (auto it = n.begin(); it != n.end(); ++it) {
      if (n.IsMap()) {
        visit(it->first);
        visit(it->second);
      } else {
        visit(*it);
      }
    }
    path_.pop_back();
  }

 private:
  const std::string& where_;
  std::vector<YAML::Node> path_;
  std::size_t visited_ = 0;
};

}  // namespace

std::string read_text_file(const std::filesystem::path& file, std::uintmax_t max_bytes, const std::string& what) {
  const std::string name = file.string();
  struct stat st {};
  if (::stat(file.c_str(), &st) != 0)
    throw SceneError(name + ": cannot read the " + what + ": " + std::strerror(errno));
  if (S_ISDIR(st.st_mode)) throw SceneError(name + ": cannot read the " + what + ": it is a directory");
  if (!S_ISREG(st.st_mode))
    throw SceneError(name + ": cannot read the " + what + ": not a regular file (a device, FIFO or socket)");
  if (static_cast<std::uintmax_t>(st.st_size) > max_bytes)
    throw SceneError(name + ": the " + what + " is " + mib(static_cast<std::uintmax_t>(st.st_size)) + "; at most " +
                     mib(max_bytes) + " is read");
  std::ifstream in(file, std::ios::binary);
  if (!in) throw SceneError(name + ": cannot read the " + what + ": " + std::strerror(errno));
  // One byte more than the file's size: reading it all means the file grew while being read.
  std::string text;
  text.resize(static_cast<std::size_t>(st.st_size) + 1);
  in.read(text.data(), static_cast<std::streamsize>(text.size()));
  if (in.bad()) throw SceneError(name + ": cannot read the " + what + ": " + std::strerror(errno));
  if (static_cast<std::size_t>(in.gcount()) == text.size())
    throw SceneError(name + ": the " + what + " changed while being read");
  text.resize(static_cast<std::size_t>(in.gcount()));
  return text;
}

void check_tree_limits(const YAML::Node& root, const std::string& where) { TreeWalk(where).visit(root); }

}  // namespace polyfloe::scene::detail
