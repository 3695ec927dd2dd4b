// A bounded pool of threads for planning and route work, with a bounded
// wait queue in front of it.
//
// Why bounded: a planning request may run for minutes and use gigabytes;
// queueing them without bound would turn overload into unbounded latency
// and memory. When every worker is busy, Run() waits in a first-come
// first-served queue of at most `max_waiting` calls; beyond that it answers
// ResourceExhausted at once (with a retry-after hint) and the client may
// retry later (or elsewhere). A waiting call gives up when its StopToken
// stops (client gone, deadline, shutdown).
//
// Run() blocks the calling (RPC) thread until the work is done, calling
// `tick` every few milliseconds meanwhile (while waiting in the queue too):
// the transports use it to forward client cancellation to the work's
// StopToken and to write stream events from the RPC thread (so only that
// thread ever writes to the client).
//
// Thread-safety: all methods may be called from any thread.
#pragma once

#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <deque>
#include <functional>
#include <list>
#include <memory>
#include <mutex>
#include <thread>
#include <vector>

#include "seaplan/common/status.h"
#include "seaplan/common/stop_token.h"

namespace seaplan::server {

class WorkPool {
 public:
  // `threads` >= 1 workers; at most `max_waiting` >= 0 calls of Run() wait
  // for one (0: refuse at once when all are busy).
  explicit WorkPool(int threads, int max_waiting = 0);
  ~WorkPool();  // Shutdown()
  WorkPool(const WorkPool&) = delete;
  WorkPool& operator=(const WorkPool&) = delete;

  // Runs `work` on a worker and waits for it. When every worker is busy,
  // waits in the queue; ResourceExhausted (without running anything) when
  // the queue is full too; Cancelled / DeadlineExceeded when `stop` stops
  // while waiting; Unavailable after Shutdown(). `tick` (may be empty) runs
  // on the calling thread every `tick_interval` while waiting or working,
  // and once more after the work ends.
  absl::Status Run(std::function<void()> work, const StopToken& stop,
                   const std::function<void()>& tick = {},
                   std::chrono::milliseconds tick_interval = std::chrono::milliseconds(10));

  // Like Run, but never refused for a full queue: for work the server
  // starts itself (a replan a feedback report triggered), which has no
  // client to retry it but must still count against the pool's bound. It
  // takes its turn in the same queue.
  absl::Status RunWhenFree(std::function<void()> work, const StopToken& stop);

  // Refuses new work, lets running work finish, joins the workers.
  void Shutdown();

  int size() const { return static_cast<int>(threads_.size()); }
  int busy() const;
  int waiting() const;
  int max_waiting() const { return max_waiting_; }

 private:
  struct Job {
    std::function<void()> work;
    std::mutex mu;
    std::condition_variable cv;
    bool done = false;
  };
  void WorkerLoop();
  // Takes a worker for the caller (busy_ counts it), waiting in the queue
  // when `bounded` allows; the status says why not.
  absl::Status Acquire(const StopToken& stop, bool bounded, const std::function<void()>& tick,
                       std::chrono::milliseconds tick_interval);
  // Hands `job` to a worker (busy_ already counts it) and waits for it.
  void Execute(const std::shared_ptr<Job>& job, const std::function<void()>& tick,
               std::chrono::milliseconds tick_interval);

  const int max_waiting_;
  mutable std::mutex mu_;
  std::condition_variable cv_;
  std::condition_variable free_cv_;         // a worker became free
  std::deque<std::shared_ptr<Job>> queue_;  // never longer than the idle workers
  std::list<std::uint64_t> waiters_;        // tickets of waiting calls, first come first
  std::uint64_t next_ticket_ = 0;
  int bounded_waiters_ = 0;  // waiters_ that count against max_waiting_
  int busy_ = 0;             // submitted and not finished
  bool shutdown_ = false;
  std::vector<std::thread> threads_;
};

}  // namespace seaplan::server
