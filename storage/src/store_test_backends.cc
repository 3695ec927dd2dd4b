#include "store_test_backends.h"

#include <unistd.h>

#include <cstdlib>

#include "seaplan/storage/postgres_store.h"
#include "seaplan/storage/sqlite_store.h"
#include "seaplan/storage/testing/postgres_cluster.h"

namespace seaplan::storage {

namespace fs = std::filesystem;

std::string BackendName(const ::testing::TestParamInfo<Backend>& info) {
  return info.param == Backend::kSqlite ? "Sqlite" : "Postgres";
}

absl::StatusOr<std::unique_ptr<TestDatabase>> TestDatabase::Create(Backend backend) {
  auto db = std::unique_ptr<TestDatabase>(new TestDatabase());
  db->backend_ = backend;
  if (backend == Backend::kSqlite) {
    static int counter = 0;
    db->folder_ = fs::temp_directory_path() / ("seaplan-storage-test-" + std::to_string(getpid()) +
                                               "-" + std::to_string(counter++));
    fs::remove_all(db->folder_);
    fs::create_directories(db->folder_);
    db->location_ = (db->folder_ / "seaplan.db").string();
    return db;
  }
  SEAPLAN_ASSIGN_OR_RETURN(testing::TemporaryPostgresCluster * cluster, testing::ProcessCluster());
  SEAPLAN_ASSIGN_OR_RETURN(db->location_, cluster->CreateDatabase());
  return db;
}

TestDatabase::~TestDatabase() {
  if (!folder_.empty()) {
    std::error_code ec;
    fs::remove_all(folder_, ec);
  }
}

absl::StatusOr<std::unique_ptr<Store>> TestDatabase::Open() const {
  if (backend_ == Backend::kSqlite) {
    SEAPLAN_ASSIGN_OR_RETURN(std::unique_ptr<SqliteStore> store, SqliteStore::Open(location_));
    return std::unique_ptr<Store>(std::move(store));
  }
  SEAPLAN_ASSIGN_OR_RETURN(std::unique_ptr<PostgresStore> store, PostgresStore::Open(location_));
  return std::unique_ptr<Store>(std::move(store));
}

void StoreTest::SetUp() {
  auto db = TestDatabase::Create(GetParam());
  if (absl::IsNotFound(db.status())) {
    const char* ci = std::getenv("CI");
    if (ci != nullptr && *ci != '\0') {
      FAIL() << "CI is set, so PostgreSQL must be available: " << db.status();
    }
    GTEST_SKIP() << "PostgreSQL not available: " << db.status().message();
  }
  ASSERT_TRUE(db.ok()) << db.status();
  database_ = *std::move(db);
  auto store = database_->Open();
  ASSERT_TRUE(store.ok()) << store.status();
  store_ = *std::move(store);
}

void StoreTest::TearDown() {
  if (store_) {
    EXPECT_TRUE(store_->Close().ok());
  }
  store_.reset();
  database_.reset();
}

std::unique_ptr<Store> StoreTest::OpenAnother() {
  auto store = database_->Open();
  EXPECT_TRUE(store.ok()) << store.status();
  return store.ok() ? *std::move(store) : nullptr;
}

MissionRecord TestMission(const std::string& id, const std::string& request_id) {
  MissionRecord m;
  m.id = id;
  m.name = "mission " + id;
  m.vessel_id = "vessel-1";
  m.request_id = request_id;
  m.spec = std::string("spec\0bytes", 10);
  m.state = 2;
  m.created_at_ms = 1000;
  m.updated_at_ms = 1000;
  return m;
}

PlanVersionRecord TestVersion(const std::string& mission, int version) {
  return {mission, version, "reason " + std::to_string(version), 2000 + version,
          "content-" + std::to_string(version)};
}

NewLogEvent TestEvent(const std::string& message, const std::string& source) {
  return {3000, 12.5, source, message};
}

}  // namespace seaplan::storage
