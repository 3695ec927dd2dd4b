#include "server/core/work_pool.h"

#include "absl/strings/str_cat.h"

namespace seaplan::server {

WorkPool::WorkPool(int threads) {
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
    free_cv_.notify_one();
    {
      std::lock_guard lock(job->mu);
      job->done = true;
    }
    job->cv.notify_all();
  }
}

absl::Status WorkPool::Run(std::function<void()> work, const std::function<void()>& tick,
                           std::chrono::milliseconds tick_interval) {
  auto job = std::make_shared<Job>();
  job->work = std::move(work);
  {
    std::lock_guard lock(mu_);
    if (shutdown_) return absl::UnavailableError("server is shutting down");
    if (busy_ >= static_cast<int>(threads_.size())) {
      return absl::ResourceExhaustedError(
          absl::StrCat("all ", threads_.size(), " planning workers are busy; retry later"));
    }
    ++busy_;
  }
  Execute(job, tick, tick_interval);
  return absl::OkStatus();
}

absl::Status WorkPool::RunWhenFree(std::function<void()> work, const StopToken& stop) {
  auto job = std::make_shared<Job>();
  job->work = std::move(work);
  {
    std::unique_lock lock(mu_);
    // Waits in short steps: a StopToken has no condition variable to wake us.
    while (!shutdown_ && busy_ >= static_cast<int>(threads_.size()) && !stop.StopRequested())
      free_cv_.wait_for(lock, std::chrono::milliseconds(20));
    if (shutdown_) return absl::UnavailableError("server is shutting down");
    if (stop.StopRequested()) {
      return stop.Reason() == StopReason::kDeadline
                 ? absl::DeadlineExceededError("stopped while waiting for a planning worker")
                 : absl::CancelledError("stopped while waiting for a planning worker");
    }
    ++busy_;
  }
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
