// The list of the files a run wrote into its output folder, kept in the folder itself (.polyfloe-manifest, one
// path relative to the folder per line; folders end in '/'). It is what lets a later run clean the folder without
// deleting anything it did not write: the clean-up removes listed files only.
//
// Entries are appended, each with one write(2), before the file they name is created, so a run killed at any moment
// leaves a list that covers every file it made (and perhaps one not yet made).
#pragma once

#include <filesystem>
#include <set>
#include <string>
#include <vector>

namespace polyfloe::io {

class OutputManifest {
 public:
  static constexpr const char* kFileName = ".polyfloe-manifest";

  // The entries of DIR's manifest (none when there is none). Lines that are not a plain relative path inside the
  // folder (absolute, '..', '.', empty parts) are dropped: the list is input like any other.
  static std::vector<std::string> read(const std::filesystem::path& dir);

  // Opens DIR's manifest for appending. `keep`: go on from the entries already there (a resumed run); otherwise
  // the list starts empty. Throws IoError naming the file.
  OutputManifest(const std::filesystem::path& dir, bool keep);
  ~OutputManifest();
  OutputManifest(const OutputManifest&) = delete;
  OutputManifest& operator=(const OutputManifest&) = delete;

  // Adds `relative` (a file, or a folder ending in '/') if not yet listed. Throws IoError.
  void record(const std::string& relative);
  bool lists(const std::string& relative) const { return entries_.count(relative) != 0; }
  const std::set<std::string>& entries() const { return entries_; }
  // Removes the listed file `relative` if it is a regular file reached without links (see remove_plain_file);
  // it stays listed. Returns whether a file was removed.
  bool remove_file(const std::string& relative) const;
  // Removes the hidden temporaries a killed writer left in `folder` (relative, "" for the top, else ending in '/')
  // beside listed files (io::temporary_sibling's ".<name>.tmp.<pid>.<n>").
  void remove_temporaries(const std::string& folder) const;
  const std::filesystem::path& directory() const { return dir_; }

 private:
  std::filesystem::path dir_;
  std::set<std::string> entries_;
  int fd_ = -1;
};

// Whether `relative` is a plain path inside a folder: relative, no '.', '..' or empty parts.
bool is_plain_relative_path(const std::string& relative);

// Removes DIR/relative if it is a regular file and no part of the way to it (below DIR) is a link; a folder is
// removed only when empty. Returns whether it removed something.
bool remove_plain_entry(const std::filesystem::path& dir, const std::string& relative);

// Removes DIR/folder/.<name>.tmp.<pid>.<n> for every folder/<name> in `listed` (`folder` as in
// OutputManifest::remove_temporaries), never through a link.
void remove_temporaries(const std::filesystem::path& dir, const std::string& folder,
                        const std::set<std::string>& listed);

}  // namespace polyfloe::io
