// The output folder contract, enforced here and nowhere else (docs/user-guide.md, "The output folder"):
//   - the folder is resolved once (symbolic links resolved); '/', the home folder, the current folder's ancestors and
//     system folders (/etc, /usr, /proc, ...) are refused;
//   - a run holds an exclusive lock (.polyfloe-lock, flock) for its lifetime: a second run into the folder is
//     refused, naming the first's process;
//   - every file a run writes is listed in the folder's manifest (io::OutputManifest) before it is made, and a new
//     run removes only what the previous run's manifest lists, never following a link;
//   - an entry the run would write (results.h5, floes/, checkpoints/, ...) that exists but is not listed, or is a
//     link, a file where a folder belongs or the reverse, is refused: polyfloe never replaces what it did not write.
// Every refusal is an OutputFolderError (bad input: exit 2) thrown before anything is created or, when the folder had
// to be made, after it is removed again.
#pragma once

#include <filesystem>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "formats/output_manifest.h"

namespace polyfloe::run {

class OutputFolderError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

class OutputFolder {
 public:
  enum class Mode {
    fresh,   // a new run: the previous run's listed files are removed
    resume,  // a restart: the run goes on with the files of the run it continues
  };
  static constexpr const char* kLockName = ".polyfloe-lock";

  // `requested` made absolute with its links resolved, after the checks that need nothing created (a refused
  // location, a name too long, a part of it that is a file). Throws OutputFolderError.
  static std::filesystem::path resolve(const std::filesystem::path& requested);

  // The checks the constructor makes on the entries a run writes (the same for a fresh and a resumed run),
  // without creating or locking anything, so that a refusal comes before any other work. Throws OutputFolderError.
  static void check(const std::filesystem::path& resolved);

  // Creates the folder if needed, takes the lock, checks the entries and, for a fresh run, removes the previous
  // run's files. Throws OutputFolderError (then leaves nothing it made behind).
  OutputFolder(const std::filesystem::path& requested, Mode mode);
  ~OutputFolder();
  OutputFolder(const OutputFolder&) = delete;
  OutputFolder& operator=(const OutputFolder&) = delete;

  const std::filesystem::path& path() const { return path_; }
  io::OutputManifest& manifest() { return *manifest_; }

  // The names (relative to the folder) of every top-level entry a run of either kind may write.
  static const std::vector<std::string>& entries();

 private:
  std::filesystem::path path_;
  int lock_fd_ = -1;
  std::unique_ptr<io::OutputManifest> manifest_;
};

}  // namespace polyfloe::run
