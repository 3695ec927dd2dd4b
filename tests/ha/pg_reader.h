// What the replica tests share: their skip rule for missing dependencies,
// a throwaway database, and a libpq connection for their own reads of it.
// Header-only; not thread-safe (one connection per test thread).
#pragma once

#include <gtest/gtest.h>
#include <libpq-fe.h>

#include <cstdint>
#include <cstdlib>
#include <memory>
#include <regex>
#include <string>
#include <vector>

#include "seaplan/storage/testing/postgres_cluster.h"

namespace seaplan::ha {

// Skips with `reason` printed, except under CI, where a missing dependency
// must fail the run.
#define REQUIRE_DEPENDENCY(ok, reason)                                                \
  do {                                                                                \
    if (!(ok)) {                                                                      \
      if (std::getenv("CI") != nullptr) FAIL() << (reason) << " (required under CI)"; \
      GTEST_SKIP() << "failover test skipped: " << (reason);                          \
    }                                                                                 \
  } while (0)

// A throwaway PostgreSQL cluster with one fresh database.
struct ThrowawayDatabase {
  std::unique_ptr<storage::testing::TemporaryPostgresCluster> cluster;
  std::string url;
};
// NotFound when PostgreSQL is not installed.
inline absl::StatusOr<ThrowawayDatabase> StartThrowawayDatabase() {
  auto cluster = storage::testing::TemporaryPostgresCluster::Start();
  if (!cluster.ok()) return cluster.status();
  auto url = (*cluster)->CreateDatabase();
  if (!url.ok()) return url.status();
  return ThrowawayDatabase{std::move(*cluster), *url};
}

// One libpq connection for the test's own reads of the shared database.
class Pg {
 public:
  explicit Pg(const std::string& url) : conn_(PQconnectdb(url.c_str())) {}
  ~Pg() { PQfinish(conn_); }
  Pg(const Pg&) = delete;
  Pg& operator=(const Pg&) = delete;
  bool ok() const { return PQstatus(conn_) == CONNECTION_OK; }
  std::string error() const { return PQerrorMessage(conn_); }

  // Rows of `sql` with $1 = `arg`, each column as text.
  std::vector<std::vector<std::string>> Rows(const std::string& sql, const std::string& arg = "") {
    const char* params[] = {arg.c_str()};
    PGresult* r = PQexecParams(conn_, sql.c_str(), arg.empty() ? 0 : 1, nullptr,
                               arg.empty() ? nullptr : params, nullptr, nullptr, 0);
    std::vector<std::vector<std::string>> rows;
    if (PQresultStatus(r) != PGRES_TUPLES_OK) {
      ADD_FAILURE() << sql << ": " << PQresultErrorMessage(r);
    } else {
      for (int i = 0; i < PQntuples(r); ++i) {
        auto& row = rows.emplace_back();
        for (int c = 0; c < PQnfields(r); ++c) row.push_back(PQgetvalue(r, i, c));
      }
    }
    PQclear(r);
    return rows;
  }
  std::vector<int64_t> Numbers(const std::string& sql, const std::string& arg) {
    std::vector<int64_t> out;
    for (const auto& row : Rows(sql, arg)) out.push_back(std::stoll(row.at(0)));
    return out;
  }

 private:
  PGconn* conn_;
};

// The process id in a work lease's holder (host:pid:random, the server's
// default holder name); -1 when it has another form.
inline int HolderPid(const std::string& holder) {
  std::smatch m;
  if (!std::regex_match(holder, m, std::regex("[^:]*:([0-9]+):.*"))) return -1;
  return std::stoi(m[1]);
}

}  // namespace seaplan::ha
