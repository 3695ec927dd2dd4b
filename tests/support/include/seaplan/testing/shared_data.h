// Locating test data: the repository (examples/, tests/data) and the shared
// benchmark/chart folder (SEAPLAN_SHARED, ../shared beside the clone). Tests
// that need shared data skip with a visible reason when it is absent, and
// fail under CI (environment variable CI set), where it is always present.
#pragma once

#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <optional>
#include <string>

namespace seaplan::testing {

// The repository root (SEAPLAN_SOURCE_DIR overrides the configured one).
std::filesystem::path SourceDir();
// build/bin, where the binaries are (SEAPLAN_BIN_DIR overrides).
std::filesystem::path BinDir();
// The shared folder if it exists.
std::optional<std::filesystem::path> SharedDir();
// Reads a whole file; fails the test (returns "") if it cannot.
std::string ReadFile(const std::filesystem::path& path);

}  // namespace seaplan::testing

// Binds `var` to SharedDir()/relative, or skips the test with the reason;
// under CI (environment variable CI set), where the shared folder is always
// beside the clone, a missing folder fails the test instead.
#define SEAPLAN_REQUIRE_SHARED(var, relative)                                            \
  auto var##_shared_root = ::seaplan::testing::SharedDir();                              \
  if (!var##_shared_root || !std::filesystem::exists(*var##_shared_root / (relative))) { \
    if (std::getenv("CI") != nullptr) {                                                  \
      GTEST_FAIL() << "shared data '" << (relative)                                      \
                   << "' not found (required under CI; set SEAPLAN_SHARED)";             \
    }                                                                                    \
    GTEST_SKIP() << "shared data '" << (relative)                                        \
                 << "' not found (set SEAPLAN_SHARED to the shared folder)";             \
  }                                                                                      \
  const std::filesystem::path var = *var##_shared_root / (relative)
