#include "formats/atomic_file.h"

#include <fcntl.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstring>
#include <system_error>

namespace polyfloe::io {
namespace {

std::string errno_text(int err) { return std::generic_category().message(err); }

// Owns a POSIX file descriptor.
class Fd {
 public:
  explicit Fd(int fd) : fd_(fd) {}
  Fd(const Fd&) = delete;
  Fd& operator=(const Fd&) = delete;
  ~Fd() {
    if (fd_ >= 0) ::close(fd_);
  }
  int get() const { return fd_; }
  // Closes now and reports the error close(2) may carry (deferred write errors on some file systems).
  int close() {
    const int rc = ::close(fd_);
    fd_ = -1;
    return rc;
  }

 private:
  int fd_;
};

// Best effort: make the rename itself durable. Failing to open a folder for fsync is not an error worth
// losing output for (some file systems refuse it).
void sync_folder(const std::filesystem::path& folder) {
  const std::string name = folder.empty() ? std::string(".") : folder.string();
  Fd dir(::open(name.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC));
  if (dir.get() >= 0) ::fsync(dir.get());
}

void remove_quietly(const std::filesystem::path& p) {
  std::error_code ignored;
  std::filesystem::remove(p, ignored);
}

}  // namespace

std::filesystem::path temporary_sibling(const std::filesystem::path& target) {
  static std::atomic<unsigned long> counter{0};
  const std::string name = "." + target.filename().string() + ".tmp." + std::to_string(::getpid()) + "." +
                           std::to_string(counter.fetch_add(1));
  return target.parent_path() / name;
}

void commit_file_atomic(const std::filesystem::path& temporary, const std::filesystem::path& target) {
  {
    Fd fd(::open(temporary.c_str(), O_RDONLY | O_CLOEXEC));
    if (fd.get() < 0 || ::fsync(fd.get()) != 0) {
      const int err = errno;
      remove_quietly(temporary);
      throw IoError("cannot flush " + temporary.string() + " (for " + target.string() + "): " + errno_text(err));
    }
  }
  if (::rename(temporary.c_str(), target.c_str()) != 0) {
    const int err = errno;
    remove_quietly(temporary);
    throw IoError("cannot rename " + temporary.string() + " to " + target.string() + ": " + errno_text(err));
  }
  sync_folder(target.parent_path());
}

void write_file_atomic(const std::filesystem::path& path, std::string_view content) {
  const std::filesystem::path tmp = temporary_sibling(path);
  Fd fd(::open(tmp.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_TRUNC | O_CLOEXEC, 0644));
  if (fd.get() < 0) {
    throw IoError("cannot create " + tmp.string() + " (for " + path.string() + "): " + errno_text(errno));
  }
  auto fail = [&](const char* what, int err) {
    fd.close();
    remove_quietly(tmp);
    throw IoError(std::string("cannot ") + what + " " + path.string() + ": " + errno_text(err));
  };
  const char* p = content.data();
  std::size_t left = content.size();
  while (left > 0) {
    const ssize_t n = ::write(fd.get(), p, left);
    if (n < 0) {
      if (errno == EINTR) continue;
      fail("write", errno);
    }
    p += n;
    left -= static_cast<std::size_t>(n);
  }
  if (::fsync(fd.get()) != 0) fail("flush", errno);
  if (fd.close() != 0) {
    const int err = errno;
    remove_quietly(tmp);
    throw IoError("cannot close " + path.string() + ": " + errno_text(err));
  }
  if (::rename(tmp.c_str(), path.c_str()) != 0) {
    const int err = errno;
    remove_quietly(tmp);
    throw IoError("cannot rename " + tmp.string() + " to " + path.string() + ": " + errno_text(err));
  }
  sync_folder(path.parent_path());
}

}  // namespace polyfloe::io
