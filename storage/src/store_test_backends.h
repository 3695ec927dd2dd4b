// The storage tests' backends: every test of the contract suite runs once on
// SQLite and once on PostgreSQL (a throwaway cluster shared by the process,
// a fresh database per test). Without PostgreSQL installed the PostgreSQL
// runs are skipped with the reason, except under CI (env CI set), where
// they fail.
#pragma once

#include <gtest/gtest.h>

#include <filesystem>
#include <memory>
#include <string>

#include "seaplan/storage/repositories.h"

namespace seaplan::storage {

enum class Backend { kSqlite, kPostgres };

std::string BackendName(const ::testing::TestParamInfo<Backend>& info);

// A fresh, empty database of one backend.
class TestDatabase {
 public:
  // NotFound when the backend is not installed.
  static absl::StatusOr<std::unique_ptr<TestDatabase>> Create(Backend backend);
  ~TestDatabase();

  // Opens a Store on the database: each call is another connection, as
  // another server process would have.
  absl::StatusOr<std::unique_ptr<Store>> Open() const;
  Backend backend() const { return backend_; }
  // The SQLite file or the PostgreSQL URL.
  const std::string& location() const { return location_; }

 private:
  Backend backend_ = Backend::kSqlite;
  std::string location_;
  std::filesystem::path folder_;  // SQLite only
};

// Parameterised over the backends. SetUp() creates the database and opens
// store(); a missing PostgreSQL skips (or fails under CI).
class StoreTest : public ::testing::TestWithParam<Backend> {
 protected:
  void SetUp() override;
  void TearDown() override;
  Store& store() { return *store_; }
  MissionRepository& missions() { return store_->missions(); }
  WorkLeaseRepository& work() { return store_->work(); }
  TestDatabase& database() { return *database_; }
  // A second store (connection) on the same database.
  std::unique_ptr<Store> OpenAnother();

 private:
  std::unique_ptr<TestDatabase> database_;
  std::unique_ptr<Store> store_;
};

// Small records for the tests.
MissionRecord TestMission(const std::string& id, const std::string& request_id = "");
PlanVersionRecord TestVersion(const std::string& mission, int version);
NewLogEvent TestEvent(const std::string& message, const std::string& source = "server");

}  // namespace seaplan::storage
