// Test-only: where the repository is. SEAPLAN_SOURCE_DIR when the environment
// has it, else the source folder this test was built from (ctest does not
// pass SEAPLAN_SOURCE_DIR through today, see the report of issue #3).
#pragma once

#include <cstdlib>
#include <filesystem>

namespace seaplan::validate::testing {

inline std::filesystem::path RepoRoot() {
  const char* env = std::getenv("SEAPLAN_SOURCE_DIR");
  if (env != nullptr && *env != '\0') return env;
  return SEAPLAN_VALIDATE_SOURCE_DIR;
}

}  // namespace seaplan::validate::testing
