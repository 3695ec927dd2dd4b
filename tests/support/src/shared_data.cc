#include "seaplan/testing/shared_data.h"

#include <cstdlib>
#include <fstream>
#include <sstream>

namespace seaplan::testing {
namespace {

std::filesystem::path FromEnv(const char* name, const std::filesystem::path& fallback) {
  const char* value = std::getenv(name);
  return value != nullptr && *value != '\0' ? std::filesystem::path(value) : fallback;
}

}  // namespace

std::filesystem::path SourceDir() {
  return FromEnv("SEAPLAN_SOURCE_DIR", SEAPLAN_DEFAULT_SOURCE_DIR);
}

std::filesystem::path BinDir() {
  return FromEnv("SEAPLAN_BIN_DIR", SEAPLAN_DEFAULT_BIN_DIR);
}

std::optional<std::filesystem::path> SharedDir() {
  const auto dir = FromEnv("SEAPLAN_SHARED", SEAPLAN_DEFAULT_SHARED_DIR);
  if (std::filesystem::is_directory(dir)) return dir;
  return std::nullopt;
}

std::string ReadFile(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    ADD_FAILURE() << "cannot read " << path;
    return "";
  }
  std::ostringstream buffer;
  buffer << in.rdbuf();
  return buffer.str();
}

}  // namespace seaplan::testing
