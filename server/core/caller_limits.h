// Per-caller limits of the server: who a call comes from, as far as the
// transport tells (CallerKey), and a token bucket per caller (RateLimiter).
//
// A caller is keyed by its credentials when it sends any (the
// `authorization` header / metadata value, hashed: the key never holds a
// secret) and by its network address otherwise, so many clients behind one
// address with their own credentials get their own buckets.
#pragma once

#include <chrono>
#include <cstddef>
#include <mutex>
#include <string>
#include <string_view>
#include <unordered_map>

#include "seaplan/common/status.h"
#include "server/core/call_context.h"

namespace seaplan::server {

// The one place a caller key is made. `authorization`: the request's
// authorization value (may be empty); `peer`: the client's address as the
// transport gives it ("ipv4:127.0.0.1:5000", "ipv6:[::1]:5000" from gRPC,
// "127.0.0.1" from HTTP); the port is dropped (it changes per connection).
std::string CallerKey(std::string_view authorization, std::string_view peer);

// What one request may ask of the server's engines: a client's own time or
// memory limit beyond these is refused (InvalidArgument naming the limit),
// so one call cannot hold a worker for hours or take the machine's memory.
struct RequestBudgets {
  double max_plan_time_s = 600;           // PlannerOptions.time_limit
  std::size_t max_plan_memory_mb = 8192;  // PlannerOptions.memory_limit_mb
  double max_route_time_s = 300;          // OptimizerOptions.time_limit
  // OptimizerOptions particles x iterations (default 30 x 100).
  long long max_route_evaluations = 100000;
};

// A client certificate names a vessel (its subject CN): such a caller may
// watch, feed and replan only missions of that vessel. PermissionDenied
// naming both when `mission_vessel_id` is another, or when the caller's
// vessel token names another vessel than the certificate; OK without a
// certificate.
absl::Status CheckVesselCertificate(const CallContext& ctx, std::string_view mission_vessel_id,
                                    std::string_view mission_id);

class RateLimiter {
 public:
  using Clock = std::chrono::steady_clock;
  struct Options {
    // Sustained calls per second per caller; 0 turns the limit off.
    double calls_per_s = 100.0;
    // Calls a caller may make at once after being idle (bucket size, >= 1).
    double burst = 200.0;
  };

  explicit RateLimiter(const Options& options);

  // Takes one call from `caller_key`'s bucket. ResourceExhausted with a
  // retry-after (status_details.h) when the bucket is empty.
  absl::Status Admit(const std::string& caller_key, Clock::time_point now = Clock::now());

  bool enabled() const { return options_.calls_per_s > 0; }
  std::size_t tracked_callers() const;

 private:
  struct Bucket {
    double tokens = 0;
    Clock::time_point updated;
  };
  // Drops buckets that have refilled completely (they are as good as new);
  // keeps the table bounded by the callers of the last burst/rate seconds.
  void Sweep(Clock::time_point now);

  const Options options_;
  mutable std::mutex mu_;
  std::unordered_map<std::string, Bucket> buckets_;
  Clock::time_point next_sweep_{};
};

}  // namespace seaplan::server
