#include "seaplan/common/file_replace.h"

#include <gtest/gtest.h>
#include <sys/stat.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace seaplan {
namespace {

namespace fs = std::filesystem;

// A folder of its own under the test's temporary directory, removed after.
class FileReplaceTest : public ::testing::Test {
 protected:
  void SetUp() override {
    folder_ = fs::path(::testing::TempDir()) /
              ("file_replace_" +
               std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()));
    fs::remove_all(folder_);
    fs::create_directories(folder_);
  }
  void TearDown() override { fs::remove_all(folder_); }

  static std::string Read(const fs::path& path) {
    std::ifstream in(path, std::ios::binary);
    std::stringstream text;
    text << in.rdbuf();
    return text.str();
  }
  int EntriesInFolder() const {
    return static_cast<int>(std::distance(fs::directory_iterator(folder_), {}));
  }
  static mode_t ModeOf(const fs::path& path) {
    struct stat info {};
    EXPECT_EQ(::stat(path.c_str(), &info), 0);
    return info.st_mode & 0777;
  }

  fs::path folder_;
};

TEST_F(FileReplaceTest, ReplacesTheContentWholeAndLeavesNoTemporaryFile) {
  const fs::path path = folder_ / "plan.txt";
  ASSERT_TRUE(ReplaceFile(path, "a much longer first content\n").ok());
  ASSERT_TRUE(ReplaceFile(path, "short\n").ok());
  EXPECT_EQ(Read(path), "short\n");
  EXPECT_EQ(EntriesInFolder(), 1);
}

TEST_F(FileReplaceTest, ANewFileGetsTheUmasksModeOrOwnerOnly) {
  const mode_t old_mask = ::umask(022);
  ASSERT_TRUE(ReplaceFile(folder_ / "shared", "x").ok());
  ASSERT_TRUE(ReplaceFile(folder_ / "secret", "x", {.owner_only = true, .durable = true}).ok());
  ::umask(old_mask);
  EXPECT_EQ(ModeOf(folder_ / "shared"), 0644u);
  EXPECT_EQ(ModeOf(folder_ / "secret"), 0600u);
}

TEST_F(FileReplaceTest, AMissingFolderIsNotFoundAndNamesThePath) {
  const fs::path path = folder_ / "absent" / "plan.txt";
  const absl::Status status = ReplaceFile(path, "x");
  EXPECT_EQ(status.code(), absl::StatusCode::kNotFound);
  EXPECT_NE(status.message().find(path.string()), std::string_view::npos) << status;
  EXPECT_EQ(EntriesInFolder(), 0);
}

TEST_F(FileReplaceTest, AFailedRenameRemovesTheTemporaryFile) {
  const fs::path path = folder_ / "taken";
  fs::create_directories(path);  // a file cannot be renamed over a folder
  const absl::Status status = ReplaceFile(path, "x");
  EXPECT_FALSE(status.ok());
  EXPECT_NE(status.message().find("cannot write"), std::string_view::npos) << status;
  EXPECT_EQ(EntriesInFolder(), 1);
  EXPECT_TRUE(fs::is_directory(path));
}

}  // namespace
}  // namespace seaplan
