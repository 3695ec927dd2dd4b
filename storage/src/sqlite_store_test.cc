#include "seaplan/storage/sqlite_store.h"

#include <gtest/gtest.h>
#include <sqlite3.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>

#include "seaplan/testing/tiny_filesystem.h"
#include "store_test_backends.h"

namespace seaplan::storage {
namespace {

namespace fs = std::filesystem;

class TempDir {
 public:
  TempDir() {
    path_ = fs::temp_directory_path() / ("seaplan-sqlite-test-" + std::to_string(::getpid()) + "-" +
                                         std::to_string(counter_++));
    fs::remove_all(path_);
    fs::create_directories(path_);
  }
  ~TempDir() { fs::remove_all(path_); }
  fs::path operator/(const std::string& name) const { return path_ / name; }

 private:
  static inline int counter_ = 0;
  fs::path path_;
};

// Runs SQL directly on a database file, as another process (or an operator
// with the sqlite3 shell) would; returns the SQLite result code.
int RawExec(const fs::path& db_path, const std::string& sql, std::string* error = nullptr) {
  sqlite3* db = nullptr;
  EXPECT_EQ(sqlite3_open(db_path.c_str(), &db), SQLITE_OK);
  char* err = nullptr;
  const int rc = sqlite3_exec(db, sql.c_str(), nullptr, nullptr, &err);
  if (error) *error = err ? err : "";
  sqlite3_free(err);
  sqlite3_close(db);
  return rc;
}

TEST(SqliteStoreTest, MigratesEmptyDatabaseToLatest) {
  TempDir dir;
  auto store = SqliteStore::Open((dir / "db.sqlite").string());
  ASSERT_TRUE(store.ok()) << store.status();
  auto version = (*store)->SchemaVersion();
  ASSERT_TRUE(version.ok());
  EXPECT_EQ(*version, LatestSchemaVersion());
  EXPECT_GE(LatestSchemaVersion(), 2);
  EXPECT_TRUE((*store)->CheckIntegrity().ok());
  ASSERT_TRUE((*store)->Close().ok());
  // Reopening applies nothing and keeps the version.
  auto again = SqliteStore::Open((dir / "db.sqlite").string());
  ASSERT_TRUE(again.ok()) << again.status();
  EXPECT_EQ(*(*again)->SchemaVersion(), LatestSchemaVersion());
}

TEST(SqliteStoreTest, WalModeAndForeignKeysAreOn) {
  TempDir dir;
  const fs::path path = dir / "db.sqlite";
  auto store = SqliteStore::Open(path.string());
  ASSERT_TRUE(store.ok());
  // journal_mode=WAL is persistent in the file: a fresh connection sees it.
  sqlite3* db = nullptr;
  ASSERT_EQ(sqlite3_open(path.c_str(), &db), SQLITE_OK);
  sqlite3_stmt* s = nullptr;
  ASSERT_EQ(sqlite3_prepare_v2(db, "PRAGMA journal_mode", -1, &s, nullptr), SQLITE_OK);
  ASSERT_EQ(sqlite3_step(s), SQLITE_ROW);
  EXPECT_STREQ(reinterpret_cast<const char*>(sqlite3_column_text(s, 0)), "wal");
  sqlite3_finalize(s);
  sqlite3_close(db);
  // Foreign keys: a version of a mission that does not exist is refused.
  std::string error;
  EXPECT_NE(RawExec(path,
                    "PRAGMA foreign_keys = ON; INSERT INTO plan_versions(mission_id, version, "
                    "reason, created_at_ms, content) VALUES ('nope', 1, 'r', 1, x'')",
                    &error),
            SQLITE_OK);
  EXPECT_NE(error.find("FOREIGN KEY"), std::string::npos) << error;
}

// The version-1 schema exactly as release 1 created it, typed by hand (not
// taken from the migration list) so the test catches an edited migration.
constexpr const char* kSchemaV1 = R"sql(
CREATE TABLE charts (seq INTEGER PRIMARY KEY AUTOINCREMENT, id TEXT NOT NULL UNIQUE, name TEXT NOT NULL,
  format INTEGER NOT NULL, options BLOB NOT NULL, summary BLOB NOT NULL, obstacles BLOB NOT NULL,
  created_at_ms INTEGER NOT NULL);
CREATE TABLE missions (seq INTEGER PRIMARY KEY AUTOINCREMENT, id TEXT NOT NULL UNIQUE, name TEXT NOT NULL,
  vessel_id TEXT NOT NULL, spec BLOB NOT NULL, state INTEGER NOT NULL, current_version INTEGER NOT NULL DEFAULT 0,
  created_at_ms INTEGER NOT NULL, updated_at_ms INTEGER NOT NULL, last_state BLOB NOT NULL DEFAULT x'',
  failure_reason TEXT NOT NULL DEFAULT '');
CREATE INDEX missions_by_state ON missions(state, seq);
CREATE TABLE plan_versions (mission_id TEXT NOT NULL REFERENCES missions(id), version INTEGER NOT NULL CHECK (version >= 1),
  reason TEXT NOT NULL, created_at_ms INTEGER NOT NULL, content BLOB NOT NULL, PRIMARY KEY (mission_id, version)) WITHOUT ROWID;
CREATE TRIGGER plan_versions_no_update BEFORE UPDATE ON plan_versions BEGIN SELECT RAISE(ABORT, 'plan versions are immutable'); END;
CREATE TRIGGER plan_versions_no_delete BEFORE DELETE ON plan_versions BEGIN SELECT RAISE(ABORT, 'plan versions are immutable'); END;
CREATE TABLE feedback (seq INTEGER PRIMARY KEY AUTOINCREMENT, mission_id TEXT NOT NULL REFERENCES missions(id),
  vessel_id TEXT NOT NULL, sequence_number INTEGER NOT NULL, kind INTEGER NOT NULL, payload BLOB NOT NULL,
  received_at_ms INTEGER NOT NULL, UNIQUE (vessel_id, sequence_number));
CREATE INDEX feedback_by_mission ON feedback(mission_id, seq);
CREATE TABLE log_events (mission_id TEXT NOT NULL REFERENCES missions(id), event_id INTEGER NOT NULL CHECK (event_id >= 1),
  time_ms INTEGER NOT NULL, mission_time_s REAL NOT NULL, source TEXT NOT NULL CHECK (length(source) > 0),
  message TEXT NOT NULL, PRIMARY KEY (mission_id, event_id)) WITHOUT ROWID;
INSERT INTO missions(id, name, vessel_id, spec, state, current_version, created_at_ms, updated_at_ms)
  VALUES ('old-mission', 'from v1', 'ship0', x'0102', 2, 1, 10, 10);
INSERT INTO plan_versions VALUES ('old-mission', 1, 'initial plan', 11, x'aa');
INSERT INTO charts(id, name, format, options, summary, obstacles, created_at_ms) VALUES ('old-chart', 'c', 2, x'', x'', x'bb', 5);
PRAGMA user_version = 1;
)sql";

TEST(SqliteStoreTest, MigratesVersionOneDatabaseKeepingData) {
  TempDir dir;
  const fs::path path = dir / "old.sqlite";
  ASSERT_EQ(RawExec(path, kSchemaV1), SQLITE_OK);
  auto store = SqliteStore::Open(path.string());
  ASSERT_TRUE(store.ok()) << store.status();
  EXPECT_EQ(*(*store)->SchemaVersion(), LatestSchemaVersion());
  auto m = (*store)->missions().Get("old-mission");
  ASSERT_TRUE(m.ok()) << m.status();
  EXPECT_EQ(m->name, "from v1");
  EXPECT_EQ(m->spec, "\x01\x02");
  EXPECT_EQ(m->current_version, 1);
  EXPECT_TRUE(m->request_id.empty());
  EXPECT_TRUE(m->completed_tasks.empty());
  auto v = (*store)->missions().GetVersion("old-mission", 1);
  ASSERT_TRUE(v.ok());
  EXPECT_EQ(v->content, "\xaa");
  auto c = (*store)->charts().Get("old-chart", true);
  ASSERT_TRUE(c.ok());
  EXPECT_EQ(c->obstacles, "\xbb");
  EXPECT_EQ(c->source_files, "");
  // Version-2 features work on the migrated file.
  ASSERT_TRUE(
      (*store)->missions().Create(TestMission("new", "req-1"), TestVersion("new", 1), {}).ok());
  auto found = (*store)->missions().FindByRequestId("req-1");
  ASSERT_TRUE(found.ok() && found->has_value());
  EXPECT_EQ((*found)->id, "new");
}

TEST(SqliteStoreTest, RefusesDatabaseFromTheFuture) {
  TempDir dir;
  const fs::path path = dir / "future.sqlite";
  ASSERT_EQ(RawExec(path, "CREATE TABLE x(a); PRAGMA user_version = 999;"), SQLITE_OK);
  auto store = SqliteStore::Open(path.string());
  EXPECT_EQ(store.status().code(), absl::StatusCode::kFailedPrecondition) << store.status();
}

TEST(SqliteStoreTest, FailedMigrationLeavesPreviousVersion) {
  TempDir dir;
  const fs::path path = dir / "clash.sqlite";
  // A v1 database where someone already created an index with the name
  // migration 2 uses: migration 2 fails halfway (after its first ALTER).
  std::string sql = kSchemaV1;
  sql += "CREATE INDEX missions_by_request_id ON missions(name);";
  ASSERT_EQ(RawExec(path, sql), SQLITE_OK);
  auto store = SqliteStore::Open(path.string());
  ASSERT_FALSE(store.ok());
  EXPECT_NE(store.status().message().find("version 2"), std::string::npos) << store.status();
  // The first ALTER of migration 2 was rolled back with the rest.
  std::string error;
  EXPECT_NE(RawExec(path, "SELECT request_id FROM missions", &error), SQLITE_OK);
  EXPECT_NE(error.find("no such column"), std::string::npos) << error;
}

// Numbering is checked on every backend (store_contract_test.cc); here: the
// SQLite triggers refuse raw SQL that would change a stored version.
TEST(SqliteStoreTest, RawSqlCannotChangePlanVersions) {
  TempDir dir;
  const fs::path path = dir / "db.sqlite";
  auto store = SqliteStore::Open(path.string());
  ASSERT_TRUE(store.ok());
  MissionRepository& repo = (*store)->missions();
  ASSERT_TRUE(repo.Create(TestMission("m1"), TestVersion("m1", 1), {}).ok());
  ASSERT_TRUE(repo.AppendVersion(TestVersion("m1", 2), {}, {}).ok());
  std::string error;
  EXPECT_NE(RawExec(path, "UPDATE plan_versions SET content = x'00' WHERE version = 2", &error),
            SQLITE_OK);
  EXPECT_NE(error.find("immutable"), std::string::npos) << error;
  EXPECT_NE(RawExec(path, "DELETE FROM plan_versions", &error), SQLITE_OK);
  EXPECT_EQ(repo.GetVersion("m1", 2)->content, "content-2");
}

// ---- the disk fails under the database: full or read-only ----

using seaplan::testing::TinyFilesystem;

// PRAGMA integrity_check of a database file, as a separate connection sees it.
std::string IntegrityCheck(const fs::path& db_path) {
  sqlite3* db = nullptr;
  std::string result;
  if (sqlite3_open(db_path.c_str(), &db) == SQLITE_OK) {
    sqlite3_exec(
        db, "PRAGMA integrity_check",
        [](void* out, int, char** values, char**) {
          *static_cast<std::string*>(out) += values[0] ? values[0] : "";
          return 0;
        },
        &result, nullptr);
  }
  sqlite3_close(db);
  return result;
}

// Opens the store at `path` and creates mission `id`: the first error.
absl::Status OpenAndWrite(const fs::path& path, const std::string& id) {
  auto store = SqliteStore::Open(path.string());
  if (!store.ok()) return store.status();
  absl::Status status = (*store)->missions().Create(TestMission(id), TestVersion(id, 1), {});
  (void)(*store)->Close();
  return status;
}

TEST(SqliteStoreTest, FullDiskIsUnavailableWithoutLossAndWritesResumeWhenSpaceIsBack) {
  TinyFilesystem disk("384k");
  if (!disk.mounted()) GTEST_SKIP() << "full-disk test skipped: " << disk.reason();
  const fs::path path = disk.path("db.sqlite");
  auto store = SqliteStore::Open(path.string());
  ASSERT_TRUE(store.ok()) << store.status();
  MissionRepository& repo = (*store)->missions();
  // Missions with a large plan until the disk is full.
  absl::Status full;
  int stored = 0;
  for (int i = 0; i < 1000 && full.ok(); ++i) {
    PlanVersionRecord version = TestVersion("m" + std::to_string(i), 1);
    version.content = std::string(16 * 1024, static_cast<char>('a' + i % 26));
    full = repo.Create(TestMission("m" + std::to_string(i)), version, {});
    if (full.ok()) ++stored;
  }
  ASSERT_FALSE(full.ok()) << "a 384 KiB disk held 1000 plans of 16 KiB";
  EXPECT_EQ(full.code(), absl::StatusCode::kUnavailable) << full;
  EXPECT_NE(full.message().find("full"), std::string_view::npos) << full;
  EXPECT_GT(stored, 0);
  // What was acknowledged is there; the refused mission is not, even in part.
  for (int i = 0; i < stored; ++i) EXPECT_TRUE(repo.Get("m" + std::to_string(i)).ok()) << i;
  EXPECT_FALSE(repo.Get("m" + std::to_string(stored)).ok());
  // Space is back: the same write succeeds, and the file is sound.
  ASSERT_TRUE(disk.Remount("size=16m"));
  PlanVersionRecord version = TestVersion("m" + std::to_string(stored), 1);
  EXPECT_TRUE(repo.Create(TestMission("m" + std::to_string(stored)), version, {}).ok());
  ASSERT_TRUE((*store)->Close().ok());
  EXPECT_EQ(IntegrityCheck(path), "ok");
}

TEST(SqliteStoreTest, ReadOnlyDiskIsUnavailableWithoutLossAndWritesResumeWhenWritable) {
  TinyFilesystem disk("16m");
  if (!disk.mounted()) GTEST_SKIP() << "read-only disk test skipped: " << disk.reason();
  const fs::path path = disk.path("db.sqlite");
  {
    auto store = SqliteStore::Open(path.string());
    ASSERT_TRUE(store.ok()) << store.status();
    ASSERT_TRUE(
        (*store)->missions().Create(TestMission("before"), TestVersion("before", 1), {}).ok());
    ASSERT_TRUE((*store)->Close().ok());
  }
  // The data folder's filesystem is read-only when the server starts (a
  // filesystem with open files cannot be remounted read-only).
  ASSERT_TRUE(disk.Remount("ro"));
  {
    const absl::Status status = OpenAndWrite(path, "during");
    EXPECT_EQ(status.code(), absl::StatusCode::kUnavailable) << status;
    EXPECT_NE(status.message().find("not writable"), std::string_view::npos) << status.ToString();
  }
  ASSERT_TRUE(disk.Remount("rw"));
  auto store = SqliteStore::Open(path.string());
  ASSERT_TRUE(store.ok()) << store.status();
  MissionRepository& repo = (*store)->missions();
  EXPECT_TRUE(repo.Create(TestMission("after"), TestVersion("after", 1), {}).ok());
  EXPECT_TRUE(repo.Get("before").ok());
  EXPECT_FALSE(repo.Get("during").ok());
  ASSERT_TRUE((*store)->Close().ok());
  EXPECT_EQ(IntegrityCheck(path), "ok");
}

TEST(SqliteStoreTest, ReadOnlyDatabaseFileIsUnavailableAndWritableAgainAfterwards) {
  if (::geteuid() == 0) {
    GTEST_SKIP() << "file permissions do not bind root: the read-only disk test covers root";
  }
  TempDir dir;
  const fs::path path = dir / "db.sqlite";
  {
    auto store = SqliteStore::Open(path.string());
    ASSERT_TRUE(store.ok()) << store.status();
    ASSERT_TRUE(
        (*store)->missions().Create(TestMission("before"), TestVersion("before", 1), {}).ok());
    ASSERT_TRUE((*store)->Close().ok());
  }
  fs::permissions(path, fs::perms::owner_read | fs::perms::group_read | fs::perms::others_read);
  {
    const absl::Status status = OpenAndWrite(path, "during");
    EXPECT_EQ(status.code(), absl::StatusCode::kUnavailable) << status;
    EXPECT_NE(status.message().find("read-only"), std::string_view::npos) << status;
  }
  // The operator makes the files writable again (SQLite created the -wal
  // and -shm files with the database file's mode).
  for (const char* suffix : {"", "-wal", "-shm"}) {
    const fs::path file = path.string() + suffix;
    if (fs::exists(file)) fs::permissions(file, fs::perms::owner_read | fs::perms::owner_write);
  }
  auto store = SqliteStore::Open(path.string());
  ASSERT_TRUE(store.ok()) << store.status();
  const absl::Status after =
      (*store)->missions().Create(TestMission("after"), TestVersion("after", 1), {});
  EXPECT_TRUE(after.ok()) << after;
  EXPECT_TRUE((*store)->missions().Get("before").ok());
  ASSERT_TRUE((*store)->Close().ok());
  EXPECT_EQ(IntegrityCheck(path), "ok");
}

}  // namespace
}  // namespace seaplan::storage
