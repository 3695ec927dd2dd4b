// The admin token the end-to-end fixtures start servers with, so that tests
// written before the server required tokens run unchanged:
//   - servers are started with --admin-token-file (WriteTestAdminTokenFile)
//     or get the token stored before they start;
//   - PassTestAdminTokenToChildren() sets SEAPLAN_TOKEN, so that the
//     clients a test starts (seaplan, seaplan-sim) present it;
//   - grpc_test_token.h's UseTestAdminTokenByDefault() also gives it to
//     this process's own gRPC calls.
// Header-only and without gRPC: fixtures of every suite include it.
#pragma once

#include <fcntl.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <string>

namespace seaplan::testing {

// A fixed token of the server's format (test data, never a real secret).
inline const std::string& TestAdminToken() {
  static const std::string token =
      "seaplan_7e57ad0000000001_test-admin-token-of-the-seaplan-fixtures-01";
  return token;
}

// Writes the token to `path` with mode 0600 (as a deployment would) and
// returns `path`.
inline std::filesystem::path WriteTestAdminTokenFile(const std::filesystem::path& path) {
  const int fd = ::open(path.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0600);
  if (fd >= 0) {
    const std::string line = TestAdminToken() + "\n";
    (void)!::write(fd, line.data(), line.size());
    ::close(fd);
  }
  return path;
}

// "Bearer <admin token>", for HTTP clients' Authorization header.
inline std::string TestAdminAuthorization() {
  return "Bearer " + TestAdminToken();
}

// The clients a test starts from now on (seaplan, seaplan-sim) present the
// admin token (they read SEAPLAN_TOKEN).
inline void PassTestAdminTokenToChildren() {
  ::setenv("SEAPLAN_TOKEN", TestAdminToken().c_str(), 1);
}

}  // namespace seaplan::testing
