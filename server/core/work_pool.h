// A bounded pool of threads for planning and route work.
//
// Why bounded with no queue: a planning request may run for minutes and use
// gigabytes; queueing them without bound would turn overload into unbounded
// latency and memory. When every worker is busy, Run() answers
// ResourceExhausted at once and the client may retry later (or elsewhere).
//
// Run() blocks the calling (RPC) thread until the work is done, calling
// `tick` every few milliseconds meanwhile: the transports use it to forward
// client cancellation to the work's StopToken and to write stream events
// from the RPC thread (so only that thread ever writes to the client).
//
// Thread-safety: all methods may be called from any thread.
#pragma once

#include <chrono>
#include <condition_variable>
#include <deque>
#include <functional>
#include <memory>
#include <mutex>
#include <thread>
#include <vector>

#include "seaplan/common/status.h"
#include "seaplan/common/stop_token.h"

namespace seaplan::server {

class WorkPool {
 public:
  // `threads` >= 1 workers.
  explicit WorkPool(int threads);
  ~WorkPool();  // Shutdown()
  WorkPool(const WorkPool&) = delete;
  WorkPool& operator=(const WorkPool&) = delete;

  // Runs `work` on a worker and waits for it. ResourceExhausted (without
  // running anything) when all workers are busy; Unavailable after
  // Shutdown(). `tick` (may be empty) runs on the calling thread every
  // `tick_interval` while waiting, and once more after the work ends.
  absl::Status Run(std::function<void()> work, const std::function<void()>& tick = {},
                   std::chrono::milliseconds tick_interval = std::chrono::milliseconds(10));

  // Like Run, but when every worker is busy waits for one to be free instead
  // of refusing: for work the server starts itself (a replan a feedback
  // report triggered), which has no client to retry it but must still count
  // against the pool's bound. Cancelled / DeadlineExceeded (without running
  // anything) when `stop` stops while waiting; Unavailable after Shutdown().
  absl::Status RunWhenFree(std::function<void()> work, const StopToken& stop);

  // Refuses new work, lets running work finish, joins the workers.
  void Shutdown();

  int size() const { return static_cast<int>(threads_.size()); }
  int busy() const;

 private:
  struct Job {
    std::function<void()> work;
    std::mutex mu;
    std::condition_variable cv;
    bool done = false;
  };
  void WorkerLoop();
  // Hands `job` to a worker (busy_ already counts it) and waits for it.
  void Execute(const std::shared_ptr<Job>& job, const std::function<void()>& tick,
               std::chrono::milliseconds tick_interval);

  mutable std::mutex mu_;
  std::condition_variable cv_;
  std::condition_variable free_cv_;         // a worker became free
  std::deque<std::shared_ptr<Job>> queue_;  // never longer than the idle workers
  int busy_ = 0;                            // submitted and not finished
  bool shutdown_ = false;
  std::vector<std::thread> threads_;
};

}  // namespace seaplan::server
