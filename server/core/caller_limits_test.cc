#include "server/core/caller_limits.h"

#include <gtest/gtest.h>

#include "server/core/status_details.h"

namespace seaplan::server {
namespace {

using std::chrono::milliseconds;

TEST(CallerKeyTest, CredentialsWinOverTheAddressAndThePortIsDropped) {
  EXPECT_EQ(CallerKey("", "ipv4:127.0.0.1:5000"), "address:127.0.0.1");
  EXPECT_EQ(CallerKey("", "ipv4:127.0.0.1:6000"), CallerKey("", "127.0.0.1"));
  EXPECT_EQ(CallerKey("", "ipv6:[::1]:5000"), "address:::1");
  const std::string a = CallerKey("Bearer secret-a", "ipv4:10.0.0.1:1");
  EXPECT_EQ(a.rfind("credentials:", 0), 0u) << a;
  EXPECT_EQ(a.find("secret"), std::string::npos) << "the key must not hold the credentials";
  EXPECT_EQ(a, CallerKey("Bearer secret-a", "ipv4:10.0.0.2:2"));  // same caller, other address
  EXPECT_NE(a, CallerKey("Bearer secret-b", "ipv4:10.0.0.1:1"));
}

TEST(RateLimiterTest, BurstThenSustainedRateWithRetryAfterPerCaller) {
  RateLimiter limiter({/*calls_per_s=*/10.0, /*burst=*/3.0});
  const auto t0 = RateLimiter::Clock::time_point{} + std::chrono::hours(1);
  for (int i = 0; i < 3; ++i) EXPECT_TRUE(limiter.Admit("a", t0).ok()) << i;
  const absl::Status refused = limiter.Admit("a", t0);
  EXPECT_EQ(refused.code(), absl::StatusCode::kResourceExhausted);
  ASSERT_TRUE(GetRetryAfter(refused).has_value());
  EXPECT_EQ(*GetRetryAfter(refused), milliseconds(100));  // one call per 100 ms
  // Another caller has its own bucket.
  EXPECT_TRUE(limiter.Admit("b", t0).ok());
  // 100 ms later one call is allowed again, not two.
  EXPECT_TRUE(limiter.Admit("a", t0 + milliseconds(100)).ok());
  EXPECT_FALSE(limiter.Admit("a", t0 + milliseconds(100)).ok());
  // After a long pause the bucket is full again (burst, not more).
  for (int i = 0; i < 3; ++i) EXPECT_TRUE(limiter.Admit("a", t0 + std::chrono::seconds(10)).ok());
  EXPECT_FALSE(limiter.Admit("a", t0 + std::chrono::seconds(10)).ok());
}

TEST(RateLimiterTest, ZeroRateIsNoLimitAndIdleCallersAreForgotten) {
  RateLimiter off({0.0, 1.0});
  for (int i = 0; i < 1000; ++i) ASSERT_TRUE(off.Admit("a").ok());
  EXPECT_EQ(off.tracked_callers(), 0u);

  RateLimiter limiter({/*calls_per_s=*/100.0, /*burst=*/10.0});
  const auto t0 = RateLimiter::Clock::time_point{} + std::chrono::hours(1);
  for (int i = 0; i < 50; ++i) ASSERT_TRUE(limiter.Admit("caller-" + std::to_string(i), t0).ok());
  EXPECT_EQ(limiter.tracked_callers(), 50u);
  // Their buckets refilled long ago: the table holds only the new caller.
  ASSERT_TRUE(limiter.Admit("late", t0 + std::chrono::seconds(5)).ok());
  EXPECT_EQ(limiter.tracked_callers(), 1u);
}

TEST(VesselCertificateTest, ACertificateActsOnlyOnItsVesselsMissions) {
  CallContext no_cert;
  EXPECT_TRUE(CheckVesselCertificate(no_cert, "mass-2", "m1").ok());
  CallContext vessel;
  vessel.client_cert_subject = "mass-1";
  EXPECT_TRUE(CheckVesselCertificate(vessel, "mass-1", "m1").ok());
  const absl::Status denied = CheckVesselCertificate(vessel, "mass-2", "m2");
  EXPECT_EQ(denied.code(), absl::StatusCode::kPermissionDenied);
  EXPECT_NE(denied.message().find("mass-1"), std::string_view::npos);
  EXPECT_NE(denied.message().find("mass-2"), std::string_view::npos);
}

}  // namespace
}  // namespace seaplan::server
