// Latency per acknowledged feedback report on SQLite and on PostgreSQL, in
// one run: the write ReportFeedback makes before it answers (the report, one
// log event and the mission update in one durable transaction). The two
// backends take turns in rounds so that load on the machine hits both alike.
//
//   build/bin/seaplan_storage_bench [--reports 2000] [--writers 1]
//                                   [--payload-bytes 512] [--database postgresql://...]
//
// Without --database a throwaway PostgreSQL cluster with fsync on is started
// (initdb + pg_ctl, see storage/testing/postgres_cluster.h). SQLite runs with
// synchronous=FULL in WAL mode, in the same file system. See README.md.
#include <CLI/CLI.hpp>
#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <thread>
#include <vector>

#include "absl/strings/str_cat.h"
#include "seaplan/bench/percentile.h"
#include "seaplan/storage/postgres_store.h"
#include "seaplan/storage/sqlite_store.h"
#include "seaplan/storage/testing/postgres_cluster.h"

namespace {

using namespace seaplan::storage;
using Clock = std::chrono::steady_clock;

struct Backend {
  std::string name;
  std::unique_ptr<Store> store;
  std::vector<double> latencies_ms;
  std::atomic<std::int64_t> next_sequence{0};
};

using seaplan::bench::Percentile;

// `count` reports from `writers` threads; appends each call's latency.
absl::Status RunRound(Backend& b, int count, int writers, const std::string& payload) {
  std::mutex mu;
  absl::Status failure;
  std::vector<std::thread> threads;
  threads.reserve(writers);
  for (int w = 0; w < writers; ++w) {
    threads.emplace_back([&, w] {
      const std::string mission = absl::StrCat("bench-", w);
      std::vector<double> mine;
      for (int i = w; i < count; i += writers) {
        const std::int64_t seq = b.next_sequence++;
        MissionUpdate update;
        update.last_state = payload;
        update.completed_tasks = std::vector<std::string>{"v1-t0", "v1-t1"};
        const auto start = Clock::now();
        auto stored = b.store->missions().RecordFeedback(
            {mission, mission, seq, 1, payload, 1000 + seq}, update,
            {{1000 + seq, static_cast<double>(seq), mission, "position report"}});
        const double ms = std::chrono::duration<double, std::milli>(Clock::now() - start).count();
        std::lock_guard lock(mu);
        if (!stored.ok() || !*stored) {
          failure =
              stored.ok() ? absl::InternalError("report stored as duplicate") : stored.status();
          return;
        }
        mine.push_back(ms);
      }
      std::lock_guard lock(mu);
      b.latencies_ms.insert(b.latencies_ms.end(), mine.begin(), mine.end());
    });
  }
  for (auto& t : threads) t.join();
  return failure;
}

absl::Status CreateMissions(Store& store, int writers) {
  for (int w = 0; w < writers; ++w) {
    MissionRecord m;
    m.id = absl::StrCat("bench-", w);
    m.name = m.id;
    m.vessel_id = m.id;
    m.spec = "spec";
    m.state = 2;
    SEAPLAN_RETURN_IF_ERROR(store.missions().Create(m, {m.id, 1, "initial", 1, "plan"}, {}));
  }
  return absl::OkStatus();
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"seaplan_storage_bench: latency per acknowledged feedback, SQLite vs PostgreSQL"};
  int reports = 2000, writers = 1, payload_bytes = 512;
  std::string database;
  app.add_option("--reports", reports, "reports per backend")->check(CLI::Range(10, 10000000));
  app.add_option("--writers", writers, "concurrent writers (one mission and vessel each)")
      ->check(CLI::Range(1, 64));
  app.add_option("--payload-bytes", payload_bytes, "size of the report and ship state blobs")
      ->check(CLI::Range(0, 1 << 20));
  app.add_option("--database", database, "an existing PostgreSQL database (its data is kept)");
  CLI11_PARSE(app, argc, argv);

  std::unique_ptr<testing::TemporaryPostgresCluster> cluster;
  if (database.empty()) {
    testing::PostgresClusterOptions options;
    options.fsync = true;  // durable commits, as in production
    auto started = testing::TemporaryPostgresCluster::Start(options);
    if (!started.ok()) {
      std::fprintf(stderr, "cannot start PostgreSQL: %s\n", started.status().ToString().c_str());
      return 1;
    }
    cluster = *std::move(started);
    auto url = cluster->CreateDatabase();
    if (!url.ok()) {
      std::fprintf(stderr, "%s\n", url.status().ToString().c_str());
      return 1;
    }
    database = *url;
  }
  const std::filesystem::path dir =
      std::filesystem::temp_directory_path() / absl::StrCat("seaplan-storage-bench-", getpid());
  std::filesystem::create_directories(dir);

  Backend sqlite{"SQLite (WAL, synchronous=FULL)"}, pg{"PostgreSQL (synchronous_commit=on)"};
  auto s = SqliteStore::Open((dir / "bench.db").string());
  auto p = PostgresStore::Open(database);
  if (!s.ok() || !p.ok()) {
    std::fprintf(stderr, "open: %s %s\n", s.status().ToString().c_str(),
                 p.status().ToString().c_str());
    return 1;
  }
  sqlite.store = *std::move(s);
  pg.store = *std::move(p);
  // A rerun on a kept --database: start after the sequence numbers stored.
  pg.next_sequence = std::chrono::duration_cast<std::chrono::microseconds>(
                         std::chrono::system_clock::now().time_since_epoch())
                         .count();
  for (Backend* b : {&sqlite, &pg}) {
    absl::Status st = CreateMissions(*b->store, writers);
    if (!st.ok() && !absl::IsAlreadyExists(st)) {
      std::fprintf(stderr, "%s: %s\n", b->name.c_str(), st.ToString().c_str());
      return 1;
    }
  }

  const std::string payload(static_cast<std::size_t>(payload_bytes), 'x');
  constexpr int kRound = 100;
  int done = 0;
  std::chrono::duration<double> wall[2] = {};
  while (done < reports) {
    const int n = std::min(kRound, reports - done);
    int i = 0;
    for (Backend* b : {&sqlite, &pg}) {
      const auto start = Clock::now();
      absl::Status st = RunRound(*b, n, writers, payload);
      wall[i++] += Clock::now() - start;
      if (!st.ok()) {
        std::fprintf(stderr, "%s: %s\n", b->name.c_str(), st.ToString().c_str());
        return 1;
      }
    }
    done += n;
  }

  std::printf("acknowledged feedback (report + log event + mission update, one transaction)\n");
  std::printf("reports per backend %d, writers %d, payload %d B\n\n", reports, writers,
              payload_bytes);
  std::printf("%-36s %9s %9s %9s %11s\n", "backend", "p50 ms", "p99 ms", "mean ms", "reports/s");
  double p50[2], p99[2];
  int i = 0;
  for (Backend* b : {&sqlite, &pg}) {
    double sum = 0;
    for (double v : b->latencies_ms) sum += v;
    p50[i] = Percentile(b->latencies_ms, 0.50);
    p99[i] = Percentile(b->latencies_ms, 0.99);
    std::printf("%-36s %9.3f %9.3f %9.3f %11.0f\n", b->name.c_str(), p50[i], p99[i],
                sum / b->latencies_ms.size(), b->latencies_ms.size() / wall[i].count());
    ++i;
  }
  std::printf("\nPostgreSQL / SQLite: p50 x%.2f, p99 x%.2f\n", p50[1] / p50[0], p99[1] / p99[0]);

  (void)sqlite.store->Close();
  (void)pg.store->Close();
  std::filesystem::remove_all(dir);
  return 0;
}
