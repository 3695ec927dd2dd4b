#include "seaplan/common/stop_token.h"

#include <algorithm>

namespace seaplan {

StopToken::StopToken() : StopToken(Clock::time_point::max()) {}

StopToken::StopToken(Clock::time_point deadline)
    : deadline_(deadline), cancelled_(std::make_shared<std::atomic<bool>>(false)) {}

StopToken StopToken::WithTimeout(std::chrono::duration<double> timeout) {
  const auto now = Clock::now();
  // Compare in floating seconds first: casting a huge timeout to ticks overflows.
  const std::chrono::duration<double> max_wait = Clock::time_point::max() - now;
  if (!(timeout < max_wait)) return StopToken();
  return StopToken(now + std::chrono::duration_cast<Clock::duration>(timeout));
}

StopToken StopToken::Child(Clock::time_point deadline) const {
  StopToken child(std::min(deadline, deadline_));
  child.parent_cancelled_ = cancelled_;
  return child;
}

void StopToken::Cancel() const {
  cancelled_->store(true, std::memory_order_relaxed);
}

StopReason StopToken::Reason() const {
  if (cancelled_->load(std::memory_order_relaxed) ||
      (parent_cancelled_ && parent_cancelled_->load(std::memory_order_relaxed))) {
    return StopReason::kCancelled;
  }
  if (deadline_ != Clock::time_point::max() && Clock::now() >= deadline_) {
    return StopReason::kDeadline;
  }
  return StopReason::kNone;
}

}  // namespace seaplan
