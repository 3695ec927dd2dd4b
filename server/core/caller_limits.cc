#include "server/core/caller_limits.h"

#include <algorithm>
#include <cmath>
#include <functional>

#include "absl/hash/hash.h"
#include "absl/strings/str_cat.h"
#include "server/core/status_details.h"

namespace seaplan::server {
namespace {

// "ipv4:1.2.3.4:5" -> "1.2.3.4"; "ipv6:[::1]:5" -> "::1"; "1.2.3.4" stays.
std::string_view PeerHost(std::string_view peer) {
  for (std::string_view scheme : {"ipv4:", "ipv6:"}) {
    if (peer.substr(0, scheme.size()) == scheme) {
      peer.remove_prefix(scheme.size());
      if (!peer.empty() && peer.front() == '[') {
        const auto close = peer.find(']');
        return close == std::string_view::npos ? peer.substr(1) : peer.substr(1, close - 1);
      }
      const auto colon = peer.rfind(':');
      return colon == std::string_view::npos ? peer : peer.substr(0, colon);
    }
  }
  return peer;
}

}  // namespace

std::string CallerKey(std::string_view authorization, std::string_view peer) {
  if (!authorization.empty()) {
    return absl::StrCat(
        "credentials:",
        absl::Hex(absl::Hash<std::string>{}(std::string(authorization)), absl::kZeroPad16));
  }
  return absl::StrCat("address:", std::string(PeerHost(peer)));
}

absl::Status CheckVesselCertificate(const CallContext& ctx, std::string_view mission_vessel_id,
                                    std::string_view mission_id) {
  if (ctx.client_cert_subject.empty()) return absl::OkStatus();
  if (ctx.caller.role == auth::Role::kVessel && !ctx.caller.internal() &&
      ctx.caller.vessel_id != ctx.client_cert_subject) {
    return absl::PermissionDeniedError(absl::StrCat(
        "a token of vessel '", ctx.caller.vessel_id,
        "' was presented with the client certificate of vessel '", ctx.client_cert_subject, "'"));
  }
  if (ctx.client_cert_subject == mission_vessel_id) return absl::OkStatus();
  return absl::PermissionDeniedError(absl::StrCat(
      "the client certificate of vessel '", ctx.client_cert_subject, "' may not act on mission '",
      std::string(mission_id), "' of vessel '", std::string(mission_vessel_id), "'"));
}

RateLimiter::RateLimiter(const Options& options)
    : options_{options.calls_per_s, std::max(1.0, options.burst)} {}

std::size_t RateLimiter::tracked_callers() const {
  std::lock_guard lock(mu_);
  return buckets_.size();
}

absl::Status RateLimiter::Admit(const std::string& caller_key, Clock::time_point now) {
  if (!enabled()) return absl::OkStatus();
  std::lock_guard lock(mu_);
  Sweep(now);
  auto [it, inserted] = buckets_.try_emplace(caller_key, Bucket{options_.burst, now});
  Bucket& bucket = it->second;
  if (!inserted && now > bucket.updated) {
    const double elapsed_s = std::chrono::duration<double>(now - bucket.updated).count();
    bucket.tokens = std::min(options_.burst, bucket.tokens + elapsed_s * options_.calls_per_s);
    bucket.updated = now;
  }
  if (bucket.tokens >= 1.0) {
    bucket.tokens -= 1.0;
    return absl::OkStatus();
  }
  const double wait_s = (1.0 - bucket.tokens) / options_.calls_per_s;
  const auto wait = std::chrono::milliseconds(static_cast<long long>(std::ceil(wait_s * 1000.0)));
  return WithRetryAfter(
      absl::ResourceExhaustedError(
          absl::StrCat("rate limit: more than ", options_.calls_per_s, " calls per second (burst ",
                       options_.burst, ") from this caller; retry after ", wait.count(), " ms")),
      wait);
}

void RateLimiter::Sweep(Clock::time_point now) {
  if (now < next_sweep_) return;
  const auto full_after = std::chrono::duration_cast<Clock::duration>(
      std::chrono::duration<double>(options_.burst / options_.calls_per_s));
  std::erase_if(buckets_,
                [&](const auto& entry) { return now - entry.second.updated >= full_after; });
  next_sweep_ = now + std::max<Clock::duration>(full_after, std::chrono::seconds(1));
}

}  // namespace seaplan::server
