// Human-readable and JSON rendering of seaplan.v1 messages for the CLI.
#pragma once

#include <cstdint>
#include <ostream>
#include <string>

#include "absl/status/status.h"
#include "google/protobuf/message.h"
#include "seaplan/v1/chart.pb.h"
#include "seaplan/v1/mission.pb.h"
#include "seaplan/v1/planning.pb.h"
#include "seaplan/v1/route.pb.h"

namespace seaplan::cli {

// Exit codes of the `seaplan` command (tested by tests/cli).
enum ExitCode : int {
  kExitSuccess = 0,
  kExitNoPlan = 1,        // no plan found, or the plan is invalid
  kExitBadInput = 2,      // bad input or usage
  kExitServiceError = 3,  // the server is unreachable or failed
};

// One-line JSON (canonical proto3 mapping).
std::string ToJson(const google::protobuf::Message& message);

// The plan in the IPC format "start: (name args) [duration]".
std::string FormatPlanText(const seaplan::v1::PlanResponse& response);
void PrintPlanResponse(std::ostream& out, const seaplan::v1::PlanResponse& response);
void PrintValidateResponse(std::ostream& out, const seaplan::v1::ValidateResponse& response);
void PrintChart(std::ostream& out, const seaplan::v1::Chart& chart);
void PrintRoute(std::ostream& out, const seaplan::v1::PlanRouteResponse& response);
void PrintRisk(std::ostream& out, const seaplan::v1::EstimateRiskResponse& response);
void PrintMission(std::ostream& out, const seaplan::v1::Mission& mission);
void PrintPlanVersion(std::ostream& out, const seaplan::v1::PlanVersion& version);
void PrintLogEvent(std::ostream& out, const seaplan::v1::LogEvent& event);
// Stored feedback reports, one line each under a header.
void PrintFeedbackTable(std::ostream& out, const seaplan::v1::ListFeedbackResponse& response);
// "2026-11-25 16:20:00Z" for ms since the epoch.
std::string FormatTimeMs(std::int64_t ms);

// Prints an error with its diagnostics (carried as a DiagnosticList payload)
// and returns the exit code for its status code.
int ReportError(std::ostream& err, const absl::Status& status);

const char* MsoModeName(seaplan::v1::MsoMode mode);

// absl::Status payload key under which a serialized seaplan.v1.DiagnosticList
// travels (the gRPC transport carries the same bytes in error_details).
inline constexpr char kDiagnosticsPayloadUrl[] = "type.googleapis.com/seaplan.v1.DiagnosticList";

}  // namespace seaplan::cli
