#include "seaplan/common/file_replace.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <string>

#include "absl/strings/str_cat.h"

namespace seaplan {
namespace {

// Writes all of `content` to `fd`; 0 or the errno of the failure.
int WriteAll(int fd, std::string_view content) {
  for (std::size_t done = 0; done < content.size();) {
    const ssize_t n = ::write(fd, content.data() + done, content.size() - done);
    if (n > 0) {
      done += static_cast<std::size_t>(n);
    } else if (n == 0) {
      return EIO;
    } else if (errno != EINTR) {
      return errno;
    }
  }
  return 0;
}

}  // namespace

absl::Status ReplaceFile(const std::filesystem::path& path, std::string_view content,
                         const FileReplaceOptions& options) {
  const std::filesystem::path folder =
      path.has_parent_path() ? path.parent_path() : std::filesystem::path(".");
  std::string temp = (folder / ("." + path.filename().string() + ".XXXXXX")).string();
  const int fd = ::mkostemp(temp.data(), O_CLOEXEC);  // 0600 from the start
  if (fd < 0) {
    return absl::ErrnoToStatus(
        errno, absl::StrCat("cannot create a temporary file beside '", path.string(), "'"));
  }
  int cause = 0;
  if (!options.owner_only) {
    const mode_t mask = ::umask(0);  // read it back: umask has no getter
    ::umask(mask);
    if (::fchmod(fd, 0666 & ~mask) != 0) cause = errno;
  }
  if (cause == 0) cause = WriteAll(fd, content);
  if (cause == 0 && options.durable && ::fsync(fd) != 0) cause = errno;
  if (::close(fd) != 0 && cause == 0) cause = errno;
  if (cause == 0 && std::rename(temp.c_str(), path.c_str()) != 0) cause = errno;
  if (cause != 0) {
    ::unlink(temp.c_str());
    return absl::ErrnoToStatus(cause, absl::StrCat("cannot write '", path.string(), "'"));
  }
  if (options.durable) {
    // The rename itself survives a crash once the folder is flushed.
    if (const int dir = ::open(folder.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC); dir >= 0) {
      (void)::fsync(dir);
      ::close(dir);
    }
  }
  return absl::OkStatus();
}

}  // namespace seaplan
