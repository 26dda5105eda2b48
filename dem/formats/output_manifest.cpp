#include "formats/output_manifest.h"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <fstream>
#include <sstream>

#include "formats/atomic_file.h"

namespace polyfloe::io {

bool is_plain_relative_path(const std::string& relative) {
  if (relative.empty() || relative.front() == '/' || relative.size() > 4096) return false;
  std::string s = relative;
  if (s.back() == '/') s.pop_back();
  std::size_t start = 0;
  while (true) {
    const std::size_t slash = s.find('/', start);
    const std::string part = s.substr(start, slash == std::string::npos ? std::string::npos : slash - start);
    if (part.empty() || part == "." || part == "..") return false;
    for (const char c : part)
      if (static_cast<unsigned char>(c) < 0x20) return false;
    if (slash == std::string::npos) return true;
    start = slash + 1;
  }
}

bool remove_plain_entry(const std::filesystem::path& dir, const std::string& relative) {
  namespace fs = std::filesystem;
  if (!is_plain_relative_path(relative)) return false;
  std::error_code ec;
  fs::path p = dir;
  const fs::path rel(relative.back() == '/' ? relative.substr(0, relative.size() - 1) : relative);
  for (auto it = rel.begin(); it != rel.end(); ++it) {
    p /= *it;
    const fs::file_status st = fs::symlink_status(p, ec);
    if (ec || fs::is_symlink(st)) return false;
    if (std::next(it) != rel.end() && !fs::is_directory(st)) return false;
    if (std::next(it) == rel.end()) {
      if (relative.back() == '/' ? !fs::is_directory(st) : !fs::is_regular_file(st)) return false;
    }
  }
  return fs::remove(p, ec) && !ec;  // a folder only when empty
}

namespace {

// NAME for a temporary sibling ".NAME.tmp.<pid>.<n>" (io::temporary_sibling), else empty. (A plain scan: GCC 12
// warns inside <regex> under the sanitizers.)
std::string temporary_of(const std::string& f) {
  auto digits_back = [&](std::size_t end) {  // start of the run of digits that ends at `end`, or npos
    std::size_t i = end;
    while (i > 0 && f[i - 1] >= '0' && f[i - 1] <= '9') --i;
    return i < end ? i : std::string::npos;
  };
  if (f.size() < 2 || f[0] != '.') return {};
  const std::size_t n = digits_back(f.size());
  if (n == std::string::npos || n < 1 || f[n - 1] != '.') return {};
  const std::size_t pid = digits_back(n - 1);
  if (pid == std::string::npos || pid < 5 || f.compare(pid - 5, 5, ".tmp.") != 0) return {};
  return pid - 5 > 1 ? f.substr(1, pid - 6) : std::string();
}

}  // namespace

void remove_temporaries(const std::filesystem::path& dir, const std::string& folder,
                        const std::set<std::string>& listed) {
  namespace fs = std::filesystem;
  std::error_code ec;
  if (!folder.empty() && !is_plain_relative_path(folder)) return;
  const fs::path where = dir / folder;
  if (fs::is_symlink(fs::symlink_status(where, ec))) return;
  std::vector<std::string> doomed;
  for (const auto& entry : fs::directory_iterator(where, ec)) {
    const std::string f = entry.path().filename().string();
    if (const std::string of = temporary_of(f); !of.empty() && listed.count(folder + of)) doomed.push_back(folder + f);
  }
  for (const std::string& d : doomed) remove_plain_entry(dir, d);
}

void OutputManifest::remove_temporaries(const std::string& folder) const {
  io::remove_temporaries(dir_, folder, entries_);
}

bool OutputManifest::remove_file(const std::string& relative) const {
  return lists(relative) && remove_plain_entry(dir_, relative);
}

std::vector<std::string> OutputManifest::read(const std::filesystem::path& dir) {
  std::vector<std::string> out;
  std::ifstream in(dir / kFileName, std::ios::binary);
  std::set<std::string> seen;
  for (std::string line; std::getline(in, line);) {
    if (!is_plain_relative_path(line) || !seen.insert(line).second) continue;
    out.push_back(line);
  }
  return out;
}

OutputManifest::OutputManifest(const std::filesystem::path& dir, bool keep) : dir_(dir) {
  const std::filesystem::path file = dir / kFileName;
  if (keep)
    for (const std::string& e : read(dir)) entries_.insert(e);
  // O_NOFOLLOW: the list is never written through a link.
  fd_ = ::open(file.c_str(), O_WRONLY | O_CREAT | O_APPEND | O_CLOEXEC | O_NOFOLLOW | (keep ? 0 : O_TRUNC), 0644);
  if (fd_ < 0) throw IoError("cannot open " + file.string() + ": " + std::strerror(errno));
}

OutputManifest::~OutputManifest() {
  if (fd_ >= 0) ::close(fd_);
}

void OutputManifest::record(const std::string& relative) {
  if (!entries_.insert(relative).second) return;
  const std::string line = relative + "\n";
  const char* p = line.data();
  std::size_t left = line.size();
  while (left > 0) {
    const ssize_t n = ::write(fd_, p, left);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) throw IoError("cannot write " + (dir_ / kFileName).string() + ": " + std::strerror(errno));
    p += n;
    left -= static_cast<std::size_t>(n);
  }
}

}  // namespace polyfloe::io
