// Cooperative interruption for long engine work (planning, route optimisation).
//
// A StopToken combines a wall-clock deadline with a cancellation flag that
// another thread (an RPC whose client went away, a SIGTERM) may raise. Engine
// loops poll `StopRequested()` between steps; it is cheap (one atomic load and,
// every call, one steady_clock read), so polling every few hundred
// microseconds keeps the 50 ms cancellation promise. Copies share the flag.
#pragma once

#include <atomic>
#include <chrono>
#include <memory>

namespace seaplan {

enum class StopReason { kNone, kCancelled, kDeadline };

class StopToken {
 public:
  using Clock = std::chrono::steady_clock;

  // Never stops.
  StopToken();
  // Stops at `deadline` or when Cancel() is called on any copy.
  explicit StopToken(Clock::time_point deadline);
  static StopToken WithTimeout(std::chrono::duration<double> timeout);

  // Returns a token that stops when this one does or at `deadline`, whichever
  // comes first; cancelling the child does not cancel the parent.
  StopToken Child(Clock::time_point deadline) const;

  void Cancel() const;
  StopReason Reason() const;
  bool StopRequested() const { return Reason() != StopReason::kNone; }
  Clock::time_point deadline() const { return deadline_; }

 private:
  Clock::time_point deadline_;
  std::shared_ptr<std::atomic<bool>> cancelled_;
  std::shared_ptr<std::atomic<bool>> parent_cancelled_;  // may be null
};

}  // namespace seaplan
