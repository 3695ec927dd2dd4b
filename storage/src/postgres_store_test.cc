// What only the PostgreSQL backend has: several processes on one database
// (migrations, change notifications across connections, lost connections),
// the schema guards against raw SQL, and choosing the backend by URL.
#include "seaplan/storage/postgres_store.h"

#include <gtest/gtest.h>

#include <thread>

#include "absl/strings/str_cat.h"
#include "seaplan/storage/open_store.h"
#include "seaplan/storage/testing/postgres_cluster.h"
#include "store_test_backends.h"

namespace seaplan::storage {
namespace {

using std::chrono::milliseconds;

class PostgresStoreTest : public StoreTest {
 protected:
  void SetUp() override {
    StoreTest::SetUp();
    if (IsSkipped() || HasFatalFailure()) return;
    cluster_ = *testing::ProcessCluster();
  }
  absl::Status Sql(const std::string& sql) { return cluster_->Execute(database().location(), sql); }
  testing::TemporaryPostgresCluster* cluster_ = nullptr;
};

INSTANTIATE_TEST_SUITE_P(Postgres, PostgresStoreTest, ::testing::Values(Backend::kPostgres),
                         BackendName);

TEST_P(PostgresStoreTest, RawSqlCannotChangePlanVersions) {
  ASSERT_TRUE(missions().Create(TestMission("m"), TestVersion("m", 1), {}).ok());
  absl::Status st = Sql("UPDATE plan_versions SET content = '\\x00'");
  EXPECT_FALSE(st.ok());
  EXPECT_NE(st.message().find("immutable"), std::string::npos) << st;
  EXPECT_FALSE(Sql("DELETE FROM plan_versions").ok());
  EXPECT_FALSE(Sql("TRUNCATE plan_versions CASCADE").ok());
  EXPECT_EQ(missions().GetVersion("m", 1)->content, "content-1");
}

TEST_P(PostgresStoreTest, RefusesADatabaseFromTheFuture) {
  auto version = dynamic_cast<PostgresStore&>(store()).SchemaVersion();
  ASSERT_TRUE(version.ok()) << version.status();
  EXPECT_EQ(*version, LatestSchemaVersion());
  ASSERT_TRUE(Sql("UPDATE seaplan_schema SET version = 999").ok());
  auto future = PostgresStore::Open(database().location());
  EXPECT_EQ(future.status().code(), absl::StatusCode::kFailedPrecondition) << future.status();
}

// Replicas started together on an empty database migrate it once.
TEST_P(PostgresStoreTest, ReplicasStartingTogetherMigrateOnce) {
  auto fresh = testing::ProcessCluster().value()->CreateDatabase();
  ASSERT_TRUE(fresh.ok()) << fresh.status();
  std::vector<absl::StatusOr<std::unique_ptr<PostgresStore>>> opened(4);
  std::vector<std::thread> threads;
  threads.reserve(opened.size());
  for (auto& slot : opened) {
    threads.emplace_back([&slot, &fresh] { slot = PostgresStore::Open(*fresh); });
  }
  for (auto& t : threads) t.join();
  for (auto& store : opened) {
    ASSERT_TRUE(store.ok()) << store.status();
    EXPECT_EQ(*(*store)->SchemaVersion(), LatestSchemaVersion());
  }
  ASSERT_TRUE((*opened[0])->missions().Create(TestMission("m"), TestVersion("m", 1), {}).ok());
  EXPECT_EQ((*opened[3])->missions().Get("m")->name, "mission m");
}

// A watcher on one connection (one replica) sees commits made through
// another (another replica).
TEST_P(PostgresStoreTest, ChangeFeedCrossesConnections) {
  std::unique_ptr<Store> writer = OpenAnother();
  ASSERT_NE(writer, nullptr);
  ChangeFeed& feed = store().changes();
  std::uint64_t seen = feed.Generation("m");
  ASSERT_TRUE(writer->missions().Create(TestMission("m"), TestVersion("m", 1), {}).ok());
  seen = feed.Wait("m", seen, milliseconds(60000));
  // Read after the wake-up: the commit is visible.
  EXPECT_TRUE(missions().Get("m").ok());
  ASSERT_TRUE(writer->missions().AppendVersion(TestVersion("m", 2), {}, {}).ok());
  EXPECT_NE(feed.Wait("m", seen, milliseconds(60000)), seen);
  EXPECT_EQ(missions().Get("m")->current_version, 2);
  ASSERT_TRUE(writer->Close().ok());
}

// The database drops every seaplan connection (a restart, a failover):
// watchers are woken to re-read, the listener reconnects and later commits
// still wake them, and calls work again once the pool has reconnected.
TEST_P(PostgresStoreTest, SurvivesLosingItsConnections) {
  ASSERT_TRUE(missions().Create(TestMission("m"), TestVersion("m", 1), {}).ok());
  ChangeFeed& feed = store().changes();
  std::uint64_t seen = feed.Generation("m");
  const std::string kill_all = absl::StrCat(
      "SELECT pg_terminate_backend(pid) FROM pg_stat_activity WHERE application_name = 'seaplan' "
      "AND datname = current_database()");
  ASSERT_TRUE(Sql(kill_all).ok());
  seen = feed.Wait("m", seen, milliseconds(60000));  // woken by the reconnection
  // Calls on connections that were killed fail as Unavailable and are
  // dropped from the pool; within a few calls a fresh connection serves.
  absl::Status last;
  for (int attempt = 0; attempt < 10; ++attempt) {
    last = missions().AppendEvents("m", {TestEvent("after")}).status();
    if (last.ok()) break;
    EXPECT_EQ(last.code(), absl::StatusCode::kUnavailable) << last;
  }
  ASSERT_TRUE(last.ok()) << last;
  // The listener is back: a commit from another connection wakes the watcher.
  std::unique_ptr<Store> writer = OpenAnother();
  ASSERT_NE(writer, nullptr);
  bool woken = false;
  for (int i = 0; i < 100 && !woken; ++i) {
    seen = feed.Generation("m");
    ASSERT_TRUE(writer->missions().AppendEvents("m", {TestEvent("ping")}).ok());
    woken = feed.Wait("m", seen, milliseconds(1000)) != seen;
  }
  EXPECT_TRUE(woken);
  ASSERT_TRUE(writer->Close().ok());
}

TEST_P(PostgresStoreTest, OpenStoreChoosesTheBackendByUrl) {
  auto pg = OpenStore(database().location(), "/nonexistent-unused");
  ASSERT_TRUE(pg.ok()) << pg.status();
  EXPECT_NE(dynamic_cast<PostgresStore*>(pg->store.get()), nullptr);
  ASSERT_TRUE(pg->store->missions().Create(TestMission("m"), TestVersion("m", 1), {}).ok());
  EXPECT_TRUE(missions().Get("m").ok());
  auto bad = OpenStore("mysql://localhost/x", "");
  EXPECT_EQ(bad.status().code(), absl::StatusCode::kInvalidArgument) << bad.status();
  auto unreachable = PostgresStore::Open("postgresql://seaplan@127.0.0.1:1/none?connect_timeout=5");
  EXPECT_EQ(unreachable.status().code(), absl::StatusCode::kUnavailable) << unreachable.status();
}

TEST(RedactDatabaseUrlTest, HidesPasswords) {
  EXPECT_EQ(RedactDatabaseUrl("postgresql://app:s3cret@db:5432/seaplan"),
            "postgresql://app:***@db:5432/seaplan");
  EXPECT_EQ(RedactDatabaseUrl("postgresql://app@db/seaplan"), "postgresql://app@db/seaplan");
  EXPECT_EQ(RedactDatabaseUrl("host=db password=s3cret dbname=x"), "host=db password=*** dbname=x");
}

TEST(OpenStoreTest, EmptyUrlOpensSqliteInTheDataFolder) {
  const std::filesystem::path dir =
      std::filesystem::temp_directory_path() / ("seaplan-open-store-" + std::to_string(::getpid()));
  std::filesystem::remove_all(dir);
  auto opened = OpenStore("", (dir / "nested").string());
  ASSERT_TRUE(opened.ok()) << opened.status();
  EXPECT_EQ(opened->description, (dir / "nested" / "seaplan.db").string());
  EXPECT_TRUE(std::filesystem::exists(dir / "nested" / "seaplan.db"));
  ASSERT_TRUE(opened->store->Close().ok());
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace seaplan::storage
