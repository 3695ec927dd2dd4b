#include "server/core/work_pool.h"

#include <algorithm>

#include "absl/strings/str_cat.h"
#include "server/core/status_details.h"

namespace seaplan::server {

WorkPool::WorkPool(int threads, int max_waiting) : max_waiting_(std::max(0, max_waiting)) {
  if (threads < 1) threads = 1;
  threads_.reserve(static_cast<std::size_t>(threads));
  for (int i = 0; i < threads; ++i) threads_.emplace_back([this] { WorkerLoop(); });
}

WorkPool::~WorkPool() {
  Shutdown();
}

int WorkPool::busy() const {
  std::lock_guard lock(mu_);
  return busy_;
}

int WorkPool::waiting() const {
  std::lock_guard lock(mu_);
  return static_cast<int>(waiters_.size());
}

void WorkPool::Shutdown() {
  {
    std::lock_guard lock(mu_);
    if (shutdown_ && threads_.empty()) return;
    shutdown_ = true;
  }
  cv_.notify_all();
  free_cv_.notify_all();
  for (auto& t : threads_) {
    if (t.joinable()) t.join();
  }
  threads_.clear();
}

void WorkPool::WorkerLoop() {
  while (true) {
    std::shared_ptr<Job> job;
    {
      std::unique_lock lock(mu_);
      cv_.wait(lock, [&] { return shutdown_ || !queue_.empty(); });
      if (queue_.empty()) return;  // shut down and nothing left
      job = std::move(queue_.front());
      queue_.pop_front();
    }
    job->work();
    {
      std::lock_guard lock(mu_);
      --busy_;
    }
    free_cv_.notify_all();  // only the first waiter in line takes it
    {
      std::lock_guard lock(job->mu);
      job->done = true;
    }
    job->cv.notify_all();
  }
}

absl::Status WorkPool::Acquire(const StopToken& stop, bool bounded,
                               const std::function<void()>& tick,
                               std::chrono::milliseconds tick_interval) {
  std::unique_lock lock(mu_);
  if (shutdown_) return absl::UnavailableError("server is shutting down");
  const int workers = static_cast<int>(threads_.size());
  if (busy_ < workers && waiters_.empty()) {
    ++busy_;
    return absl::OkStatus();
  }
  if (bounded && bounded_waiters_ >= max_waiting_) {
    // A guess at when a place frees up: planning jobs take seconds.
    return WithRetryAfter(absl::ResourceExhaustedError(absl::StrCat(
                              "all ", workers, " planning workers are busy and ", bounded_waiters_,
                              " requests are waiting (the most allowed); retry later")),
                          std::chrono::seconds(1));
  }
  const std::uint64_t ticket = next_ticket_++;
  auto me = waiters_.insert(waiters_.end(), ticket);
  if (bounded) ++bounded_waiters_;
  auto leave = [&] {
    waiters_.erase(me);
    if (bounded) --bounded_waiters_;
    // The next in line may be able to go now.
    free_cv_.notify_all();
  };
  while (true) {
    if (shutdown_) {
      leave();
      return absl::UnavailableError("server is shutting down");
    }
    if (busy_ < workers && waiters_.front() == ticket) {
      leave();
      ++busy_;
      return absl::OkStatus();
    }
    if (stop.StopRequested()) {
      leave();
      return stop.Reason() == StopReason::kDeadline
                 ? absl::DeadlineExceededError("stopped while waiting for a planning worker")
                 : absl::CancelledError("stopped while waiting for a planning worker");
    }
    // A StopToken has no condition variable to wake us: wait in short steps.
    free_cv_.wait_for(lock, tick_interval);
    if (tick) {
      lock.unlock();
      tick();
      lock.lock();
    }
  }
}

absl::Status WorkPool::Run(std::function<void()> work, const StopToken& stop,
                           const std::function<void()>& tick,
                           std::chrono::milliseconds tick_interval) {
  SEAPLAN_RETURN_IF_ERROR(Acquire(stop, /*bounded=*/true, tick, tick_interval));
  auto job = std::make_shared<Job>();
  job->work = std::move(work);
  Execute(job, tick, tick_interval);
  return absl::OkStatus();
}

absl::Status WorkPool::RunWhenFree(std::function<void()> work, const StopToken& stop) {
  SEAPLAN_RETURN_IF_ERROR(Acquire(stop, /*bounded=*/false, {}, std::chrono::milliseconds(20)));
  auto job = std::make_shared<Job>();
  job->work = std::move(work);
  Execute(job, {}, std::chrono::milliseconds(10));
  return absl::OkStatus();
}

void WorkPool::Execute(const std::shared_ptr<Job>& job, const std::function<void()>& tick,
                       std::chrono::milliseconds tick_interval) {
  {
    std::lock_guard lock(mu_);
    queue_.push_back(job);
  }
  cv_.notify_one();
  std::unique_lock lock(job->mu);
  while (!job->done) {
    if (job->cv.wait_for(lock, tick_interval, [&] { return job->done; })) break;
    if (tick) {
      lock.unlock();
      tick();
      lock.lock();
    }
  }
  lock.unlock();
  if (tick) tick();
}

}  // namespace seaplan::server
