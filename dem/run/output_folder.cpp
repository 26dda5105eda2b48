#include "run/output_folder.h"

#include <fcntl.h>
#include <pwd.h>
#include <sys/file.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <climits>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <set>

#include "formats/atomic_file.h"
#include "run/simulation.h"

namespace polyfloe::run {

namespace fs = std::filesystem;

namespace {

const char* const kHint = "; choose another with -o DIR";

[[noreturn]] void refuse(const fs::path& dir, const std::string& why) {
  throw OutputFolderError("output folder " + dir.string() + ": " + why + kHint);
}

// Folders a run must never write into, nor below (the system's own).
bool is_system_folder(const fs::path& p) {
  static const char* const below[] = {"/bin",     "/boot",      "/dev",      "/etc",        "/lib", "/lib32",
                                      "/lib64",   "/libx32",    "/proc",     "/sbin",       "/sys", "/usr",
                                      "/var/log", "/var/spool", "/var/mail", "/var/backups"};
  static const char* const exactly[] = {"/",          "/home", "/root", "/tmp",   "/var", "/var/tmp", "/var/lib",
                                        "/var/cache", "/run",  "/mnt",  "/media", "/opt", "/srv",     "/snap"};
  const std::string s = p.string();
  for (const char* e : exactly)
    if (s == e) return true;
  for (const char* b : below) {
    const std::string base = b;
    if (s == base || s.rfind(base + "/", 0) == 0) return true;
  }
  return false;
}

fs::path home_folder() {
  std::error_code ec;
  std::vector<std::string> candidates;
  if (const char* h = std::getenv("HOME"); h && *h) candidates.emplace_back(h);
  if (const passwd* pw = ::getpwuid(::geteuid()); pw && pw->pw_dir) candidates.emplace_back(pw->pw_dir);
  for (const std::string& c : candidates) {
    const fs::path p = fs::weakly_canonical(c, ec);
    if (!ec) return p;
  }
  return {};
}

// The entries the run writes that exist: each must be listed by the previous run's manifest, as the kind of
// entry the run writes (a folder: 'name/'), and not be a link.
void check_entries(const fs::path& dir, const std::vector<std::string>& listed) {
  const std::set<std::string> list(listed.begin(), listed.end());
  std::error_code ec;
  for (const std::string& name : OutputFolder::entries()) {
    const fs::path p = dir / name;
    const fs::file_status st = fs::symlink_status(p, ec);
    if (ec || !fs::exists(st)) continue;
    const bool folder = name == "floes" || name == "contacts" || name == "bonds" || name == "velocity" ||
                        name == "bodies" || name == "checkpoints";
    if (fs::is_symlink(st))
      refuse(dir, name +
                      " is a symbolic link: a run writes only inside its output folder and never through "
                      "links; remove the link");
    if (folder && !fs::is_directory(st))
      refuse(dir, name + " is not a folder; the run writes its " + name + " frames there: move it away");
    if (!folder && !fs::is_regular_file(st))
      refuse(dir, name + " is not a regular file; the run writes its " + name + " there: move it away");
    if (!list.count(folder ? name + "/" : name))
      refuse(dir, name + " exists but no polyfloe run into this folder wrote it (" +
                      std::string(io::OutputManifest::kFileName) +
                      " does not list it); polyfloe never replaces files it did not write: move it away");
  }
}

// Removes the previous run's listed files (and the hidden temporaries made while writing them), then its listed
// folders that this leaves empty, deepest first.
void remove_previous_run(const fs::path& dir, const std::vector<std::string>& listed) {
  std::vector<std::string> folders;
  std::set<std::string> files_in_folder;  // "sub/" -> listed files there, for temporaries
  for (const std::string& e : listed) {
    if (e.back() == '/') {
      folders.push_back(e);
      continue;
    }
    io::remove_plain_entry(dir, e);
    const std::size_t slash = e.rfind('/');
    files_in_folder.insert(slash == std::string::npos ? std::string() : e.substr(0, slash + 1));
  }
  // The hidden temporaries a killed writer left beside listed names, in the folders the run made (or the top).
  const std::set<std::string> names(listed.begin(), listed.end());
  for (const std::string& sub : files_in_folder)
    if (sub.empty() || names.count(sub)) io::remove_temporaries(dir, sub, names);
  std::sort(folders.begin(), folders.end(), [](const std::string& a, const std::string& b) {
    return std::count(a.begin(), a.end(), '/') > std::count(b.begin(), b.end(), '/');
  });
  for (const std::string& f : folders) io::remove_plain_entry(dir, f);
}

std::string lock_holder(const fs::path& lock) {
  std::ifstream in(lock);
  std::string pid;
  std::getline(in, pid);
  pid.erase(std::remove_if(pid.begin(), pid.end(), [](char c) { return c < '0' || c > '9'; }), pid.end());
  return pid.empty() ? std::string("another polyfloe run") : "another polyfloe run (process " + pid + ")";
}

}  // namespace

const std::vector<std::string>& OutputFolder::entries() {
  static const std::vector<std::string> names{"scene.resolved.yaml", "results.h5",       "floes.pvd",  "floes",
                                              "contacts.pvd",        "contacts",         "bonds.pvd",  "bonds",
                                              "velocity.pvd",        "velocity",         "bodies.pvd", "bodies",
                                              "checkpoints",         kInterruptedResults};
  return names;
}

fs::path OutputFolder::resolve(const fs::path& requested) {
  if (requested.empty()) throw OutputFolderError("output folder: an empty name; give a folder with -o DIR");
  std::error_code ec;
  const fs::path absolute = fs::absolute(requested, ec);
  if (ec) refuse(requested, ec.message());
  for (const fs::path& part : absolute)
    if (part.string().size() > NAME_MAX)
      refuse(requested, "the name '" + part.string().substr(0, 40) + "...' has " +
                            std::to_string(part.string().size()) + " bytes; a folder name has at most " +
                            std::to_string(NAME_MAX));
  // The existing part of the path, with its links resolved; every part of it must be a folder.
  fs::path existing = absolute, rest;
  while (!fs::exists(fs::symlink_status(existing, ec))) {
    if (!existing.has_relative_path()) break;
    rest = existing.filename() / rest;
    existing = existing.parent_path();
  }
  if (fs::is_symlink(fs::symlink_status(existing, ec)) && !fs::exists(fs::status(existing, ec)))
    refuse(requested, existing.string() + " is a symbolic link to " + fs::read_symlink(existing, ec).string() +
                          ", which does not exist (or is a loop of links)");
  const fs::path real = fs::canonical(existing, ec);
  if (ec) refuse(requested, existing.string() + ": " + ec.message());
  if (!fs::is_directory(real, ec)) refuse(requested, real.string() + " is not a folder");
  const fs::path resolved = (rest.empty() ? real : real / rest).lexically_normal();
  fs::path dir = resolved;
  if (dir.has_filename() == false && dir.has_relative_path()) dir = dir.parent_path();

  if (const fs::path home = home_folder(); !home.empty() && dir == home)
    refuse(requested, "the home folder itself; give a folder below it");
  if (is_system_folder(dir))
    refuse(requested, "a system folder (" + dir.string() + "); a run writes only into a folder of its own");
  const fs::path cwd = fs::weakly_canonical(fs::current_path(ec), ec);
  if (!ec && dir != cwd) {
    const auto [d, c] = std::mismatch(dir.begin(), dir.end(), cwd.begin(), cwd.end());
    if (d == dir.end()) refuse(requested, "a folder above the current folder; give a folder of its own");
  }
  if (access(real.c_str(), W_OK | X_OK) != 0)
    refuse(requested, (rest.empty() ? std::string("it is") : real.string() + " is") + " not writable (" +
                          std::strerror(errno) + ")");
  return dir;
}

void OutputFolder::check(const fs::path& resolved) {
  std::error_code ec;
  if (!fs::exists(fs::symlink_status(resolved, ec))) return;  // a new folder: nothing there to collide with
  for (const char* own : {kLockName, io::OutputManifest::kFileName}) {
    const fs::file_status st = fs::symlink_status(resolved / own, ec);
    if (fs::exists(st) && !fs::is_regular_file(st))
      refuse(resolved, std::string(own) + " (polyfloe's own) is not a regular file: remove it");
  }
  check_entries(resolved, io::OutputManifest::read(resolved));
}

OutputFolder::OutputFolder(const fs::path& requested, Mode mode) : path_(resolve(requested)) {
  std::error_code ec;
  // The folders this creates, outermost first, so that a refusal removes them again.
  std::vector<fs::path> made;
  for (fs::path p = path_; !fs::exists(fs::symlink_status(p, ec)); p = p.parent_path()) made.insert(made.begin(), p);
  bool lock_made = false;
  auto undo = [&] {
    if (lock_fd_ >= 0) ::close(lock_fd_);
    lock_fd_ = -1;
    manifest_.reset();
    if (lock_made) fs::remove(path_ / kLockName, ec);
    for (auto it = made.rbegin(); it != made.rend(); ++it) fs::remove(*it, ec);
  };
  try {
    for (const fs::path& p : made)
      if (!fs::create_directory(p, ec) && ec) refuse(path_, "cannot create " + p.string() + ": " + ec.message());
    const fs::path lock = path_ / kLockName;
    lock_made = !fs::exists(fs::symlink_status(lock, ec));
    lock_fd_ = ::open(lock.c_str(), O_RDWR | O_CREAT | O_CLOEXEC | O_NOFOLLOW, 0644);
    if (lock_fd_ < 0) refuse(path_, "cannot open the lock file " + lock.string() + ": " + std::strerror(errno));
    if (::flock(lock_fd_, LOCK_EX | LOCK_NB) != 0) {
      lock_made = false;  // the other run's
      refuse(path_, lock_holder(lock) + " is writing into it; wait for it to end");
    }
    const std::string pid = std::to_string(::getpid()) + "\n";
    if (::ftruncate(lock_fd_, 0) != 0 || ::pwrite(lock_fd_, pid.data(), pid.size(), 0) < 0)
      refuse(path_, "cannot write the lock file " + lock.string() + ": " + std::strerror(errno));
    const std::vector<std::string> listed = io::OutputManifest::read(path_);
    check_entries(path_, listed);
    if (mode == Mode::fresh) remove_previous_run(path_, listed);
    manifest_ = std::make_unique<io::OutputManifest>(path_, mode == Mode::resume);
    // A folder the previous run made that the clean-up left (your files are in it) stays the program's: listed
    // again, so that a later run may write there even if this one does not.
    for (const std::string& e : listed)
      if (e.back() == '/' && fs::is_directory(fs::symlink_status(path_ / e.substr(0, e.size() - 1), ec)))
        manifest_->record(e);
  } catch (const OutputFolderError&) {
    undo();
    throw;
  } catch (const std::exception& e) {
    undo();
    refuse(path_, e.what());
  }
}

OutputFolder::~OutputFolder() {
  manifest_.reset();
  if (lock_fd_ >= 0) ::close(lock_fd_);  // releases the lock; the file stays (removing it would race a waiting run)
}

}  // namespace polyfloe::run
