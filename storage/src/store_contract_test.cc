// The guarantees of repositories.h, checked on every backend (SQLite and
// PostgreSQL) by the same tests.
#include <gtest/gtest.h>

#include <atomic>
#include <cmath>
#include <iostream>
#include <set>
#include <thread>
#include <vector>

#include "store_test_backends.h"

namespace seaplan::storage {
namespace {

using std::chrono::milliseconds;

INSTANTIATE_TEST_SUITE_P(Backends, StoreTest,
                         ::testing::Values(Backend::kSqlite, Backend::kPostgres), BackendName);

TEST_P(StoreTest, SchemaIsLatestAndReopeningKeepsData) {
  ASSERT_TRUE(missions().Create(TestMission("m1"), TestVersion("m1", 1), {TestEvent("hi")}).ok());
  ASSERT_TRUE(store().Close().ok());
  EXPECT_EQ(missions().Get("m1").status().code(), absl::StatusCode::kFailedPrecondition);
  std::unique_ptr<Store> again = OpenAnother();
  ASSERT_NE(again, nullptr);
  auto m = again->missions().Get("m1");
  ASSERT_TRUE(m.ok()) << m.status();
  EXPECT_EQ(m->spec, std::string("spec\0bytes", 10));
  EXPECT_EQ(again->missions().GetVersion("m1", 1)->content, "content-1");
  EXPECT_EQ(again->missions().ListEvents("m1", 0, 10)->size(), 1u);
}

TEST_P(StoreTest, FeedbackIsIdempotentByVesselAndSequence) {
  MissionRepository& repo = missions();
  ASSERT_TRUE(repo.Create(TestMission("m1"), TestVersion("m1", 1), {}).ok());
  MissionUpdate update;
  update.completed_tasks = std::vector<std::string>{"v1-t0"};
  auto first = repo.RecordFeedback({"m1", "vessel-1", 7, 2, "payload-a", 100}, update,
                                   {TestEvent("task done", "vessel-1")});
  ASSERT_TRUE(first.ok()) << first.status();
  EXPECT_TRUE(*first);
  // The retry (even with different content) changes nothing.
  MissionUpdate other;
  other.completed_tasks = std::vector<std::string>{"v1-t0", "v1-t1"};
  auto retry = repo.RecordFeedback({"m1", "vessel-1", 7, 3, "payload-b", 200}, other,
                                   {TestEvent("again", "vessel-1")});
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
  EXPECT_FALSE(repo.FindFeedback("vessel-1", 9)->has_value());
  // ListFeedback gives the latest reports, oldest first.
  auto latest = repo.ListFeedback("m1", 1);
  ASSERT_EQ(latest->size(), 1u);
  EXPECT_EQ((*latest)[0].sequence_number, 8);
  // Feedback for a mission that does not exist is refused.
  auto r = repo.RecordFeedback({"no-such-mission", "v", 1, 1, "p", 1}, {}, {});
  EXPECT_EQ(r.status().code(), absl::StatusCode::kNotFound) << r.status();
}

TEST_P(StoreTest, FeedbackPagesInArrivalOrderPerMissionAndResumesAfterTheCursor) {
  MissionRepository& repo = missions();
  ASSERT_TRUE(repo.Create(TestMission("m1"), TestVersion("m1", 1), {}).ok());
  ASSERT_TRUE(repo.Create(TestMission("m2"), TestVersion("m2", 1), {}).ok());
  // Two missions' reports interleaved; the vessel's numbers deliberately not
  // in arrival order (a journal resent after an outage).
  for (int i = 0; i < 5; ++i) {
    ASSERT_TRUE(
        *repo.RecordFeedback({"m1", "vessel-1", 100 - i, 4, "m1-" + std::to_string(i), i}, {}, {}));
    ASSERT_TRUE(
        *repo.RecordFeedback({"m2", "vessel-2", i, 4, "m2-" + std::to_string(i), i}, {}, {}));
  }
  std::vector<std::string> payloads;
  std::int64_t after = 0, last_seq = 0;
  int pages = 0;
  do {
    auto page = repo.ListFeedbackPage("m1", after, 2);
    ASSERT_TRUE(page.ok()) << page.status();
    ++pages;
    for (const FeedbackRecord& f : page->items) {
      EXPECT_EQ(f.mission_id, "m1");
      EXPECT_GT(f.seq, last_seq);  // strictly increasing across pages
      last_seq = f.seq;
      payloads.push_back(f.payload);
    }
    after = page->next_after;
  } while (after != 0);
  EXPECT_EQ(pages, 3);
  EXPECT_EQ(payloads, (std::vector<std::string>{"m1-0", "m1-1", "m1-2", "m1-3", "m1-4"}));
  // The last report's seq asks for what arrived since: nothing, then the new one.
  EXPECT_TRUE(repo.ListFeedbackPage("m1", last_seq, 10)->items.empty());
  ASSERT_TRUE(*repo.RecordFeedback({"m1", "vessel-1", 200, 1, "m1-late", 9}, {}, {}));
  auto since = repo.ListFeedbackPage("m1", last_seq, 10);
  ASSERT_TRUE(since.ok()) << since.status();
  ASSERT_EQ(since->items.size(), 1u);
  EXPECT_EQ(since->items[0].payload, "m1-late");
  EXPECT_EQ(since->items[0].sequence_number, 200);
  EXPECT_EQ(since->next_after, 0);
  // FindFeedback reports the same cursor.
  EXPECT_EQ((*repo.FindFeedback("vessel-1", 200))->seq, since->items[0].seq);
  EXPECT_TRUE(repo.ListFeedbackPage("no-such-mission", 0, 10)->items.empty());
  EXPECT_EQ(repo.ListFeedbackPage("m1", 0, 0).status().code(), absl::StatusCode::kInvalidArgument);
}

TEST_P(StoreTest, FailingStatementInTheMiddleLeavesNothingHalfDone) {
  MissionRepository& repo = missions();
  ASSERT_TRUE(repo.Create(TestMission("m1"), TestVersion("m1", 1), {TestEvent("created")}).ok());
  // Version 2 is inserted first, then the events: the second event violates
  // CHECK(length(source) > 0), so the whole append must roll back.
  MissionUpdate update;
  update.state = 3;
  absl::Status st =
      repo.AppendVersion(TestVersion("m1", 2), update, {TestEvent("ok"), TestEvent("bad", "")});
  EXPECT_EQ(st.code(), absl::StatusCode::kInvalidArgument) << st;
  EXPECT_EQ(repo.GetVersion("m1", 2).status().code(), absl::StatusCode::kNotFound);
  auto m = repo.Get("m1");
  EXPECT_EQ(m->current_version, 1);
  EXPECT_EQ(m->state, 2);
  EXPECT_EQ(repo.ListEvents("m1", 0, 100)->size(), 1u);
  // A mission whose first version is refused is not stored either.
  st = repo.Create(TestMission("m2"), TestVersion("m2", 1), {TestEvent("x", "")});
  EXPECT_FALSE(st.ok());
  EXPECT_EQ(repo.Get("m2").status().code(), absl::StatusCode::kNotFound);
  // Feedback with a bad event: the feedback row is rolled back, so the retry
  // is not mistaken for a duplicate.
  auto f = repo.RecordFeedback({"m1", "vessel-1", 1, 1, "p", 1}, {}, {TestEvent("bad", "")});
  EXPECT_FALSE(f.ok());
  auto again = repo.RecordFeedback({"m1", "vessel-1", 1, 1, "p", 1}, {}, {});
  ASSERT_TRUE(again.ok());
  EXPECT_TRUE(*again);
  // A NaN mission time is refused the same way.
  EXPECT_FALSE(repo.AppendEvents("m1", {{1, std::nan(""), "server", "nan"}}).ok());
  EXPECT_EQ(repo.ListEvents("m1", 0, 100)->size(), 1u);
  // The store is still usable after the failures.
  EXPECT_TRUE(repo.AppendVersion(TestVersion("m1", 2), update, {TestEvent("ok")}).ok());
}

TEST_P(StoreTest, PlanVersionsAreNumberedWithoutGaps) {
  MissionRepository& repo = missions();
  ASSERT_TRUE(repo.Create(TestMission("m1"), TestVersion("m1", 1), {}).ok());
  EXPECT_EQ(repo.AppendVersion(TestVersion("m1", 3), {}, {}).code(), absl::StatusCode::kAborted);
  EXPECT_EQ(repo.AppendVersion(TestVersion("m1", 1), {}, {}).code(), absl::StatusCode::kAborted);
  ASSERT_TRUE(repo.AppendVersion(TestVersion("m1", 2), {}, {}).ok());
  PlanVersionRecord v3 = TestVersion("m1", 3);
  v3.engine_state = std::string("\0state", 6);
  ASSERT_TRUE(repo.AppendVersion(v3, {}, {}).ok());
  EXPECT_EQ(repo.Get("m1")->current_version, 3);
  auto versions = repo.ListVersions("m1", 1, 100);
  ASSERT_TRUE(versions.ok());
  ASSERT_EQ(versions->size(), 2u);
  EXPECT_EQ((*versions)[0].version, 2);
  EXPECT_EQ((*versions)[1].version, 3);
  EXPECT_EQ((*versions)[1].content, "content-3");
  EXPECT_EQ((*versions)[1].engine_state, std::string("\0state", 6));
  EXPECT_EQ(repo.ListVersions("m1", 0, 1)->size(), 1u);
  EXPECT_EQ(repo.AppendVersion(TestVersion("nope", 1), {}, {}).code(), absl::StatusCode::kNotFound);
  EXPECT_EQ(repo.GetVersion("m1", 4).status().code(), absl::StatusCode::kNotFound);
}

TEST_P(StoreTest, ListsPageThroughMissionsAndCharts) {
  for (int i = 0; i < 5; ++i) {
    MissionRecord m = TestMission("m" + std::to_string(i));
    m.state = i % 2 == 0 ? 2 : 6;
    ASSERT_TRUE(missions().Create(m, TestVersion(m.id, 1), {}).ok());
    ChartRecord c;
    c.id = "c" + std::to_string(i);
    c.name = "chart";
    c.obstacles = "big";
    ASSERT_TRUE(store().charts().Insert(c).ok());
  }
  std::vector<std::string> seen;
  std::int64_t after = 0;
  do {
    auto page = missions().List(0, 2, after);
    ASSERT_TRUE(page.ok());
    for (const auto& m : page->items) seen.push_back(m.id);
    after = page->next_after;
  } while (after != 0);
  EXPECT_EQ(seen, (std::vector<std::string>{"m0", "m1", "m2", "m3", "m4"}));
  auto active = missions().List(2, 10, 0);
  ASSERT_EQ(active->items.size(), 3u);
  EXPECT_EQ(active->next_after, 0);
  auto charts = store().charts().List(3, 0);
  ASSERT_EQ(charts->items.size(), 3u);
  EXPECT_TRUE(charts->items[0].obstacles.empty());  // listing leaves blobs out
  EXPECT_NE(charts->next_after, 0);
  EXPECT_EQ(store().charts().List(3, charts->next_after)->items.size(), 2u);
  EXPECT_EQ(store().charts().Get("c1", true)->obstacles, "big");
  EXPECT_TRUE(store().charts().Get("c1", false)->obstacles.empty());
  EXPECT_EQ(store().charts().Get("c9", false).status().code(), absl::StatusCode::kNotFound);
  EXPECT_EQ(store().charts().Insert(ChartRecord{.id = "c1"}).status().code(),
            absl::StatusCode::kAlreadyExists);
  EXPECT_EQ(missions().List(0, 0, 0).status().code(), absl::StatusCode::kInvalidArgument);
}

TEST_P(StoreTest, RequestIdIsUniqueAndConcurrentWritersAreSerialised) {
  MissionRepository& repo = missions();
  ASSERT_TRUE(repo.Create(TestMission("a", "same"), TestVersion("a", 1), {}).ok());
  EXPECT_EQ(repo.Create(TestMission("b", "same"), TestVersion("b", 1), {}).code(),
            absl::StatusCode::kAlreadyExists);
  EXPECT_EQ(repo.Create(TestMission("a"), TestVersion("a", 1), {}).code(),
            absl::StatusCode::kAlreadyExists);
  auto found = repo.FindByRequestId("same");
  ASSERT_TRUE(found.ok() && found->has_value());
  EXPECT_EQ((*found)->id, "a");
  EXPECT_FALSE(repo.FindByRequestId("other")->has_value());
  // Many threads appending events: ids stay 1..N without gaps or repeats.
  constexpr int kWriters = 4;
  std::vector<std::thread> threads;
  threads.reserve(kWriters);
  for (int t = 0; t < kWriters; ++t) {
    threads.emplace_back([&] {
      for (int i = 0; i < 25; ++i) ASSERT_TRUE(repo.AppendEvents("a", {TestEvent("e")}).ok());
    });
  }
  for (auto& t : threads) t.join();
  auto events = repo.ListEvents("a", 0, 1000);
  ASSERT_EQ(events->size(), 100u);
  for (std::size_t i = 0; i < events->size(); ++i)
    EXPECT_EQ((*events)[i].event_id, static_cast<std::int64_t>(i + 1));
  EXPECT_EQ(repo.ListEvents("a", 98, 10)->size(), 2u);
}

// Two connections (as two server processes would have) race on one mission:
// each appends "the next version" and retries when told another was first.
// Every version is stored exactly once, numbered 1..N; event ids likewise;
// a report sent through both is stored once.
TEST_P(StoreTest, WritersOnTwoConnectionsNeverCollide) {
  std::unique_ptr<Store> other = OpenAnother();
  ASSERT_NE(other, nullptr);
  ASSERT_TRUE(missions().Create(TestMission("m"), TestVersion("m", 1), {}).ok());
  constexpr int kPerWriter = 15;
  std::atomic<int> stored{0}, aborted{0}, duplicates{0};
  auto writer = [&](Store* s, const std::string& name) {
    for (int i = 0; i < kPerWriter; ++i) {
      while (true) {
        auto m = s->missions().Get("m");
        ASSERT_TRUE(m.ok()) << m.status();
        PlanVersionRecord v = TestVersion("m", m->current_version + 1);
        v.reason = name;
        absl::Status st = s->missions().AppendVersion(v, {}, {TestEvent(name)});
        if (st.ok()) {
          ++stored;
          break;
        }
        ASSERT_EQ(st.code(), absl::StatusCode::kAborted) << st;
        ++aborted;
      }
      auto fresh = s->missions().RecordFeedback({"m", "vessel-1", i, 1, name, 1}, {}, {});
      ASSERT_TRUE(fresh.ok()) << fresh.status();
      if (!*fresh) ++duplicates;
    }
  };
  std::thread a(writer, &store(), "a"), b(writer, other.get(), "b");
  a.join();
  b.join();
  EXPECT_EQ(stored.load(), 2 * kPerWriter);
  auto versions = missions().ListVersions("m", 0, 1000);
  ASSERT_TRUE(versions.ok());
  ASSERT_EQ(versions->size(), static_cast<std::size_t>(2 * kPerWriter + 1));
  for (std::size_t i = 0; i < versions->size(); ++i) {
    EXPECT_EQ((*versions)[i].version, static_cast<int>(i + 1));
  }
  EXPECT_EQ(missions().Get("m")->current_version, 2 * kPerWriter + 1);
  auto events = missions().ListEvents("m", 0, 1000);
  ASSERT_EQ(events->size(), static_cast<std::size_t>(2 * kPerWriter));
  for (std::size_t i = 0; i < events->size(); ++i) {
    EXPECT_EQ((*events)[i].event_id, static_cast<std::int64_t>(i + 1));
  }
  // Both wrote sequence numbers 0..kPerWriter-1 of the same vessel.
  EXPECT_EQ(duplicates.load(), kPerWriter);
  EXPECT_EQ(missions().ListFeedback("m", 1000)->size(), static_cast<std::size_t>(kPerWriter));
  ASSERT_TRUE(other->Close().ok());
}

// ---- work leases ----

TEST_P(StoreTest, WorkIsClaimedByOneHolderRenewedAndCompleted) {
  ASSERT_TRUE(missions().Create(TestMission("m"), TestVersion("m", 1), {}).ok());
  EXPECT_FALSE(work().Get("m")->has_value());
  EXPECT_FALSE(work().Claim("m", "r1", milliseconds(60000))->has_value());  // nothing to do
  auto first = work().Request("m", {"task failed", 1});
  ASSERT_TRUE(first.ok()) << first.status();
  EXPECT_TRUE(*first);
  EXPECT_FALSE(*work().Request("m", {"deviation", 1}));  // joins the pending work
  auto lease = work().Claim("m", "r1", milliseconds(60000));
  ASSERT_TRUE(lease.ok()) << lease.status();
  ASSERT_TRUE(lease->has_value());
  EXPECT_EQ((*lease)->holder, "r1");
  EXPECT_EQ((*lease)->reason, "deviation");
  EXPECT_EQ((*lease)->claimed_requests, 2);
  EXPECT_GT((*lease)->expires_at_ms, 0);
  // Held and not expired: nobody else gets it, not even by ClaimNext.
  EXPECT_FALSE(work().Claim("m", "r2", milliseconds(60000))->has_value());
  EXPECT_TRUE(work().ClaimNext("r2", milliseconds(60000), 10)->empty());
  auto renewed = work().Renew(**lease, milliseconds(120000));
  ASSERT_TRUE(renewed.ok()) << renewed.status();
  EXPECT_GE(renewed->expires_at_ms, (*lease)->expires_at_ms);
  EXPECT_EQ(renewed->token, (*lease)->token);
  auto more = work().Complete(**lease);
  ASSERT_TRUE(more.ok()) << more.status();
  EXPECT_FALSE(*more);
  auto done = work().Get("m");
  ASSERT_TRUE(done->has_value());
  EXPECT_FALSE((*done)->pending());
  EXPECT_TRUE((*done)->holder.empty());
  EXPECT_FALSE(work().Claim("m", "r2", milliseconds(60000))->has_value());
  // A completed lease cannot be used again.
  EXPECT_EQ(work().Complete(**lease).status().code(), absl::StatusCode::kAborted);
  // Bad arguments and unknown missions.
  EXPECT_EQ(work().Request("nope", {"x", 1}).status().code(), absl::StatusCode::kNotFound);
  EXPECT_EQ(work().Claim("m", "", milliseconds(1000)).status().code(),
            absl::StatusCode::kInvalidArgument);
  EXPECT_EQ(work().ClaimNext("r1", milliseconds(0), 1).status().code(),
            absl::StatusCode::kInvalidArgument);
}

TEST_P(StoreTest, RequestsDuringARunAreNotLost) {
  ASSERT_TRUE(missions().Create(TestMission("m"), TestVersion("m", 1), {}).ok());
  ASSERT_TRUE(work().Request("m", {"first", 1}).ok());
  auto lease = work().Claim("m", "r1", milliseconds(60000));
  ASSERT_TRUE(lease.ok() && lease->has_value());
  ASSERT_TRUE(work().Request("m", {"second", 2}).ok());  // arrives while r1 works
  auto more = work().Complete(**lease);
  ASSERT_TRUE(more.ok());
  EXPECT_TRUE(*more);
  auto next = work().ClaimNext("r2", milliseconds(60000), 10);
  ASSERT_TRUE(next.ok());
  ASSERT_EQ(next->size(), 1u);
  EXPECT_EQ((*next)[0].reason, "second");
  EXPECT_EQ((*next)[0].base_version, 2);
  EXPECT_GT((*next)[0].token, (*lease)->token);
}

// A request claimed in one step: it covers the requests pending before
// it, and records nothing while another lease on the work is live.
TEST_P(StoreTest, RequestAndClaimRecordsOnlyWhenItGetsTheWork) {
  ASSERT_TRUE(missions().Create(TestMission("m"), TestVersion("m", 1), {}).ok());
  ASSERT_TRUE(work().Request("m", {"task failed", 1}).ok());  // pending, nobody holds it
  auto mine = work().RequestAndClaim("m", "operator", "r1", milliseconds(60000));
  ASSERT_TRUE(mine.ok()) << mine.status();
  ASSERT_TRUE(mine->has_value());
  EXPECT_EQ((*mine)->holder, "r1");
  EXPECT_EQ((*mine)->reason, "operator");
  EXPECT_EQ((*mine)->requests, 2);
  EXPECT_EQ((*mine)->claimed_requests, 2);
  EXPECT_EQ((*mine)->base_version, 1);  // the mission's current version
  // Held: another holder's request is not recorded, nor the holder's own.
  std::unique_ptr<Store> other = OpenAnother();
  ASSERT_NE(other, nullptr);
  for (auto* w : {&other->work(), &work()}) {
    auto refused = w->RequestAndClaim("m", "second operator", "r2", milliseconds(60000));
    ASSERT_TRUE(refused.ok()) << refused.status();
    EXPECT_FALSE(refused->has_value());
  }
  EXPECT_EQ((*work().Get("m"))->requests, 2);
  EXPECT_FALSE(*work().Complete(**mine));  // nothing left pending
  ASSERT_TRUE(missions().AppendVersion(TestVersion("m", 2), {}, {}).ok());
  auto theirs = other->work().RequestAndClaim("m", "second operator", "r2", milliseconds(1));
  ASSERT_TRUE(theirs.ok() && theirs->has_value()) << theirs.status();
  EXPECT_EQ((*theirs)->claimed_requests, 3);
  EXPECT_EQ((*theirs)->base_version, 2);
  EXPECT_GT((*theirs)->token, (*mine)->token);
  // An expired lease does not block: its pending request is covered too.
  std::this_thread::sleep_for(milliseconds(50));
  auto after = work().RequestAndClaim("m", "third", "r1", milliseconds(60000));
  ASSERT_TRUE(after.ok() && after->has_value()) << after.status();
  EXPECT_EQ((*after)->claimed_requests, 4);
  EXPECT_EQ(other->work().Complete(**theirs).status().code(), absl::StatusCode::kAborted);
  EXPECT_EQ(work().RequestAndClaim("nope", "x", "r1", milliseconds(1000)).status().code(),
            absl::StatusCode::kNotFound);
  EXPECT_EQ(work().RequestAndClaim("m", "x", "", milliseconds(1000)).status().code(),
            absl::StatusCode::kInvalidArgument);
  ASSERT_TRUE(other->Close().ok());
}

TEST_P(StoreTest, ExpiredLeaseIsTakenOverAndTheOldHolderIsFenced) {
  ASSERT_TRUE(missions().Create(TestMission("m"), TestVersion("m", 1), {}).ok());
  ASSERT_TRUE(work().Request("m", {"replan", 1}).ok());
  auto dead = work().Claim("m", "dead-replica", milliseconds(1));
  ASSERT_TRUE(dead.ok() && dead->has_value());
  // Sleeping only guarantees a lower bound on the time passed, which is all
  // this needs: the 1 ms lease has expired.
  std::this_thread::sleep_for(milliseconds(50));
  std::unique_ptr<Store> other = OpenAnother();
  ASSERT_NE(other, nullptr);
  auto taken = other->work().ClaimNext("live-replica", milliseconds(60000), 10);
  ASSERT_TRUE(taken.ok()) << taken.status();
  ASSERT_EQ(taken->size(), 1u);
  EXPECT_EQ((*taken)[0].holder, "live-replica");
  EXPECT_GT((*taken)[0].token, (*dead)->token);
  EXPECT_EQ(work().Renew(**dead, milliseconds(60000)).status().code(), absl::StatusCode::kAborted);
  EXPECT_EQ(work().Complete(**dead).status().code(), absl::StatusCode::kAborted);
  EXPECT_EQ(work().Release(**dead).code(), absl::StatusCode::kAborted);
  EXPECT_EQ((*work().Get("m"))->holder, "live-replica");
  ASSERT_TRUE(other->Close().ok());
}

// A holder whose lease was taken over cannot append a version or change
// the mission: its fenced writes are refused and change nothing.
TEST_P(StoreTest, WritesFencedByALostLeaseAreRefused) {
  ASSERT_TRUE(missions().Create(TestMission("m"), TestVersion("m", 1), {}).ok());
  ASSERT_TRUE(work().Request("m", {"replan", 1}).ok());
  auto dead = work().Claim("m", "dead-replica", milliseconds(1));
  ASSERT_TRUE(dead.ok() && dead->has_value());
  MissionUpdate stale;
  stale.fence = WorkFence{(*dead)->holder, (*dead)->token};
  std::this_thread::sleep_for(milliseconds(50));  // the 1 ms lease has expired
  auto live = work().Claim("m", "live-replica", milliseconds(60000));
  ASSERT_TRUE(live.ok() && live->has_value());
  EXPECT_EQ(missions().AppendVersion(TestVersion("m", 2), stale, {}).code(),
            absl::StatusCode::kAborted);
  stale.last_state = "from the stale holder";
  EXPECT_EQ(missions().Update("m", stale, {}).code(), absl::StatusCode::kAborted);
  EXPECT_EQ(missions().Get("m")->current_version, 1);
  EXPECT_NE(missions().Get("m")->last_state, "from the stale holder");
  MissionUpdate held;
  held.fence = WorkFence{(*live)->holder, (*live)->token};
  EXPECT_TRUE(missions().AppendVersion(TestVersion("m", 2), held, {}).ok());
  EXPECT_EQ(missions().Get("m")->current_version, 2);
}

TEST_P(StoreTest, ReleasedWorkIsFreeAtOnce) {
  for (const char* id : {"a", "b", "c"}) {
    ASSERT_TRUE(missions().Create(TestMission(id), TestVersion(id, 1), {}).ok());
    ASSERT_TRUE(work().Request(id, {"replan", 1}).ok());
  }
  auto mine = work().ClaimNext("r1", milliseconds(60000), 2);
  ASSERT_TRUE(mine.ok());
  ASSERT_EQ(mine->size(), 2u);
  ASSERT_TRUE(work().Release((*mine)[0]).ok());
  auto shutdown = work().ReleaseAll("r1");  // graceful shutdown hands back the rest
  ASSERT_TRUE(shutdown.ok());
  EXPECT_EQ(*shutdown, 1);
  auto theirs = work().ClaimNext("r2", milliseconds(60000), 10);
  ASSERT_TRUE(theirs.ok());
  EXPECT_EQ(theirs->size(), 3u);
}

// Two connections claiming concurrently never get the same item.
TEST_P(StoreTest, ConcurrentClaimersGetDisjointWork) {
  constexpr int kMissions = 30;
  for (int i = 0; i < kMissions; ++i) {
    const std::string id = "m" + std::to_string(i);
    ASSERT_TRUE(missions().Create(TestMission(id), TestVersion(id, 1), {}).ok());
    ASSERT_TRUE(work().Request(id, {"replan", 1}).ok());
  }
  std::unique_ptr<Store> other = OpenAnother();
  ASSERT_NE(other, nullptr);
  std::mutex mu;
  std::multiset<std::string> claimed;
  auto claimer = [&](Store* s, const std::string& holder) {
    while (true) {
      auto got = s->work().ClaimNext(holder, milliseconds(60000), 2);
      ASSERT_TRUE(got.ok()) << got.status();
      if (got->empty()) return;
      std::lock_guard lock(mu);
      for (const WorkLease& w : *got) claimed.insert(w.mission_id);
    }
  };
  std::thread a(claimer, &store(), "r1"), b(claimer, other.get(), "r2");
  a.join();
  b.join();
  EXPECT_EQ(claimed.size(), static_cast<std::size_t>(kMissions));
  for (const std::string& id : claimed) EXPECT_EQ(claimed.count(id), 1u) << id;
  ASSERT_TRUE(other->Close().ok());
}

// Work requested with a feedback report is stored in the same transaction:
// a duplicate report requests nothing, a failed one requests nothing.
TEST_P(StoreTest, WorkRequestedWithFeedbackIsAtomic) {
  ASSERT_TRUE(missions().Create(TestMission("m"), TestVersion("m", 1), {}).ok());
  MissionUpdate update;
  update.request_work = WorkRequest{"task failed", 1};
  ASSERT_TRUE(*missions().RecordFeedback({"m", "vessel-1", 1, 1, "p", 1}, update, {}));
  EXPECT_FALSE(*missions().RecordFeedback({"m", "vessel-1", 1, 1, "p", 1}, update, {}));
  EXPECT_FALSE(missions()
                   .RecordFeedback({"m", "vessel-1", 2, 1, "p", 1}, update, {TestEvent("x", "")})
                   .ok());
  auto w = work().Get("m");
  ASSERT_TRUE(w.ok() && w->has_value());
  EXPECT_EQ((*w)->requests, 1);
  EXPECT_EQ((*w)->reason, "task failed");
  EXPECT_TRUE((*w)->pending());
}

// ---- change feed ----

TEST_P(StoreTest, ChangeFeedWakesAWatcherAfterEachCommit) {
  ChangeFeed& feed = store().changes();
  ASSERT_TRUE(missions().Create(TestMission("m"), TestVersion("m", 1), {}).ok());
  std::uint64_t seen = feed.Generation("m");
  // A watcher waiting before the write is woken by it.
  std::atomic<std::uint64_t> woke_at{seen};
  std::thread watcher([&] { woke_at = feed.Wait("m", seen, milliseconds(60000)); });
  ASSERT_TRUE(missions().AppendEvents("m", {TestEvent("x")}).ok());
  watcher.join();
  EXPECT_NE(woke_at.load(), seen);
  // Each kind of write moves the generation (eventually: PostgreSQL delivers
  // notifications asynchronously, so wait for it).
  auto moves = [&](const std::function<void()>& write) {
    const std::uint64_t before = feed.Generation("m");
    write();
    return feed.Wait("m", before, milliseconds(60000)) != before;
  };
  EXPECT_TRUE(
      moves([&] { ASSERT_TRUE(missions().AppendVersion(TestVersion("m", 2), {}, {}).ok()); }));
  EXPECT_TRUE(moves([&] {
    ASSERT_TRUE(*missions().RecordFeedback({"m", "v", 1, 1, "p", 1}, {}, {}));
  }));
  MissionUpdate update;
  update.state = 4;
  EXPECT_TRUE(moves([&] { ASSERT_TRUE(missions().Update("m", update, {}).ok()); }));
  // Other missions' generations are independent of this one's writes.
  const std::uint64_t quiet = feed.Generation("other");
  EXPECT_EQ(feed.Wait("other", quiet, milliseconds(20)), quiet);
  // Closing the store releases waiters at once.
  const std::uint64_t now = feed.Generation("m");
  std::thread closer([&] { EXPECT_TRUE(store().Close().ok()); });
  EXPECT_EQ(feed.Wait("m", now, milliseconds(600000)), now);
  closer.join();
}

TokenRecord TestToken(const std::string& id, const std::string& role,
                      const std::string& vessel = "") {
  TokenRecord t;
  t.id = id;
  t.secret_hash = std::string(64, 'a');
  t.role = role;
  t.vessel_id = vessel;
  t.description = "for " + id;
  t.created_by = "creator";
  t.created_at_ms = 1000;
  t.expires_at_ms = 5000;
  return t;
}

TEST_P(StoreTest, TokensAreStoredListedAndRevokedOnce) {
  TokenRepository& tokens = store().tokens();
  ASSERT_TRUE(tokens.Insert(TestToken("t1", "admin")).ok());
  ASSERT_TRUE(tokens.Insert(TestToken("t2", "vessel", "mass-1")).ok());
  EXPECT_EQ(tokens.Insert(TestToken("t1", "viewer")).code(), absl::StatusCode::kAlreadyExists);
  // The schema refuses a vessel token without a vessel and an unknown role.
  EXPECT_EQ(tokens.Insert(TestToken("t3", "vessel")).code(), absl::StatusCode::kInvalidArgument);
  EXPECT_EQ(tokens.Insert(TestToken("t4", "root")).code(), absl::StatusCode::kInvalidArgument);

  auto t2 = tokens.Get("t2");
  ASSERT_TRUE(t2.ok()) << t2.status();
  EXPECT_EQ(t2->role, "vessel");
  EXPECT_EQ(t2->vessel_id, "mass-1");
  EXPECT_EQ(t2->secret_hash, std::string(64, 'a'));
  EXPECT_EQ(t2->description, "for t2");
  EXPECT_EQ(t2->created_by, "creator");
  EXPECT_EQ(t2->created_at_ms, 1000);
  EXPECT_EQ(t2->expires_at_ms, 5000);
  EXPECT_EQ(t2->revoked_at_ms, 0);
  EXPECT_EQ(tokens.Get("nope").status().code(), absl::StatusCode::kNotFound);

  auto revoked = tokens.Revoke("t2", 7000);
  ASSERT_TRUE(revoked.ok()) << revoked.status();
  EXPECT_EQ(revoked->revoked_at_ms, 7000);
  // A second revocation keeps the first time.
  EXPECT_EQ(tokens.Revoke("t2", 9000)->revoked_at_ms, 7000);
  EXPECT_EQ(tokens.Revoke("nope", 1).status().code(), absl::StatusCode::kNotFound);

  // Another connection (another server process) sees the same.
  std::unique_ptr<Store> again = OpenAnother();
  ASSERT_NE(again, nullptr);
  auto all = again->tokens().List();
  ASSERT_TRUE(all.ok()) << all.status();
  ASSERT_EQ(all->size(), 2u);
  EXPECT_EQ((*all)[0].id, "t1");
  EXPECT_EQ((*all)[0].revoked_at_ms, 0);
  EXPECT_EQ((*all)[1].revoked_at_ms, 7000);
}

// The first admin token: stored only while no usable admin token is (a
// revoked or expired one does not count), and of several connections (server
// processes) asking at once on an empty database exactly one stores it.
TEST_P(StoreTest, FirstAdminIsStoredOnceEvenWhenProcessesAskAtOnce) {
  TokenRepository& tokens = store().tokens();
  TokenRecord expired = TestToken("old", "admin");  // expires at 5000
  ASSERT_TRUE(tokens.Insert(expired).ok());
  ASSERT_TRUE(tokens.Insert(TestToken("revoked", "admin")).ok());
  ASSERT_TRUE(tokens.Revoke("revoked", 2000).ok());
  ASSERT_TRUE(tokens.Insert(TestToken("viewer", "viewer")).ok());
  TokenRecord first = TestToken("first", "admin");
  first.expires_at_ms = 0;
  // At 4000 the expiring admin token is still usable; at 6000 it is not.
  EXPECT_FALSE(*tokens.InsertFirstAdmin(first, 4000));
  EXPECT_EQ(tokens.Get("first").status().code(), absl::StatusCode::kNotFound);
  EXPECT_TRUE(*tokens.InsertFirstAdmin(first, 6000));
  TokenRecord second = TestToken("second", "admin");
  EXPECT_FALSE(*tokens.InsertFirstAdmin(second, 6000));
  EXPECT_EQ(tokens.List()->size(), 4u);

  constexpr int kRounds = 5, kProcesses = 4;
  for (int round = 0; round < kRounds; ++round) {
    absl::StatusOr<std::unique_ptr<TestDatabase>> fresh = TestDatabase::Create(GetParam());
    ASSERT_TRUE(fresh.ok()) << fresh.status();
    std::vector<std::unique_ptr<Store>> stores;
    for (int p = 0; p < kProcesses; ++p) {
      auto opened = (*fresh)->Open();
      ASSERT_TRUE(opened.ok()) << opened.status();
      stores.push_back(std::move(*opened));
    }
    std::atomic<int> ready{0};
    std::vector<absl::StatusOr<bool>> stored(kProcesses, absl::UnknownError("not run"));
    std::vector<std::thread> threads;
    threads.reserve(kProcesses);
    for (int p = 0; p < kProcesses; ++p) {
      threads.emplace_back([&, p] {
        TokenRecord admin = TestToken("admin-" + std::to_string(p), "admin");
        admin.expires_at_ms = 0;
        ++ready;
        while (ready.load() < kProcesses) {
        }
        stored[p] = stores[p]->tokens().InsertFirstAdmin(admin, 6000);
      });
    }
    for (std::thread& t : threads) t.join();
    int created = 0;
    for (int p = 0; p < kProcesses; ++p) {
      ASSERT_TRUE(stored[p].ok()) << "round " << round << ": " << stored[p].status();
      created += *stored[p] ? 1 : 0;
    }
    EXPECT_EQ(created, 1) << "round " << round;
    EXPECT_EQ(stores[0]->tokens().List()->size(), 1u) << "round " << round;
    for (auto& s : stores) ASSERT_TRUE(s->Close().ok());
  }
}

TEST_P(StoreTest, AuditLogAppendsInOrderAndPages) {
  AuditRepository& audit = store().audit();
  for (int i = 1; i <= 5; ++i) {
    auto r = audit.Append(
        {0, 100 + i, "tok", "operator", "", "CreateMission", "m" + std::to_string(i), "detail"});
    ASSERT_TRUE(r.ok()) << r.status();
    EXPECT_GT(r->seq, 0);
  }
  EXPECT_FALSE(audit.Append({0, 1, "tok", "operator", "", "", "x", ""}).ok());  // no action
  auto first = audit.ListAudit(3, 0);
  ASSERT_TRUE(first.ok()) << first.status();
  ASSERT_EQ(first->items.size(), 3u);
  EXPECT_EQ(first->items[0].target, "m1");
  EXPECT_EQ(first->items[0].time_ms, 101);
  EXPECT_EQ(first->items[0].role, "operator");
  EXPECT_EQ(first->items[0].action, "CreateMission");
  EXPECT_NE(first->next_after, 0);
  auto rest = audit.ListAudit(3, first->next_after);
  ASSERT_TRUE(rest.ok());
  ASSERT_EQ(rest->items.size(), 2u);
  EXPECT_EQ(rest->items[1].target, "m5");
  EXPECT_EQ(rest->next_after, 0);
  EXPECT_EQ(audit.ListAudit(0, 0).status().code(), absl::StatusCode::kInvalidArgument);
}

// An audit row as a handler builds it; an empty `action` is refused by the
// schema's CHECK, which is how the tests below make the audit insert fail.
AuditRecord TestAudit(const std::string& action, const std::string& target) {
  return {0, 42, "tok", "operator", "", action, target, ""};
}

std::vector<std::string> AuditTargets(Store& store) {
  std::vector<std::string> out;
  auto page = store.audit().ListAudit(1000, 0);
  EXPECT_TRUE(page.ok()) << page.status();
  if (page.ok()) {
    for (const AuditRecord& r : page->items) out.push_back(r.action + " " + r.target);
  }
  return out;
}

// Every audited write with a good row stores the change and the row.
TEST_P(StoreTest, AuditedWritesStoreTheirRowWithTheChange) {
  const AuditRecord chart = TestAudit("ChartService/UploadChart", "c1");
  ASSERT_TRUE(store().charts().Insert(ChartRecord{.id = "c1"}, &chart).ok());
  const AuditRecord mission = TestAudit("MissionService/CreateMission", "m1");
  ASSERT_TRUE(missions().Create(TestMission("m1"), TestVersion("m1", 1), {}, &mission).ok());
  MissionUpdate cancel;
  cancel.state = 5;
  cancel.audit = TestAudit("MissionService/CancelMission", "m1");
  ASSERT_TRUE(missions().Update("m1", cancel, {TestEvent("cancelled")}).ok());
  const AuditRecord token = TestAudit("AccessService/CreateToken", "t1");
  ASSERT_TRUE(store().tokens().Insert(TestToken("t1", "viewer"), &token).ok());
  const AuditRecord revoke = TestAudit("AccessService/RevokeToken", "t1");
  ASSERT_TRUE(store().tokens().Revoke("t1", 7000, &revoke).ok());
  EXPECT_EQ(
      AuditTargets(store()),
      (std::vector<std::string>{"ChartService/UploadChart c1", "MissionService/CreateMission m1",
                                "MissionService/CancelMission m1", "AccessService/CreateToken t1",
                                "AccessService/RevokeToken t1"}));
}

// The audit row cannot be written: the change it records is rolled back
// with it, on every write that takes one.
TEST_P(StoreTest, AFailingAuditRowRollsTheAuditedChangeBack) {
  const AuditRecord bad = TestAudit("", "x");
  EXPECT_FALSE(store().charts().Insert(ChartRecord{.id = "c1"}, &bad).ok());
  EXPECT_EQ(store().charts().Get("c1", false).status().code(), absl::StatusCode::kNotFound);

  EXPECT_FALSE(missions().Create(TestMission("m1"), TestVersion("m1", 1), {}, &bad).ok());
  EXPECT_EQ(missions().Get("m1").status().code(), absl::StatusCode::kNotFound);
  EXPECT_EQ(missions().GetVersion("m1", 1).status().code(), absl::StatusCode::kNotFound);

  ASSERT_TRUE(missions().Create(TestMission("m2"), TestVersion("m2", 1), {}).ok());
  const int state_before = missions().Get("m2")->state;
  MissionUpdate cancel;
  cancel.state = state_before + 1;
  cancel.audit = bad;
  EXPECT_FALSE(missions().Update("m2", cancel, {TestEvent("cancelled")}).ok());
  EXPECT_EQ(missions().Get("m2")->state, state_before);
  EXPECT_TRUE(missions().ListEvents("m2", 0, 10)->empty());

  EXPECT_FALSE(store().tokens().Insert(TestToken("t1", "viewer"), &bad).ok());
  EXPECT_EQ(store().tokens().Get("t1").status().code(), absl::StatusCode::kNotFound);

  ASSERT_TRUE(store().tokens().Insert(TestToken("t2", "viewer")).ok());
  EXPECT_FALSE(store().tokens().Revoke("t2", 7000, &bad).ok());
  EXPECT_EQ(store().tokens().Get("t2")->revoked_at_ms, 0);

  EXPECT_TRUE(AuditTargets(store()).empty());
}

// The change fails: its audit row is not stored either.
TEST_P(StoreTest, AFailedAuditedChangeLeavesNoAuditRow) {
  ASSERT_TRUE(store().charts().Insert(ChartRecord{.id = "c1"}).ok());
  const AuditRecord chart = TestAudit("ChartService/UploadChart", "c1");
  EXPECT_EQ(store().charts().Insert(ChartRecord{.id = "c1"}, &chart).status().code(),
            absl::StatusCode::kAlreadyExists);
  const AuditRecord cancel_row = TestAudit("MissionService/CancelMission", "nope");
  MissionUpdate cancel;
  cancel.state = 5;
  cancel.audit = cancel_row;
  EXPECT_EQ(missions().Update("nope", cancel, {}).code(), absl::StatusCode::kNotFound);
  const AuditRecord revoke = TestAudit("AccessService/RevokeToken", "nope");
  EXPECT_EQ(store().tokens().Revoke("nope", 1, &revoke).status().code(),
            absl::StatusCode::kNotFound);
  EXPECT_TRUE(AuditTargets(store()).empty());
}

// Missions in states 1..3 count; a spec "uses:<chart id>" refers to that chart.
ChartUse TestChartUse() {
  return {{1, 2, 3}, [](const std::string& spec, const std::string& chart_id) {
            return spec == "uses:" + chart_id;
          }};
}

MissionRecord MissionUsing(const std::string& id, const std::string& chart_id, int state) {
  MissionRecord m = TestMission(id);
  m.spec = "uses:" + chart_id;
  m.state = state;
  return m;
}

TEST_P(StoreTest, DeletingAChartRemovesItWithItsAuditRow) {
  ASSERT_TRUE(store().charts().Insert(ChartRecord{.id = "c1", .obstacles = "big"}).ok());
  ASSERT_TRUE(store().charts().Insert(ChartRecord{.id = "c2"}).ok());
  // Finished missions (state 4) and active missions of other charts do not hold it.
  ASSERT_TRUE(missions().Create(MissionUsing("done", "c1", 4), TestVersion("done", 1), {}).ok());
  ASSERT_TRUE(missions().Create(MissionUsing("other", "c2", 2), TestVersion("other", 1), {}).ok());
  const AuditRecord row = TestAudit("ChartService/DeleteChart", "c1");
  const absl::Status deleted = store().charts().Delete("c1", TestChartUse(), &row);
  ASSERT_TRUE(deleted.ok()) << deleted;
  EXPECT_EQ(store().charts().Get("c1", true).status().code(), absl::StatusCode::kNotFound);
  auto listed = store().charts().List(10, 0);
  ASSERT_TRUE(listed.ok());
  ASSERT_EQ(listed->items.size(), 1u);
  EXPECT_EQ(listed->items[0].id, "c2");
  EXPECT_EQ(AuditTargets(store()), std::vector<std::string>{"ChartService/DeleteChart c1"});
  // A second delete (and an unknown id) is NotFound and audits nothing.
  EXPECT_EQ(store().charts().Delete("c1", TestChartUse(), &row).code(),
            absl::StatusCode::kNotFound);
  EXPECT_EQ(AuditTargets(store()).size(), 1u);
  // The id may be used again.
  EXPECT_TRUE(store().charts().Insert(ChartRecord{.id = "c1"}).ok());
}

TEST_P(StoreTest, AChartActiveMissionsUseIsNotDeleted) {
  ASSERT_TRUE(store().charts().Insert(ChartRecord{.id = "c1"}).ok());
  ASSERT_TRUE(missions().Create(MissionUsing("m-a", "c1", 2), TestVersion("m-a", 1), {}).ok());
  ASSERT_TRUE(missions().Create(MissionUsing("m-b", "c1", 3), TestVersion("m-b", 1), {}).ok());
  const AuditRecord row = TestAudit("ChartService/DeleteChart", "c1");
  const absl::Status refused = store().charts().Delete("c1", TestChartUse(), &row);
  EXPECT_EQ(refused.code(), absl::StatusCode::kFailedPrecondition);
  EXPECT_NE(refused.message().find("m-a, m-b"), std::string::npos) << refused;
  EXPECT_TRUE(store().charts().Get("c1", false).ok());
  EXPECT_TRUE(AuditTargets(store()).empty());
  // Once both have ended the chart goes.
  MissionUpdate end;
  end.state = 4;
  ASSERT_TRUE(missions().Update("m-a", end, {}).ok());
  EXPECT_EQ(store().charts().Delete("c1", TestChartUse(), &row).code(),
            absl::StatusCode::kFailedPrecondition);
  ASSERT_TRUE(missions().Update("m-b", end, {}).ok());
  EXPECT_TRUE(store().charts().Delete("c1", TestChartUse(), &row).ok());
  EXPECT_EQ(store().charts().Get("c1", false).status().code(), absl::StatusCode::kNotFound);
}

TEST_P(StoreTest, AFailingAuditRowKeepsTheChart) {
  ASSERT_TRUE(store().charts().Insert(ChartRecord{.id = "c1"}).ok());
  const AuditRecord bad = TestAudit("", "c1");
  EXPECT_FALSE(store().charts().Delete("c1", TestChartUse(), &bad).ok());
  EXPECT_TRUE(store().charts().Get("c1", false).ok());
  EXPECT_TRUE(AuditTargets(store()).empty());
}

// A mission created on a chart that is gone is refused whole: no mission,
// version, log event or audit row.
TEST_P(StoreTest, AMissionOnADeletedChartIsNotCreated) {
  ASSERT_TRUE(store().charts().Insert(ChartRecord{.id = "c1"}).ok());
  const AuditRecord row = TestAudit("MissionService/CreateMission", "m-1");
  ASSERT_TRUE(
      missions()
          .Create(MissionUsing("m-1", "c1", 2), TestVersion("m-1", 1), {TestEvent("a")}, &row, "c1")
          .ok());
  ASSERT_TRUE(missions().Update("m-1", MissionUpdate{.state = 4}, {}).ok());
  ASSERT_TRUE(store().charts().Delete("c1", TestChartUse()).ok());
  const absl::Status refused = missions().Create(
      MissionUsing("m-2", "c1", 2), TestVersion("m-2", 1), {TestEvent("b")}, &row, "c1");
  EXPECT_EQ(refused.code(), absl::StatusCode::kNotFound) << refused;
  EXPECT_NE(refused.message().find("c1"), std::string::npos) << refused;
  EXPECT_EQ(missions().Get("m-2").status().code(), absl::StatusCode::kNotFound);
  EXPECT_EQ(missions().GetVersion("m-2", 1).status().code(), absl::StatusCode::kNotFound);
  EXPECT_TRUE(missions().ListEvents("m-2", 0, 10)->empty());
  EXPECT_EQ(AuditTargets(store()).size(), 1u);  // m-1's only
}

// A mission created on a chart while another connection (another server
// process) deletes that chart: exactly one of the two commits, never both,
// so no active mission is left on a deleted chart. Many rounds, so that the
// two transactions overlap in every order.
TEST_P(StoreTest, CreatingOnAChartAndDeletingItNeverBothSucceed) {
  std::unique_ptr<Store> other = OpenAnother();
  ASSERT_NE(other, nullptr);
  constexpr int kRounds = 40;
  int created = 0, deleted = 0;
  for (int round = 0; round < kRounds; ++round) {
    const std::string chart = "c" + std::to_string(round);
    const std::string mission = "m" + std::to_string(round);
    ASSERT_TRUE(store().charts().Insert(ChartRecord{.id = chart}).ok());
    std::atomic<int> ready{0};
    absl::Status create_status, delete_status;
    std::thread creator([&] {
      ++ready;
      while (ready.load() < 2) {
      }
      create_status = other->missions().Create(MissionUsing(mission, chart, 2),
                                               TestVersion(mission, 1), {}, nullptr, chart);
    });
    std::thread deleter([&] {
      ++ready;
      while (ready.load() < 2) {
      }
      delete_status = store().charts().Delete(chart, TestChartUse());
    });
    creator.join();
    deleter.join();
    ASSERT_NE(create_status.ok(), delete_status.ok())
        << "round " << round << ": create " << create_status << ", delete " << delete_status;
    if (create_status.ok()) {
      ++created;
      EXPECT_EQ(delete_status.code(), absl::StatusCode::kFailedPrecondition) << delete_status;
      EXPECT_TRUE(store().charts().Get(chart, false).ok());
    } else {
      ++deleted;
      EXPECT_EQ(create_status.code(), absl::StatusCode::kNotFound) << create_status;
      EXPECT_EQ(missions().Get(mission).status().code(), absl::StatusCode::kNotFound);
    }
  }
  std::cout << "creations first: " << created << ", deletions first: " << deleted << "\n";
  ASSERT_TRUE(other->Close().ok());
}

}  // namespace
}  // namespace seaplan::storage
