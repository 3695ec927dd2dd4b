// A small tmpfs mounted on a fresh folder for the life of the object: a disk
// that fills up (size=...) or turns read-only (Remount("ro")) under a
// database, without touching the machine's own disks. Mounting needs root
// (CI runs as root); reason() says why not otherwise, for the skip message.
#ifndef SEAPLAN_TESTING_TINY_FILESYSTEM_H_
#define SEAPLAN_TESTING_TINY_FILESYSTEM_H_

#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <string>

namespace seaplan::testing {

class TinyFilesystem {
 public:
  explicit TinyFilesystem(const std::string& size) {
    std::string pattern =
        (std::filesystem::temp_directory_path() / "seaplan-tiny-fs-XXXXXX").string();
    if (::mkdtemp(pattern.data()) == nullptr) {
      reason_ = "cannot create a folder to mount on";
      return;
    }
    dir_ = pattern;
    if (::geteuid() != 0) {
      reason_ = "needs root to mount a small tmpfs (run as root, as CI does)";
      return;
    }
    if (!Mount("-t tmpfs -o size=" + size + ",mode=0755 tmpfs")) {
      reason_ = "mount -t tmpfs failed (no mount permission in this container?)";
      return;
    }
    mounted_ = true;
  }
  ~TinyFilesystem() {
    if (mounted_) Run("umount -l '" + dir_.string() + "'");
    std::error_code ignored;
    std::filesystem::remove_all(dir_, ignored);
  }
  TinyFilesystem(const TinyFilesystem&) = delete;
  TinyFilesystem& operator=(const TinyFilesystem&) = delete;

  bool mounted() const { return mounted_; }
  const std::string& reason() const { return reason_; }
  std::filesystem::path path(const std::string& name) const { return dir_ / name; }
  // Changes the mount's options (size=..., ro, rw).
  bool Remount(const std::string& options) { return Mount("-o remount," + options); }

 private:
  bool Mount(const std::string& args) { return Run("mount " + args + " '" + dir_.string() + "'"); }
  static bool Run(const std::string& command) {
    return std::system((command + " >/dev/null 2>&1").c_str()) == 0;
  }

  std::filesystem::path dir_;
  bool mounted_ = false;
  std::string reason_;
};

}  // namespace seaplan::testing

#endif  // SEAPLAN_TESTING_TINY_FILESYSTEM_H_
