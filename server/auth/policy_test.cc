#include "server/auth/policy.h"

#include <gtest/gtest.h>

#include <set>

namespace seaplan::server::auth {
namespace {

Caller As(Role role, std::string vessel = "") {
  return Caller{"tok", role, std::move(vessel)};
}

TEST(PolicyTest, RolesRoundTrip) {
  for (Role r : kAllRoles) EXPECT_EQ(ParseRole(RoleName(r)), r);
  EXPECT_FALSE(ParseRole("root").has_value());
}

TEST(PolicyTest, TableHasEachMethodOnceAndAdminEverywhere) {
  std::set<std::string_view> seen;
  for (const MethodRule& rule : MethodRules()) {
    EXPECT_TRUE(seen.insert(rule.method).second) << rule.method;
    EXPECT_TRUE(rule.Allows(Role::kAdmin)) << rule.method;
    // Vessel scoping only means something where a vessel may call.
    if (rule.vessel_scoped) {
      EXPECT_TRUE(rule.Allows(Role::kVessel)) << rule.method;
    }
  }
}

TEST(PolicyTest, DecisionsFollowTheRoles) {
  EXPECT_TRUE(Authorize(As(Role::kOperator), "MissionService/CreateMission").ok());
  EXPECT_EQ(Authorize(As(Role::kViewer), "MissionService/CreateMission").code(),
            absl::StatusCode::kPermissionDenied);
  EXPECT_TRUE(Authorize(As(Role::kViewer), "MissionService/WatchMission").ok());
  EXPECT_EQ(Authorize(As(Role::kViewer), "MissionService/ReportFeedback").code(),
            absl::StatusCode::kPermissionDenied);
  EXPECT_TRUE(Authorize(As(Role::kVessel, "mass-1"), "MissionService/ReportFeedback").ok());
  EXPECT_EQ(Authorize(As(Role::kVessel, "mass-1"), "MissionService/ListMissions").code(),
            absl::StatusCode::kPermissionDenied);
  EXPECT_EQ(Authorize(As(Role::kOperator), "AccessService/CreateToken").code(),
            absl::StatusCode::kPermissionDenied);
  EXPECT_TRUE(Authorize(As(Role::kAdmin), "AccessService/CreateToken").ok());
  // A method without an entry is denied even to an admin.
  EXPECT_EQ(Authorize(As(Role::kAdmin), "MissionService/DropEverything").code(),
            absl::StatusCode::kPermissionDenied);
  // The server's own work passes.
  EXPECT_TRUE(Authorize(Caller{}, "MissionService/DropEverything").ok());
}

TEST(PolicyTest, VesselTokensReachOnlyTheirVessel) {
  EXPECT_TRUE(CheckVessel(As(Role::kVessel, "mass-1"), "mass-1", "m").ok());
  const absl::Status other = CheckVessel(As(Role::kVessel, "mass-1"), "mass-2", "m");
  EXPECT_EQ(other.code(), absl::StatusCode::kPermissionDenied);
  EXPECT_NE(other.message().find("mass-2"), std::string_view::npos);
  EXPECT_TRUE(CheckVessel(As(Role::kViewer), "mass-2", "m").ok());
  EXPECT_TRUE(CheckVessel(Caller{}, "mass-2", "m").ok());
}

}  // namespace
}  // namespace seaplan::server::auth
