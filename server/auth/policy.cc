#include "server/auth/policy.h"

#include <algorithm>

#include "absl/strings/str_cat.h"

namespace seaplan::server::auth {
namespace {

constexpr std::uint8_t Bit(Role r) {
  return static_cast<std::uint8_t>(1u << static_cast<int>(r));
}
constexpr std::uint8_t kAdmin = Bit(Role::kAdmin);
constexpr std::uint8_t kStaff = kAdmin | Bit(Role::kOperator);
constexpr std::uint8_t kReaders = kStaff | Bit(Role::kViewer);
constexpr std::uint8_t kEveryone = kReaders | Bit(Role::kVessel);
constexpr std::uint8_t kStaffAndVessel = kStaff | Bit(Role::kVessel);

// Keep server/README.md's table in step; access_matrix_e2e_test calls every
// RPC of the proto with every role against this table.
constexpr MethodRule kRules[] = {
    {"PlanningService/Plan", kStaff, false, false},
    {"PlanningService/PlanStream", kStaff, false, false},
    {"PlanningService/Validate", kStaff, false, false},
    {"ChartService/UploadChart", kStaff, false, true},
    {"ChartService/GetChart", kEveryone, false, false},
    {"ChartService/ListCharts", kEveryone, false, false},
    {"ChartService/GetObstacles", kEveryone, false, false},
    {"ChartService/DeleteChart", kAdmin, false, true},
    {"RouteService/PlanRoute", kStaff, false, false},
    {"RouteService/EstimateRisk", kStaff, false, false},
    {"MissionService/CreateMission", kStaff, false, true},
    {"MissionService/GetMission", kEveryone, true, false},
    {"MissionService/ListMissions", kReaders, false, false},
    {"MissionService/WatchMission", kEveryone, true, false},
    {"MissionService/ReportFeedback", kStaffAndVessel, true, false},
    {"MissionService/RequestReplan", kStaffAndVessel, true, true},
    {"MissionService/CancelMission", kStaff, false, true},
    {"MissionService/ReportVesselState", kStaffAndVessel, true, false},
    {"MissionService/ListFeedback", kEveryone, true, false},
    {"AccessService/WhoAmI", kEveryone, false, false},
    {"AccessService/CreateToken", kAdmin, false, true},
    {"AccessService/ListTokens", kAdmin, false, false},
    {"AccessService/RevokeToken", kAdmin, false, true},
    {"AccessService/ListAuditEvents", kAdmin, false, false},
};

}  // namespace

std::string_view RoleName(Role role) {
  switch (role) {
    case Role::kAdmin:
      return "admin";
    case Role::kOperator:
      return "operator";
    case Role::kViewer:
      return "viewer";
    case Role::kVessel:
      return "vessel";
  }
  return "unknown";
}

std::optional<Role> ParseRole(std::string_view name) {
  for (Role r : kAllRoles) {
    if (RoleName(r) == name) return r;
  }
  return std::nullopt;
}

std::span<const MethodRule> MethodRules() {
  return kRules;
}

const MethodRule* FindRule(std::string_view method) {
  const auto* it = std::find_if(std::begin(kRules), std::end(kRules),
                                [&](const MethodRule& r) { return r.method == method; });
  return it == std::end(kRules) ? nullptr : it;
}

absl::Status Authorize(const Caller& caller, std::string_view method) {
  if (caller.internal()) return absl::OkStatus();
  const MethodRule* rule = FindRule(method);
  if (rule == nullptr) {
    return absl::PermissionDeniedError(
        absl::StrCat(std::string(method), " has no entry in the access table: denied to every role"));
  }
  if (!rule->Allows(caller.role)) {
    return absl::PermissionDeniedError(
        absl::StrCat("role '", std::string(RoleName(caller.role)), "' may not call ",
                     std::string(method)));
  }
  return absl::OkStatus();
}

absl::Status CheckVessel(const Caller& caller, std::string_view mission_vessel_id,
                         std::string_view mission_id) {
  if (caller.internal() || caller.role != Role::kVessel) return absl::OkStatus();
  if (caller.vessel_id == mission_vessel_id) return absl::OkStatus();
  return absl::PermissionDeniedError(absl::StrCat(
      "a token of vessel '", caller.vessel_id, "' may not act on mission '",
      std::string(mission_id), "' of vessel '", std::string(mission_vessel_id), "'"));
}

}  // namespace seaplan::server::auth
