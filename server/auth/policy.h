// Roles, the caller's identity and the role x RPC table: which roles may
// call each RPC ("Service/Method", as both transports name it) and whether
// a vessel token is limited to its own vessel's missions there.
//
//   admin     everything, and tokens and the audit log
//   operator  missions, charts, planning and routes
//   viewer    read only (charts, missions, their watch)
//   vessel    bound to one vessel: its missions only (read, watch, report
//             feedback and state, request replans), and chart reads
#pragma once

#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>

#include "seaplan/common/status.h"

namespace seaplan::server::auth {

enum class Role : std::uint8_t { kAdmin = 0, kOperator = 1, kViewer = 2, kVessel = 3 };
inline constexpr Role kAllRoles[] = {Role::kAdmin, Role::kOperator, Role::kViewer, Role::kVessel};

// "admin", "operator", "viewer", "vessel".
std::string_view RoleName(Role role);
std::optional<Role> ParseRole(std::string_view name);

// Who is calling. `token_id` is empty for the server's own work (replans
// it runs by itself, in-process callers), which passes every check.
struct Caller {
  std::string token_id;
  Role role = Role::kAdmin;
  std::string vessel_id;  // set for Role::kVessel only

  bool internal() const { return token_id.empty(); }
};

struct MethodRule {
  std::string_view method;  // "MissionService/GetMission"
  std::uint8_t roles;       // bit (1 << Role) per role allowed
  // For a vessel token: only missions of its own vessel (the handler checks,
  // it knows the mission).
  bool vessel_scoped;
  // Recorded in the audit log when it succeeds (it changes state).
  bool audited;

  bool Allows(Role role) const { return (roles >> static_cast<int>(role)) & 1u; }
};

// The whole table, in proto order.
std::span<const MethodRule> MethodRules();
// nullptr when `method` has no entry (such a method is denied to everyone).
const MethodRule* FindRule(std::string_view method);

// OK when `caller` may call `method`; PermissionDenied (saying the role
// and the method) otherwise.
absl::Status Authorize(const Caller& caller, std::string_view method);

// For a handler of a vessel-scoped RPC: PermissionDenied when a vessel
// token acts on a mission of another vessel.
absl::Status CheckVessel(const Caller& caller, std::string_view mission_vessel_id,
                         std::string_view mission_id);

}  // namespace seaplan::server::auth
