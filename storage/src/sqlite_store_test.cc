#include "seaplan/storage/sqlite_store.h"

#include <gtest/gtest.h>
#include <sqlite3.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <thread>

namespace seaplan::storage {
namespace {

namespace fs = std::filesystem;

class TempDir {
 public:
  TempDir() {
    path_ = fs::temp_directory_path() / ("seaplan-storage-test-" + std::to_string(::getpid()) +
                                         "-" + std::to_string(counter_++));
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

MissionRecord Mission(const std::string& id, const std::string& request_id = "") {
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

PlanVersionRecord Version(const std::string& mission, int version) {
  return {mission, version, "reason " + std::to_string(version), 2000 + version,
          "content-" + std::to_string(version)};
}

NewLogEvent Event(const std::string& message, const std::string& source = "server") {
  return {3000, 12.5, source, message};
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
  // Foreign keys: feedback for a mission that does not exist is refused.
  auto r = (*store)->missions().RecordFeedback({"no-such-mission", "v", 1, 1, "p", 1}, {}, {});
  EXPECT_EQ(r.status().code(), absl::StatusCode::kNotFound) << r.status();
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
  ASSERT_TRUE((*store)->missions().Create(Mission("new", "req-1"), Version("new", 1), {}).ok());
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

TEST(SqliteStoreTest, FeedbackIsIdempotentByVesselAndSequence) {
  auto store = SqliteStore::Open(":memory:");
  ASSERT_TRUE(store.ok());
  MissionRepository& repo = (*store)->missions();
  ASSERT_TRUE(repo.Create(Mission("m1"), Version("m1", 1), {}).ok());
  MissionUpdate update;
  update.completed_tasks = std::vector<std::string>{"v1-t0"};
  auto first = repo.RecordFeedback({"m1", "vessel-1", 7, 2, "payload-a", 100}, update,
                                   {Event("task done", "vessel-1")});
  ASSERT_TRUE(first.ok()) << first.status();
  EXPECT_TRUE(*first);
  // The retry (even with different content) changes nothing.
  MissionUpdate other;
  other.completed_tasks = std::vector<std::string>{"v1-t0", "v1-t1"};
  auto retry = repo.RecordFeedback({"m1", "vessel-1", 7, 3, "payload-b", 200}, other,
                                   {Event("again", "vessel-1")});
  ASSERT_TRUE(retry.ok()) << retry.status();
  EXPECT_FALSE(*retry);
  auto all = repo.ListFeedback("m1", 100);
  ASSERT_TRUE(all.ok());
  ASSERT_EQ(all->size(), 1u);
  EXPECT_EQ((*all)[0].payload, "payload-a");
  EXPECT_EQ(repo.Get("m1")->completed_tasks, std::vector<std::string>{"v1-t0"});
  EXPECT_EQ(repo.ListEvents("m1", 0, 100)->size(), 1u);
  // Another sequence number is new.
  EXPECT_TRUE(*repo.RecordFeedback({"m1", "vessel-1", 8, 2, "c", 300}, {}, {}));
  auto found = repo.FindFeedback("vessel-1", 8);
  ASSERT_TRUE(found.ok() && found->has_value());
  EXPECT_EQ((*found)->payload, "c");
}

TEST(SqliteStoreTest, FailingStatementInTheMiddleLeavesNothingHalfDone) {
  auto store = SqliteStore::Open(":memory:");
  ASSERT_TRUE(store.ok());
  MissionRepository& repo = (*store)->missions();
  ASSERT_TRUE(repo.Create(Mission("m1"), Version("m1", 1), {Event("created")}).ok());
  // Version 2 is inserted first, then the events: the second event violates
  // CHECK(length(source) > 0), so the whole append must roll back.
  MissionUpdate update;
  update.state = 3;
  absl::Status st = repo.AppendVersion(Version("m1", 2), update, {Event("ok"), Event("bad", "")});
  EXPECT_EQ(st.code(), absl::StatusCode::kInvalidArgument) << st;
  EXPECT_EQ(repo.GetVersion("m1", 2).status().code(), absl::StatusCode::kNotFound);
  auto m = repo.Get("m1");
  EXPECT_EQ(m->current_version, 1);
  EXPECT_EQ(m->state, 2);
  EXPECT_EQ(repo.ListEvents("m1", 0, 100)->size(), 1u);
  // A mission whose first version is refused is not stored either.
  st = repo.Create(Mission("m2"), Version("m2", 1), {Event("x", "")});
  EXPECT_FALSE(st.ok());
  EXPECT_EQ(repo.Get("m2").status().code(), absl::StatusCode::kNotFound);
  // Feedback with a bad event: the feedback row is rolled back, so the retry
  // is not mistaken for a duplicate.
  auto f = repo.RecordFeedback({"m1", "vessel-1", 1, 1, "p", 1}, {}, {Event("bad", "")});
  EXPECT_FALSE(f.ok());
  auto again = repo.RecordFeedback({"m1", "vessel-1", 1, 1, "p", 1}, {}, {});
  ASSERT_TRUE(again.ok());
  EXPECT_TRUE(*again);
  // A NaN mission time (stored as NULL) violates NOT NULL the same way.
  EXPECT_FALSE(repo.AppendEvents("m1", {{1, std::nan(""), "server", "nan"}}).ok());
  EXPECT_EQ(repo.ListEvents("m1", 0, 100)->size(), 1u);
}

TEST(SqliteStoreTest, PlanVersionsAreNumberedAndImmutable) {
  TempDir dir;
  const fs::path path = dir / "db.sqlite";
  auto store = SqliteStore::Open(path.string());
  ASSERT_TRUE(store.ok());
  MissionRepository& repo = (*store)->missions();
  ASSERT_TRUE(repo.Create(Mission("m1"), Version("m1", 1), {}).ok());
  EXPECT_EQ(repo.AppendVersion(Version("m1", 3), {}, {}).code(), absl::StatusCode::kAborted);
  EXPECT_EQ(repo.AppendVersion(Version("m1", 1), {}, {}).code(), absl::StatusCode::kAborted);
  ASSERT_TRUE(repo.AppendVersion(Version("m1", 2), {}, {}).ok());
  ASSERT_TRUE(repo.AppendVersion(Version("m1", 3), {}, {}).ok());
  EXPECT_EQ(repo.Get("m1")->current_version, 3);
  auto versions = repo.ListVersions("m1", 1, 100);
  ASSERT_TRUE(versions.ok());
  ASSERT_EQ(versions->size(), 2u);
  EXPECT_EQ((*versions)[0].version, 2);
  EXPECT_EQ((*versions)[1].version, 3);
  EXPECT_EQ((*versions)[1].content, "content-3");
  EXPECT_EQ(repo.AppendVersion(Version("nope", 1), {}, {}).code(), absl::StatusCode::kNotFound);
  // Even raw SQL cannot change or delete a stored version.
  std::string error;
  EXPECT_NE(RawExec(path, "UPDATE plan_versions SET content = x'00' WHERE version = 2", &error),
            SQLITE_OK);
  EXPECT_NE(error.find("immutable"), std::string::npos) << error;
  EXPECT_NE(RawExec(path, "DELETE FROM plan_versions", &error), SQLITE_OK);
  EXPECT_EQ(repo.GetVersion("m1", 2)->content, "content-2");
}

TEST(SqliteStoreTest, ListsPageThroughMissionsAndCharts) {
  auto store = SqliteStore::Open(":memory:");
  ASSERT_TRUE(store.ok());
  for (int i = 0; i < 5; ++i) {
    MissionRecord m = Mission("m" + std::to_string(i));
    m.state = i % 2 == 0 ? 2 : 6;
    ASSERT_TRUE((*store)->missions().Create(m, Version(m.id, 1), {}).ok());
    ChartRecord c;
    c.id = "c" + std::to_string(i);
    c.name = "chart";
    c.obstacles = "big";
    ASSERT_TRUE((*store)->charts().Insert(c).ok());
  }
  std::vector<std::string> seen;
  std::int64_t after = 0;
  do {
    auto page = (*store)->missions().List(0, 2, after);
    ASSERT_TRUE(page.ok());
    for (const auto& m : page->items) seen.push_back(m.id);
    after = page->next_after;
  } while (after != 0);
  EXPECT_EQ(seen, (std::vector<std::string>{"m0", "m1", "m2", "m3", "m4"}));
  auto active = (*store)->missions().List(2, 10, 0);
  ASSERT_EQ(active->items.size(), 3u);
  EXPECT_EQ(active->next_after, 0);
  auto charts = (*store)->charts().List(3, 0);
  ASSERT_EQ(charts->items.size(), 3u);
  EXPECT_TRUE(charts->items[0].obstacles.empty());  // listing leaves blobs out
  EXPECT_NE(charts->next_after, 0);
  EXPECT_EQ((*store)->charts().List(3, charts->next_after)->items.size(), 2u);
  EXPECT_EQ((*store)->charts().Get("c1", true)->obstacles, "big");
  EXPECT_EQ((*store)->charts().Insert(ChartRecord{.id = "c1"}).status().code(),
            absl::StatusCode::kAlreadyExists);
  EXPECT_EQ((*store)->missions().List(0, 0, 0).status().code(), absl::StatusCode::kInvalidArgument);
}

TEST(SqliteStoreTest, RequestIdIsUniqueAndConcurrentWritersAreSerialised) {
  auto store = SqliteStore::Open(":memory:");
  ASSERT_TRUE(store.ok());
  MissionRepository& repo = (*store)->missions();
  ASSERT_TRUE(repo.Create(Mission("a", "same"), Version("a", 1), {}).ok());
  EXPECT_EQ(repo.Create(Mission("b", "same"), Version("b", 1), {}).code(),
            absl::StatusCode::kAlreadyExists);
  // Many threads appending events: ids stay 1..N without gaps or repeats.
  std::vector<std::thread> threads;
  for (int t = 0; t < 4; ++t) {
    threads.emplace_back([&] {
      for (int i = 0; i < 25; ++i) ASSERT_TRUE(repo.AppendEvents("a", {Event("e")}).ok());
    });
  }
  for (auto& t : threads) t.join();
  auto events = repo.ListEvents("a", 0, 1000);
  ASSERT_EQ(events->size(), 100u);
  for (std::size_t i = 0; i < events->size(); ++i)
    EXPECT_EQ((*events)[i].event_id, static_cast<std::int64_t>(i + 1));
  EXPECT_EQ(repo.ListEvents("a", 98, 10)->size(), 2u);
  ASSERT_TRUE((*store)->Close().ok());
  EXPECT_EQ(repo.Get("a").status().code(), absl::StatusCode::kFailedPrecondition);
}

}  // namespace
}  // namespace seaplan::storage
