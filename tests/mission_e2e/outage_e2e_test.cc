// The shore going away during a running mission: seaplan-server (real
// binary, loopback) SIGKILLed and restarted on the same port and data
// folder while seaplan-sim (real binary) executes the mission. Checked
// through the server's database (read-only SQL), its API and the sim's
// feedback journal and report.
//
// SEAPLAN_KILL_TRIALS (default 3) sets the number of random-moment kills of
// ServerKilledAtRandomMomentsLosesNothing; scripts/kill9_trials.sh runs 20.
// SEAPLAN_KILL_SEED fixes their random moments (default: from the clock,
// printed).
#include <grpcpp/grpcpp.h>
#include <gtest/gtest.h>
#include <sqlite3.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <map>
#include <random>
#include <regex>
#include <set>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "absl/strings/str_cat.h"
#include "e2e_support.h"
#include "seaplan/testing/shared_data.h"
#include "seaplan/v1/mission.grpc.pb.h"

namespace seaplan {
namespace {

namespace fs = std::filesystem;
using seaplan::testing::BinDir;
using seaplan::testing::SourceDir;

using e2e::JournalView;
using e2e::ReadJournal;

// A connection to the server's SQLite file (read-write, as the server
// itself opens it: a crashed server's WAL is then recovered the same way).
class Db {
 public:
  explicit Db(const fs::path& path) {
    if (sqlite3_open_v2(path.c_str(), &db_, SQLITE_OPEN_READWRITE, nullptr) != SQLITE_OK) {
      ADD_FAILURE() << "cannot open " << path << ": " << sqlite3_errmsg(db_);
    }
    sqlite3_busy_timeout(db_, 5000);
  }
  ~Db() { sqlite3_close(db_); }
  Db(const Db&) = delete;
  Db& operator=(const Db&) = delete;

  // Rows of `sql` (with `?1` bound to `arg`), each column as text.
  std::vector<std::vector<std::string>> Rows(const std::string& sql, const std::string& arg = "") {
    std::vector<std::vector<std::string>> rows;
    sqlite3_stmt* s = nullptr;
    if (sqlite3_prepare_v2(db_, sql.c_str(), -1, &s, nullptr) != SQLITE_OK) {
      ADD_FAILURE() << sql << ": " << sqlite3_errmsg(db_);
      return rows;
    }
    if (sqlite3_bind_parameter_count(s) > 0)
      sqlite3_bind_text(s, 1, arg.c_str(), -1, SQLITE_TRANSIENT);
    int rc;
    while ((rc = sqlite3_step(s)) == SQLITE_ROW) {
      auto& row = rows.emplace_back();
      for (int c = 0; c < sqlite3_column_count(s); ++c) {
        const unsigned char* t = sqlite3_column_text(s, c);
        row.push_back(t ? reinterpret_cast<const char*>(t) : "");
      }
    }
    if (rc != SQLITE_DONE) ADD_FAILURE() << sql << ": " << sqlite3_errmsg(db_);
    sqlite3_finalize(s);
    return rows;
  }
  // sequence number -> stored rows, for one mission.
  std::map<int64_t, int> FeedbackCounts(const std::string& mission_id) {
    std::map<int64_t, int> out;
    for (const auto& r :
         Rows("SELECT sequence_number, COUNT(*) FROM feedback WHERE mission_id = ?1 "
              "GROUP BY sequence_number",
              mission_id)) {
      out[std::stoll(r[0])] = std::stoi(r[1]);
    }
    return out;
  }
  std::vector<int> Versions(const std::string& mission_id) {
    std::vector<int> out;
    for (const auto& r :
         Rows("SELECT version FROM plan_versions WHERE mission_id = ?1 ORDER BY version",
              mission_id))
      out.push_back(std::stoi(r[0]));
    return out;
  }
  std::string IntegrityCheck() {
    std::string out;
    for (const auto& r : Rows("PRAGMA integrity_check")) out += r[0];
    return out;
  }

 private:
  sqlite3* db_ = nullptr;
};

// Every event of a mission from the start (version 0, event 0) until the
// stream ends (terminal state) or 10 s pass.
std::vector<v1::MissionEvent> WatchAll(v1::MissionService::Stub* stub, const std::string& id) {
  v1::WatchMissionRequest req;
  req.set_mission_id(id);
  grpc::ClientContext ctx;
  ctx.set_deadline(std::chrono::system_clock::now() + std::chrono::seconds(10));
  auto reader = stub->WatchMission(&ctx, req);
  std::vector<v1::MissionEvent> out;
  v1::MissionEvent ev;
  while (reader->Read(&ev)) out.push_back(ev);
  reader->Finish();
  return out;
}

class OutageE2eTest : public ::testing::Test {
 protected:
  void SetUp() override {
    if (!fs::exists(BinDir() / "seaplan-server") || !fs::exists(BinDir() / "seaplan-sim")) {
      GTEST_SKIP() << "seaplan-server or seaplan-sim not built in " << BinDir();
    }
    dir_ = fs::temp_directory_path() /
           ("seaplan-outage-e2e-" + std::to_string(getpid()) + "-" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    ASSERT_TRUE(StartServer(0)) << "seaplan-server did not start";
  }
  void TearDown() override {
    server_.Stop();
    std::error_code ec;
    if (!HasFailure()) fs::remove_all(dir_, ec);
  }

  bool StartServer(int port) {
    if (!server_.Start(BinDir() / "seaplan-server", dir_ / "server", port)) return false;
    stub_ = v1::MissionService::NewStub(
        grpc::CreateChannel(server_.address(), grpc::InsecureChannelCredentials()));
    return true;
  }
  fs::path DbPath() const { return dir_ / "server" / "data" / "seaplan.db"; }

  // seaplan-sim on `scenario` in the background; its report and journal in `run_dir`.
  // `time_factor` 0: as fast as possible.
  pid_t StartSim(const std::string& scenario, const fs::path& run_dir, int time_factor = 0) {
    fs::create_directories(run_dir);
    return e2e::StartProcess(
        {(BinDir() / "seaplan-sim").string(), "--server", server_.address(), "--scenario",
         (SourceDir() / "examples/scenarios" / (scenario + ".scenario")).string(), "--report-dir",
         (run_dir / "report").string(), "--replan-timeout-s", "120", "--shore-wait-s", "120",
         "--log-level", "info", "--time-factor", std::to_string(time_factor)},
        {}, run_dir / "sim.out");
  }
  // The mission id the sim prints first ("mission <id>"), waiting up to 120 s.
  static std::string MissionId(const fs::path& run_dir) {
    const std::regex re("(^|\n)mission ([^ \n:]+)\n");
    for (int i = 0; i < 2400; ++i) {
      const std::string out = e2e::ReadWholeFile(run_dir / "sim.out");
      std::smatch m;
      if (std::regex_search(out, m, re)) return m[2];
      std::this_thread::sleep_for(std::chrono::milliseconds(50));
    }
    return "";
  }

  // The checks after a mission that lived through a server kill.
  struct Outcome {
    int versions = 0;
    size_t reports = 0;
  };
  Outcome CheckMission(const std::string& mission_id, const fs::path& run_dir,
                       const e2e::ProcessResult& sim) {
    Outcome o;
    EXPECT_EQ(sim.exit_code, 0) << sim.output;
    // The mission completed, and a watch from the start replays it: each
    // version once, in order, ending on the final state.
    v1::Mission m;
    {
      v1::GetMissionRequest get;
      get.set_mission_id(mission_id);
      grpc::ClientContext ctx;
      grpc::Status st = stub_->GetMission(&ctx, get, &m);
      EXPECT_TRUE(st.ok()) << st.error_message();
    }
    EXPECT_EQ(m.state(), v1::MISSION_STATE_COMPLETED) << m.failure_reason();
    std::vector<int> watched;
    v1::MissionState last_state = v1::MISSION_STATE_UNSPECIFIED;
    for (const v1::MissionEvent& e : WatchAll(stub_.get(), mission_id)) {
      if (e.has_plan_version()) watched.push_back(e.plan_version().version());
      if (e.has_mission()) last_state = e.mission().state();
    }
    EXPECT_EQ(last_state, v1::MISSION_STATE_COMPLETED);
    Db db(DbPath());
    const std::vector<int> stored = db.Versions(mission_id);
    EXPECT_EQ(watched, stored);
    for (size_t i = 0; i < stored.size(); ++i)
      EXPECT_EQ(stored[i], static_cast<int>(i) + 1) << "plan versions 1..N without gap";
    EXPECT_EQ(static_cast<int>(stored.size()), m.current_version());
    // The sim received every version at most once.
    const std::vector<double> received =
        e2e::Numbers(e2e::ReadWholeFile(run_dir / "report" / "report.json"), "version");
    EXPECT_EQ(std::set<double>(received.begin(), received.end()).size(), received.size());
    // Every report the sim made is stored exactly once, and nothing else.
    const JournalView j = ReadJournal(run_dir / "report" / "feedback.journal");
    const std::map<int64_t, int> counts = db.FeedbackCounts(mission_id);
    EXPECT_EQ(std::set<int64_t>(j.reported.begin(), j.reported.end()).size(), j.reported.size())
        << "a sequence number journaled twice";
    for (int64_t seq : j.reported) {
      const auto it = counts.find(seq);
      EXPECT_TRUE(it != counts.end() && it->second == 1)
          << "report " << seq << (j.acknowledged.count(seq) ? " (acknowledged)" : "") << " stored "
          << (it == counts.end() ? 0 : it->second) << " times";
      EXPECT_EQ(j.acknowledged.count(seq), 1u) << "report " << seq << " never acknowledged";
    }
    EXPECT_EQ(counts.size(), j.reported.size()) << "reports stored that the sim never made";
    o.versions = static_cast<int>(stored.size());
    o.reports = j.reported.size();
    return o;
  }

  fs::path dir_;
  e2e::ServerProcess server_;
  std::unique_ptr<v1::MissionService::Stub> stub_;
};

// Case C with the server down for a stretch once the ship is under way:
// the ship executes on, keeps its reports, and the mission completes with
// every report stored once.
TEST_F(OutageE2eTest, CaseCRidesOutAShoreOutageAndEveryReportIsStoredOnce) {
  const fs::path run = dir_ / "case-c";
  const pid_t sim = StartSim("case-c", run);
  const std::string id = MissionId(run);
  ASSERT_FALSE(id.empty()) << e2e::ReadWholeFile(run / "sim.out");
  // Under way: a few reports stored.
  bool under_way = false;
  for (int i = 0; i < 2400 && !under_way; ++i) {
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
    Db db(DbPath());
    under_way = db.FeedbackCounts(id).size() >= 3;
  }
  ASSERT_TRUE(under_way) << e2e::ReadWholeFile(run / "sim.out");
  const int port = server_.port();
  server_.Kill();
  std::this_thread::sleep_for(std::chrono::seconds(2));
  ASSERT_TRUE(StartServer(port)) << "the server did not restart on port " << port;
  const e2e::ProcessResult r = e2e::WaitProcess(sim, run / "sim.out", std::chrono::seconds(400));
  ASSERT_FALSE(r.timed_out) << r.output;
  const Outcome o = CheckMission(id, run, r);
  EXPECT_GE(o.versions, 2) << "case C replans for fuel";
  // The outage was noticed and ridden out (log lines and the navigation log).
  EXPECT_NE(r.output.find("shore link lost"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("shore link back"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("shore unreachable: executing plan version"), std::string::npos)
      << r.output;
  Db db(DbPath());
  EXPECT_EQ(db.IntegrityCheck(), "ok");
}

// A version the ship was never told about: while the shore is unreachable
// to the ship (the server killed, then restarted where the ship cannot
// reach it), an operator replans, and the ship runs its plan out on board.
// Back on its port, the server gets every report, none of which triggers a
// replan (they are about the older version); the ship then follows the newer
// version to the end (it used to stop there, leaving the mission ACTIVE; a
// server killed between storing a report that triggers a replan and
// answering it does the same).
TEST_F(OutageE2eTest, AVersionMadeWhileTheShipWasUnreachableIsFollowedAfterThePlanRanOut) {
  constexpr int kTimeFactor = 400;  // case C: about 7.5 s of wall time
  const fs::path run = dir_ / "case-c";
  const pid_t sim = StartSim("case-c", run, kTimeFactor);
  const std::string id = MissionId(run);
  ASSERT_FALSE(id.empty()) << e2e::ReadWholeFile(run / "sim.out");
  // Under way on its second version, not replanning.
  bool under_way = false;
  for (int i = 0; i < 2400 && !under_way; ++i) {
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
    Db db(DbPath());
    const auto row = db.Rows("SELECT state, current_version FROM missions WHERE id = ?1", id);
    under_way = !row.empty() && std::stoi(row[0][0]) == v1::MISSION_STATE_ACTIVE &&
                std::stoi(row[0][1]) >= 2 && db.FeedbackCounts(id).size() >= 10;
  }
  ASSERT_TRUE(under_way) << e2e::ReadWholeFile(run / "sim.out");
  const int port = server_.port();
  server_.Kill();
  const auto killed_at = std::chrono::steady_clock::now();
  // On another port: the operator's replan.
  ASSERT_TRUE(StartServer(0));
  int operators_version = 0;
  {
    v1::RequestReplanRequest req;
    req.set_mission_id(id);
    req.set_reason("operator, shore only");
    grpc::ClientContext ctx;
    ctx.set_deadline(std::chrono::system_clock::now() + std::chrono::seconds(120));
    v1::RequestReplanResponse resp;
    const grpc::Status st = stub_->RequestReplan(&ctx, req, &resp);
    ASSERT_TRUE(st.ok()) << st.error_message();
    operators_version = resp.version().version();
  }
  server_.Stop();
  // Long enough for the ship to run any version of case C out on board.
  std::this_thread::sleep_until(killed_at + std::chrono::seconds(15));
  ASSERT_TRUE(StartServer(port)) << "the server did not restart on port " << port;
  const e2e::ProcessResult r = e2e::WaitProcess(sim, run / "sim.out", std::chrono::seconds(400));
  ASSERT_FALSE(r.timed_out) << r.output;
  const Outcome o = CheckMission(id, run, r);
  EXPECT_GE(o.versions, operators_version);
  // The ship executed on while unreachable, then received the operator's version.
  const std::string followed = absl::StrCat("plan version ", operators_version, " received");
  const std::size_t unreachable = r.output.find("shore unreachable: executing plan version");
  EXPECT_NE(unreachable, std::string::npos) << r.output;
  EXPECT_NE(r.output.find(followed), std::string::npos) << r.output;
  EXPECT_LT(unreachable, r.output.find(followed)) << r.output;
}

// Kill -9 at random moments of running missions (one kill per mission),
// restart after a random pause on the same port and data folder: no
// acknowledged report lost, no duplicate plan version, the watch resumes,
// the database stays sound.
TEST_F(OutageE2eTest, ServerKilledAtRandomMomentsLosesNothing) {
  int trials = 3;
  if (const char* t = std::getenv("SEAPLAN_KILL_TRIALS")) trials = std::max(1, std::atoi(t));
  uint64_t seed =
      static_cast<uint64_t>(std::chrono::system_clock::now().time_since_epoch().count());
  if (const char* s = std::getenv("SEAPLAN_KILL_SEED")) seed = std::strtoull(s, nullptr, 10);
  std::printf("kill -9 trials: %d, seed %llu\n", trials, static_cast<unsigned long long>(seed));
  std::mt19937_64 rng(seed);
  // Case C at 400 times real time lasts about 7.5 s of wall time (about
  // 3000 s of mission time, up to four plan versions): kill within its first
  // 7 s, down for 0-2 s.
  constexpr int kTimeFactor = 400;
  std::uniform_int_distribution<int> kill_after_ms(0, 7000), down_ms(0, 2000);
  int completed = 0;
  for (int t = 0; t < trials; ++t) {
    SCOPED_TRACE("trial " + std::to_string(t));
    const fs::path run = dir_ / ("trial-" + std::to_string(t));
    const pid_t sim = StartSim("case-c", run, kTimeFactor);
    const std::string id = MissionId(run);
    ASSERT_FALSE(id.empty()) << e2e::ReadWholeFile(run / "sim.out");
    const int after = kill_after_ms(rng), down = down_ms(rng);
    std::this_thread::sleep_for(std::chrono::milliseconds(after));
    const int port = server_.port();
    server_.Kill();
    // The crashed state: sound, and what it held.
    std::string at_kill;
    {
      Db db(DbPath());
      EXPECT_EQ(db.IntegrityCheck(), "ok") << "after the kill";
      const auto row = db.Rows("SELECT state, current_version FROM missions WHERE id = ?1", id);
      if (!row.empty()) {
        at_kill = v1::MissionState_Name(static_cast<v1::MissionState>(std::stoi(row[0][0]))) +
                  " v" + row[0][1] + ", " + std::to_string(db.FeedbackCounts(id).size()) +
                  " reports stored";
      }
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(down));
    ASSERT_TRUE(StartServer(port)) << "the server did not restart on port " << port;
    const e2e::ProcessResult r = e2e::WaitProcess(sim, run / "sim.out", std::chrono::seconds(400));
    ASSERT_FALSE(r.timed_out) << r.output;
    const Outcome o = CheckMission(id, run, r);
    const bool ok = !::testing::Test::HasFailure();
    if (ok) ++completed;
    std::printf(
        "trial %d: killed %d ms into the mission (%s), down %d ms; sim exit %d, %d plan "
        "versions, %zu reports each stored once%s\n",
        t, after, at_kill.c_str(), down, r.exit_code, o.versions, o.reports,
        ok ? "" : " -- FAILED");
    std::fflush(stdout);
    if (!ok) break;
  }
  Db db(DbPath());
  EXPECT_EQ(db.IntegrityCheck(), "ok");
  std::printf("kill -9 trials: %d of %d passed every check\n", completed, trials);
}

}  // namespace
}  // namespace seaplan
