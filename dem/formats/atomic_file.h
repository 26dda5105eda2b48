// Files that are either wholly old or wholly new: write a temporary sibling, fsync it, rename it over the target.
//
// A reader (ParaView polling a .pvd, a script tailing a run) never sees a half-written file, and a run killed at
// any instant leaves the previous complete version in place. rename(2) is atomic within one file system, which
// is why the temporary file lives in the target's own folder.
#pragma once

#include <filesystem>
#include <stdexcept>
#include <string>
#include <string_view>

namespace polyfloe::io {

// Base of every error the io module throws; the message names the file concerned.
class IoError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Replaces `path` by a file holding exactly `content` (created if absent). Throws IoError naming the file.
void write_file_atomic(const std::filesystem::path& path, std::string_view content);

// A name for a temporary file next to `target` (same folder, hidden, unique within this process), for writers
// that must produce the file themselves (e.g. VTK) before commit_file_atomic() moves it into place.
std::filesystem::path temporary_sibling(const std::filesystem::path& target);

// Flushes `temporary` to disk and renames it over `target`; on failure removes `temporary` and throws IoError.
void commit_file_atomic(const std::filesystem::path& temporary, const std::filesystem::path& target);

}  // namespace polyfloe::io
