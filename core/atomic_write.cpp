// Whole-file writes through a temporary file and rename(2) (contract in core/atomic_write.h).
#include "core/atomic_write.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <climits>
#include <cstdlib>
#include <cstring>
#include <string>

#include "core/error.h"

namespace blocklab {
namespace {

std::string reason(int error_number) { return std::strerror(error_number); }

// Writes all `size` bytes to `fd`, retrying short writes and EINTR; returns 0 or the errno of the failure.
int write_all(int fd, const void* data, std::size_t size) {
  const auto* bytes = static_cast<const unsigned char*>(data);
  while (size > 0) {
    const ssize_t written = ::write(fd, bytes, size);
    if (written < 0) {
      if (errno == EINTR) continue;
      return errno;
    }
    if (written == 0) return EIO;
    bytes += written;
    size -= static_cast<std::size_t>(written);
  }
  return 0;
}

// Writes into an existing non-regular file (device, FIFO): there is nothing to rename over.
void write_in_place(const std::string& path, const void* data, std::size_t size) {
  const int fd = ::open(path.c_str(), O_WRONLY | O_TRUNC | O_CLOEXEC);
  if (fd < 0) fail(path, "cannot open for writing (" + reason(errno) + ")");
  const int write_error = write_all(fd, data, size);
  const int close_error = ::close(fd) == 0 ? 0 : errno;
  if (write_error != 0) fail(path, "cannot write (" + reason(write_error) + ")");
  if (close_error != 0) fail(path, "cannot write (" + reason(close_error) + ")");
}

// The regular file a symbolic link at `path` names, or `path` itself when it is no link or a dangling one.
std::string resolve_link(const std::string& path) {
  struct stat link_status {};
  if (::lstat(path.c_str(), &link_status) != 0 || !S_ISLNK(link_status.st_mode)) return path;
  char resolved[PATH_MAX];
  if (::realpath(path.c_str(), resolved) == nullptr) return path;  // dangling: the link itself is replaced
  return resolved;
}

}  // namespace

void write_file_atomically(const std::string& path, const void* data, std::size_t size) {
  struct stat status {};
  const bool exists = ::stat(path.c_str(), &status) == 0;
  if (exists && S_ISDIR(status.st_mode)) fail(path, "cannot write: is a directory");
  if (exists && !S_ISREG(status.st_mode)) {
    write_in_place(path, data, size);
    return;
  }

  const std::string target = resolve_link(path);
  const std::string temp = target + ".tmp." + std::to_string(static_cast<long>(::getpid()));
  const mode_t mode = exists ? (status.st_mode & 07777) : 0666;
  const int fd = ::open(temp.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, mode);
  if (fd < 0) fail(path, "cannot create file (" + reason(errno) + ")");
  int error = write_all(fd, data, size);
  if (error == 0 && exists) error = ::fchmod(fd, mode) == 0 ? 0 : errno;  // umask does not narrow a kept mode
  const int close_error = ::close(fd) == 0 ? 0 : errno;
  if (error == 0) error = close_error;
  if (error == 0 && ::rename(temp.c_str(), target.c_str()) != 0) error = errno;
  if (error != 0) {
    ::unlink(temp.c_str());
    fail(path, "cannot write (" + reason(error) + ")");
  }
}

}  // namespace blocklab
