// The coordinator over a real SQLite store and work pool, with a small
// engine whose answers the tests choose.
#include "server/core/mission_coordinator.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <atomic>
#include <filesystem>
#include <thread>

#include "absl/strings/str_cat.h"
#include "seaplan/storage/sqlite_store.h"

namespace seaplan::server {
namespace {

namespace fs = std::filesystem;

// Version N: tasks vN-t0 (move) and vN-t1 (load). A failed task replans; the
// last task completed completes the mission.
class TwoTaskEngine final : public mission::MissionEngine {
 public:
  explicit TwoTaskEngine(const WorkPool& pool) : pool_(pool) {}
  std::atomic<int> busy_in_replan{-1};  // the pool's busy count seen by Replan
  std::atomic<int> replans{0};
  // When set, Replan waits until its StopToken stops (at most 20 s).
  std::atomic<bool> block_replans{false};
  // Replan takes this long (or until its StopToken stops).
  std::atomic<int> replan_ms{0};

  Status CheckSpec(const mission::MissionSpec&, std::vector<pddl::Diagnostic>*) override {
    return absl::OkStatus();
  }
  StatusOr<chart::LocalFrame> Frame(const mission::MissionSpec&) override {
    return chart::LocalFrame();
  }
  StatusOr<mission::PlannedVersion> PlanInitial(const mission::MissionSpec&,
                                                const StopToken&) override {
    return Version(1, mission::PlanQuality::kOptimal);
  }
  StatusOr<std::optional<mission::PlannedVersion>> Replan(const mission::MissionSpec&,
                                                          const mission::MissionRuntime& runtime,
                                                          std::string_view reason,
                                                          const StopToken& stop) override {
    busy_in_replan = pool_.busy();
    ++replans;
    if (block_replans) {
      for (int i = 0; i < 2000 && !stop.StopRequested(); ++i)
        std::this_thread::sleep_for(std::chrono::milliseconds(10));
      return absl::CancelledError("replan stopped");
    }
    for (int i = 0; i < replan_ms / 10 && !stop.StopRequested(); ++i)
      std::this_thread::sleep_for(std::chrono::milliseconds(10));
    mission::PlannedVersion v =
        Version(runtime.current.version + 1, mission::PlanQuality::kSatisficing);
    v.version.reason = std::string(reason);
    return std::optional<mission::PlannedVersion>(std::move(v));
  }
  mission::FeedbackOutcome OnFeedback(const mission::MissionSpec&,
                                      const mission::MissionRuntime& runtime,
                                      const mission::Feedback& f) override {
    mission::FeedbackOutcome out;
    out.completed_task_ids = runtime.completed_task_ids;
    if (f.kind == mission::FeedbackKind::kTaskFailed) out.replan_reason = "task failed";
    if (f.kind == mission::FeedbackKind::kTaskCompleted) {
      out.completed_task_ids.push_back(f.task_id);
      out.completed_changed = true;
      out.mission_completed = f.task_id == runtime.current.tasks.back().id;
    }
    return out;
  }

 private:
  static mission::PlannedVersion Version(int n, mission::PlanQuality quality) {
    mission::PlannedVersion v;
    v.version.version = n;
    v.version.quality = quality;
    for (int i = 0; i < 2; ++i) {
      mission::Task t;
      t.id = absl::StrCat("v", n, "-t", i);
      t.kind = i == 0 ? mission::TaskKind::kMove : mission::TaskKind::kLoad;
      v.version.tasks.push_back(t);
    }
    v.engine_state = absl::StrCat("v", n);
    return v;
  }
  const WorkPool& pool_;
};

class MissionCoordinatorTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           absl::StrCat("seaplan-coordinator-test-", ::getpid(), "-",
                        ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
    auto store = storage::SqliteStore::Open((dir_ / "seaplan.db").string());
    ASSERT_TRUE(store.ok()) << store.status();
    store_ = std::move(*store);
    engine_ = std::make_shared<TwoTaskEngine>(pool_);
    MissionCoordinator::Options options;
    options.watch_poll = std::chrono::milliseconds(10);
    coordinator_ =
        std::make_unique<MissionCoordinator>(store_->missions(), pool_, root_, engine_, options);
  }
  void TearDown() override {
    coordinator_->Shutdown();
    pool_.Shutdown();
    coordinator_.reset();
    (void)store_->Close();
    std::error_code ec;
    fs::remove_all(dir_, ec);
  }

  CallContext Call() const {
    return CallContext{"test", root_.Child(StopToken::Clock::time_point::max()), {}};
  }

  v1::Mission Create() {
    v1::CreateMissionRequest req;
    req.mutable_spec()->set_name("m");
    req.mutable_spec()->set_domain("(define (domain d))");
    req.mutable_spec()->set_problem("(define (problem p) (:domain d))");
    auto m = coordinator_->CreateMission(req, Call());
    EXPECT_TRUE(m.ok()) << m.status();
    return m.ok() ? *m : v1::Mission();
  }

  absl::StatusOr<v1::ReportFeedbackResponse> Report(const std::string& id, int seq,
                                                    v1::Feedback::Kind kind,
                                                    const std::string& task,
                                                    MissionCoordinator* through = nullptr) {
    v1::ReportFeedbackRequest req;
    req.set_mission_id(id);
    req.set_vessel_id("ship0");
    req.set_sequence_number(seq);
    req.mutable_feedback()->set_kind(kind);
    req.mutable_feedback()->set_task_id(task);
    return (through != nullptr ? through : coordinator_.get())->ReportFeedback(req, Call());
  }

  v1::Mission Get(const std::string& id) {
    v1::GetMissionRequest req;
    req.set_mission_id(id);
    auto m = coordinator_->GetMission(req, Call());
    EXPECT_TRUE(m.ok()) << m.status();
    return m.ok() ? *m : v1::Mission();
  }

  // A coordinator as one replica of several on this database: work leases
  // and the change feed of the store, a short lease.
  std::unique_ptr<MissionCoordinator> Replica(const std::string& holder,
                                              std::shared_ptr<TwoTaskEngine> engine, WorkPool& pool,
                                              StopToken root) {
    MissionCoordinator::Options options;
    options.watch_poll = std::chrono::milliseconds(10);
    options.lease_ttl = std::chrono::milliseconds(300);
    options.sweep_interval = std::chrono::milliseconds(150);
    return std::make_unique<MissionCoordinator>(
        store_->missions(), pool, std::move(root), std::move(engine), options,
        MissionCoordinator::Cluster{&store_->work(), &store_->changes(), holder});
  }
  // Waits (bounded, 20 s) until the mission has `version`.
  void AwaitVersion(const std::string& id, int version) {
    for (int i = 0; i < 4000 && store_->missions().Get(id)->current_version < version; ++i)
      std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }

  // Waits (bounded, 20 s) until `engine` has started a replan.
  static bool ReplanStarted(const TwoTaskEngine& engine) {
    for (int i = 0; i < 4000 && engine.replans.load() == 0; ++i)
      std::this_thread::sleep_for(std::chrono::milliseconds(5));
    return engine.replans.load() > 0;
  }

  fs::path dir_;
  StopToken root_;
  WorkPool pool_{1};
  // Two more replicas' pools and engines, for the tests that make them.
  WorkPool pool_a_{1}, pool_b_{1};
  std::shared_ptr<TwoTaskEngine> engine_a_ = std::make_shared<TwoTaskEngine>(pool_a_);
  std::shared_ptr<TwoTaskEngine> engine_b_ = std::make_shared<TwoTaskEngine>(pool_b_);
  std::unique_ptr<storage::SqliteStore> store_;
  std::shared_ptr<TwoTaskEngine> engine_;
  std::unique_ptr<MissionCoordinator> coordinator_;
};

TEST_F(MissionCoordinatorTest, StoresVersionOneWithThePlannersStatus) {
  const v1::Mission m = Create();
  EXPECT_EQ(m.state(), v1::MISSION_STATE_ACTIVE);
  EXPECT_EQ(m.current_version(), 1);
  auto v = store_->missions().GetVersion(m.mission_id(), 1);
  ASSERT_TRUE(v.ok()) << v.status();
  v1::PlanVersion version;
  ASSERT_TRUE(version.ParseFromString(v->content));
  EXPECT_EQ(version.planner_status(), v1::SOLVED_OPTIMALLY);
  EXPECT_EQ(version.reason(), "initial plan");
  EXPECT_EQ(v->engine_state, "v1");
}

TEST_F(MissionCoordinatorTest, TriggeredReplansRunOnTheWorkPool) {
  const v1::Mission m = Create();
  auto r = Report(m.mission_id(), 1, v1::Feedback::KIND_TASK_FAILED, "v1-t0");
  ASSERT_TRUE(r.ok()) << r.status();
  EXPECT_TRUE(r->replan_triggered());
  EXPECT_EQ(r->replan_reason(), "task failed");
  // Wait (bounded) for version 2 from the background replan.
  for (int i = 0; i < 2000 && Get(m.mission_id()).current_version() < 2; ++i)
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  const v1::Mission after = Get(m.mission_id());
  ASSERT_EQ(after.current_version(), 2);
  EXPECT_EQ(after.state(), v1::MISSION_STATE_ACTIVE);
  // The replan held the pool's only worker while it ran.
  EXPECT_EQ(engine_->busy_in_replan.load(), 1);
  auto v = store_->missions().GetVersion(m.mission_id(), 2);
  ASSERT_TRUE(v.ok());
  v1::PlanVersion version;
  ASSERT_TRUE(version.ParseFromString(v->content));
  EXPECT_EQ(version.planner_status(), v1::SOLVED_SATISFICING);
  EXPECT_EQ(version.reason(), "task failed");
}

TEST_F(MissionCoordinatorTest, LastTaskCompletesTheMissionAndLaterFeedbackIsRefused) {
  const v1::Mission m = Create();
  ASSERT_TRUE(Report(m.mission_id(), 1, v1::Feedback::KIND_TASK_COMPLETED, "v1-t0").ok());
  EXPECT_EQ(Get(m.mission_id()).state(), v1::MISSION_STATE_ACTIVE);
  ASSERT_TRUE(Report(m.mission_id(), 2, v1::Feedback::KIND_TASK_COMPLETED, "v1-t1").ok());
  const v1::Mission done = Get(m.mission_id());
  EXPECT_EQ(done.state(), v1::MISSION_STATE_COMPLETED);
  EXPECT_EQ(done.completed_tasks_size(), 2);
  auto late = Report(m.mission_id(), 3, v1::Feedback::KIND_TASK_FAILED, "v1-t1");
  EXPECT_TRUE(absl::IsFailedPrecondition(late.status())) << late.status();
  EXPECT_EQ(engine_->replans.load(), 0);
  // A retry of a stored report is a duplicate, whatever the state.
  auto retry = Report(m.mission_id(), 2, v1::Feedback::KIND_TASK_COMPLETED, "v1-t1");
  ASSERT_TRUE(retry.ok());
  EXPECT_TRUE(retry->duplicate());
}

TEST_F(MissionCoordinatorTest, CancelledIsFinal) {
  const v1::Mission m = Create();
  v1::CancelMissionRequest cancel;
  cancel.set_mission_id(m.mission_id());
  auto c = coordinator_->CancelMission(cancel, Call());
  ASSERT_TRUE(c.ok()) << c.status();
  EXPECT_EQ(c->state(), v1::MISSION_STATE_CANCELLED);
  EXPECT_TRUE(coordinator_->CancelMission(cancel, Call()).ok());  // idempotent
  v1::RequestReplanRequest replan;
  replan.set_mission_id(m.mission_id());
  EXPECT_TRUE(absl::IsFailedPrecondition(coordinator_->RequestReplan(replan, Call()).status()));
  EXPECT_TRUE(absl::IsFailedPrecondition(
      Report(m.mission_id(), 1, v1::Feedback::KIND_TASK_COMPLETED, "v1-t0").status()));
}

}  // namespace
}  // namespace seaplan::server

namespace seaplan::server {
namespace {

// Replicas: a replica shutting down hands its running replan back (the
// mission stays REPLANNING) and another replica's sweep finishes it.
TEST_F(MissionCoordinatorTest, ShutdownHandsTheRunningReplanToAnotherReplica) {
  WorkPool pool_a(1), pool_b(1);
  auto engine_a = std::make_shared<TwoTaskEngine>(pool_a);
  auto engine_b = std::make_shared<TwoTaskEngine>(pool_b);
  engine_a->block_replans = true;
  StopToken root_a;
  auto a = Replica("replica-a", engine_a, pool_a, root_a);
  const v1::Mission m = Create();
  auto r = Report(m.mission_id(), 1, v1::Feedback::KIND_TASK_FAILED, "v1-t0", a.get());
  ASSERT_TRUE(r.ok()) << r.status();
  ASSERT_TRUE(r->replan_triggered());
  for (int i = 0; i < 4000 && engine_a->replans.load() == 0; ++i)
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  ASSERT_EQ(engine_a->replans.load(), 1);
  EXPECT_EQ((*store_->work().Get(m.mission_id()))->holder, "replica-a");

  // B starts while A plans: the work is A's, B does not run it.
  auto b = Replica("replica-b", engine_b, pool_b, StopToken());
  std::this_thread::sleep_for(std::chrono::milliseconds(200));
  EXPECT_EQ(engine_b->replans.load(), 0);

  root_a.Cancel();  // SIGTERM: the server cancels its work, then shuts down
  a->Shutdown();
  EXPECT_EQ(Get(m.mission_id()).state(), v1::MISSION_STATE_REPLANNING);

  AwaitVersion(m.mission_id(), 2);
  const v1::Mission after = Get(m.mission_id());
  EXPECT_EQ(after.current_version(), 2);
  EXPECT_EQ(after.state(), v1::MISSION_STATE_ACTIVE);
  EXPECT_EQ(engine_b->replans.load(), 1);
  auto v2 = store_->missions().GetVersion(m.mission_id(), 2);
  ASSERT_TRUE(v2.ok()) << v2.status();
  EXPECT_EQ(v2->reason, "task failed");
  b->Shutdown();
  EXPECT_FALSE((*store_->work().Get(m.mission_id()))->pending());
}

// Replicas: the lease of a replica that died mid-replan expires, another
// takes the work over, and the dead holder's late write is refused.
TEST_F(MissionCoordinatorTest, DeadReplicasLeaseExpiresAndAnotherReplicaReplans) {
  const v1::Mission m = Create();
  // What a replica killed while replanning leaves behind.
  storage::MissionUpdate replanning;
  replanning.state = v1::MISSION_STATE_REPLANNING;
  replanning.request_work = storage::WorkRequest{"task failed", 1};
  ASSERT_TRUE(store_->missions().Update(m.mission_id(), replanning, {}).ok());
  auto dead = store_->work().Claim(m.mission_id(), "dead-replica", std::chrono::milliseconds(300));
  ASSERT_TRUE(dead.ok() && dead->has_value());

  WorkPool pool_b(1);
  auto engine_b = std::make_shared<TwoTaskEngine>(pool_b);
  auto b = Replica("replica-b", engine_b, pool_b, StopToken());
  AwaitVersion(m.mission_id(), 2);
  EXPECT_EQ(Get(m.mission_id()).current_version(), 2);
  EXPECT_EQ(Get(m.mission_id()).state(), v1::MISSION_STATE_ACTIVE);
  EXPECT_EQ(engine_b->replans.load(), 1);

  storage::MissionUpdate late;
  late.fence = storage::WorkFence{(*dead)->holder, (*dead)->token};
  storage::PlanVersionRecord v3{m.mission_id(), 3, "late", 0, "", ""};
  EXPECT_TRUE(absl::IsAborted(store_->missions().AppendVersion(v3, late, {})));
  EXPECT_EQ(Get(m.mission_id()).current_version(), 2);
  b->Shutdown();
}

absl::StatusOr<v1::RequestReplanResponse> OperatorReplan(MissionCoordinator& replica,
                                                         const std::string& id,
                                                         const std::string& reason,
                                                         const StopToken& root) {
  v1::RequestReplanRequest req;
  req.set_mission_id(id);
  req.set_reason(reason);
  return replica.RequestReplan(
      req, CallContext{"test", root.Child(StopToken::Clock::time_point::max()), {}});
}

// Replicas: operators asking two replicas for a replan at once get a
// version each, planned once, numbered without gap (the second waits for
// the first one's lease, then plans from its version).
TEST_F(MissionCoordinatorTest, OperatorReplansOnTwoReplicasGetAVersionEach) {
  engine_a_->replan_ms = 200;  // long enough for the two calls to overlap
  engine_b_->replan_ms = 200;
  StopToken root_a, root_b;
  auto a = Replica("replica-a", engine_a_, pool_a_, root_a);
  auto b = Replica("replica-b", engine_b_, pool_b_, root_b);
  const v1::Mission m = Create();
  for (int round = 0; round < 2; ++round) {
    absl::StatusOr<v1::RequestReplanResponse> on_a = absl::UnknownError("not run"),
                                              on_b = absl::UnknownError("not run");
    std::thread ta([&] { on_a = OperatorReplan(*a, m.mission_id(), "operator on a", root_a); });
    std::thread tb([&] { on_b = OperatorReplan(*b, m.mission_id(), "operator on b", root_b); });
    ta.join();
    tb.join();
    ASSERT_TRUE(on_a.ok()) << on_a.status();
    ASSERT_TRUE(on_b.ok()) << on_b.status();
    const int first = 2 + 2 * round;
    EXPECT_EQ(std::min(on_a->version().version(), on_b->version().version()), first);
    EXPECT_EQ(std::max(on_a->version().version(), on_b->version().version()), first + 1);
    EXPECT_EQ(on_a->version().reason(), "operator on a");
    EXPECT_EQ(store_->missions().GetVersion(m.mission_id(), on_b->version().version())->reason,
              "operator on b");
  }
  EXPECT_EQ(engine_a_->replans.load() + engine_b_->replans.load(), 4);  // none planned twice
  // One at a time: each version was planned from the one before it (two
  // replans at once would both start from the same version).
  for (int v = 2; v <= 5; ++v)
    EXPECT_EQ(store_->missions().GetVersion(m.mission_id(), v)->engine_state, absl::StrCat("v", v));
  const v1::Mission after = Get(m.mission_id());
  EXPECT_EQ(after.current_version(), 5);
  EXPECT_EQ(after.state(), v1::MISSION_STATE_ACTIVE);
  auto work = store_->work().Get(m.mission_id());
  ASSERT_TRUE(work.ok() && work->has_value());
  EXPECT_FALSE((*work)->pending());
  EXPECT_TRUE((*work)->holder.empty());
  a->Shutdown();
  b->Shutdown();
}

// Replicas: an operator's replan on a replica that shuts down is handed
// back (the caller hears so) and another replica plans that request.
TEST_F(MissionCoordinatorTest, OperatorReplanOfAStoppingReplicaIsHandedOver) {
  engine_a_->block_replans = true;
  StopToken root_a;
  auto a = Replica("replica-a", engine_a_, pool_a_, root_a);
  const v1::Mission m = Create();
  absl::StatusOr<v1::RequestReplanResponse> answer = absl::UnknownError("not run");
  std::thread caller([&] { answer = OperatorReplan(*a, m.mission_id(), "operator", root_a); });
  ASSERT_TRUE(ReplanStarted(*engine_a_));
  EXPECT_EQ((*store_->work().Get(m.mission_id()))->holder, "replica-a");
  EXPECT_EQ(Get(m.mission_id()).state(), v1::MISSION_STATE_REPLANNING);
  root_a.Cancel();  // SIGTERM
  caller.join();
  EXPECT_TRUE(absl::IsUnavailable(answer.status())) << answer.status();
  EXPECT_NE(answer.status().message().find("handed to another server"), std::string_view::npos)
      << answer.status();
  a->Shutdown();
  EXPECT_EQ(Get(m.mission_id()).state(), v1::MISSION_STATE_REPLANNING);

  auto b = Replica("replica-b", engine_b_, pool_b_, StopToken());
  AwaitVersion(m.mission_id(), 2);
  EXPECT_EQ(Get(m.mission_id()).current_version(), 2);
  EXPECT_EQ(Get(m.mission_id()).state(), v1::MISSION_STATE_ACTIVE);
  EXPECT_EQ(store_->missions().GetVersion(m.mission_id(), 2)->reason, "operator");
  b->Shutdown();
}

// Replicas: a call whose deadline passes while another replica's replan
// holds the lease ends DEADLINE_EXCEEDED and leaves no request behind.
TEST_F(MissionCoordinatorTest, OperatorReplanWaitingPastItsDeadlineRecordsNothing) {
  engine_a_->block_replans = true;
  StopToken root_a, root_b;
  auto a = Replica("replica-a", engine_a_, pool_a_, root_a);
  auto b = Replica("replica-b", engine_b_, pool_b_, root_b);
  const v1::Mission m = Create();
  ASSERT_TRUE(Report(m.mission_id(), 1, v1::Feedback::KIND_TASK_FAILED, "v1-t0", a.get()).ok());
  ASSERT_TRUE(ReplanStarted(*engine_a_));
  const std::int64_t requests = (*store_->work().Get(m.mission_id()))->requests;

  v1::RequestReplanRequest req;
  req.set_mission_id(m.mission_id());
  auto answer = b->RequestReplan(
      req, CallContext{
               "test", root_b.Child(StopToken::Clock::now() + std::chrono::milliseconds(300)), {}});
  EXPECT_TRUE(absl::IsDeadlineExceeded(answer.status())) << answer.status();
  EXPECT_NE(answer.status().message().find("waiting for the replan under way"),
            std::string_view::npos)
      << answer.status();
  EXPECT_EQ(engine_b_->replans.load(), 0);
  EXPECT_EQ((*store_->work().Get(m.mission_id()))->requests, requests);
  EXPECT_EQ((*store_->work().Get(m.mission_id()))->holder, "replica-a");
  root_a.Cancel();
  a->Shutdown();
  b->Shutdown();
}

TEST(MissionCoordinatorOptionsTest, LeaseAndSweepAreChecked) {
  MissionCoordinator::Options options;
  EXPECT_TRUE(options.Validate().ok()) << options.Validate();
  options.lease_ttl = std::chrono::milliseconds(99);
  options.sweep_interval = std::chrono::milliseconds(50);
  EXPECT_TRUE(absl::IsInvalidArgument(options.Validate()));
  EXPECT_NE(options.Validate().message().find("lease"), std::string_view::npos);
  options.lease_ttl = std::chrono::milliseconds(1000);
  options.sweep_interval = std::chrono::milliseconds(1000);  // must be shorter than the lease
  EXPECT_TRUE(absl::IsInvalidArgument(options.Validate()));
  EXPECT_NE(options.Validate().message().find("sweep"), std::string_view::npos);
  options.sweep_interval = std::chrono::milliseconds(5);
  EXPECT_TRUE(absl::IsInvalidArgument(options.Validate()));
  options.sweep_interval = std::chrono::milliseconds(999);
  EXPECT_TRUE(options.Validate().ok());
}

}  // namespace
}  // namespace seaplan::server
