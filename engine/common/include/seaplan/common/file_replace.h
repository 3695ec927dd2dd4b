// Replacing a file whole: the content goes to a new file beside the target,
// which is then renamed over it. A reader, or a process killed meanwhile,
// sees the old file or the new one, never part of either; processes writing
// at once each write their own temporary file.
#pragma once

#include <filesystem>
#include <string_view>

#include "absl/status/status.h"

namespace seaplan {

struct FileReplaceOptions {
  // False: the mode a new file would get (0666 less the umask). True: 0600,
  // from the file's creation on (for secrets).
  bool owner_only = false;
  // Flush the file, and the folder after the rename, so that the new content
  // survives a crash of the machine, not only of the process.
  bool durable = false;
};

// Writes `content` to `path` as described above. The temporary file is named
// ".NAME.XXXXXX" in the same folder and removed on failure. Errors carry the
// errno's status code (PermissionDenied, NotFound, ResourceExhausted...) and
// name the path.
absl::Status ReplaceFile(const std::filesystem::path& path, std::string_view content,
                         const FileReplaceOptions& options = {});

}  // namespace seaplan
