#include "server/core/convert.h"

#include <charconv>
#include <chrono>
#include <mutex>
#include <random>

#include "absl/strings/str_cat.h"
#include "absl/strings/str_format.h"

namespace seaplan::server {

v1::Diagnostic ToProto(const pddl::Diagnostic& d) {
  v1::Diagnostic out;
  out.set_severity(d.severity == pddl::Severity::kError ? v1::Diagnostic::ERROR
                                                        : v1::Diagnostic::WARNING);
  switch (d.kind) {
    case pddl::DiagnosticKind::kSyntax:
      out.set_kind(v1::Diagnostic::SYNTAX);
      break;
    case pddl::DiagnosticKind::kSemantic:
      out.set_kind(v1::Diagnostic::SEMANTIC);
      break;
    case pddl::DiagnosticKind::kUnsupported:
      out.set_kind(v1::Diagnostic::UNSUPPORTED);
      break;
  }
  out.set_file(d.location.file);
  out.set_line(d.location.line);
  out.set_column(d.location.column);
  out.set_symbol(d.symbol);
  out.set_message(d.message);
  out.set_expected(d.expected);
  return out;
}

v1::DiagnosticList ToProto(const std::vector<pddl::Diagnostic>& diagnostics) {
  v1::DiagnosticList list;
  for (const auto& d : diagnostics) *list.add_diagnostics() = ToProto(d);
  return list;
}

google::protobuf::Timestamp ToTimestamp(std::int64_t ms) {
  google::protobuf::Timestamp t;
  std::int64_t seconds = ms / 1000;
  std::int64_t rest = ms % 1000;
  if (rest < 0) {
    rest += 1000;
    --seconds;
  }
  t.set_seconds(seconds);
  t.set_nanos(static_cast<std::int32_t>(rest * 1'000'000));
  return t;
}

std::int64_t NowMs() {
  return std::chrono::duration_cast<std::chrono::milliseconds>(
             std::chrono::system_clock::now().time_since_epoch())
      .count();
}

absl::StatusOr<double> DurationSeconds(const google::protobuf::Duration& d, const char* field) {
  const double s = static_cast<double>(d.seconds()) + static_cast<double>(d.nanos()) * 1e-9;
  if (s < 0) return absl::InvalidArgumentError(absl::StrCat(field, " must not be negative"));
  return s;
}

absl::StatusOr<std::int64_t> ParsePageToken(const std::string& token) {
  if (token.empty()) return 0;
  std::int64_t value = 0;
  auto [end, ec] = std::from_chars(token.data(), token.data() + token.size(), value);
  if (ec != std::errc() || end != token.data() + token.size() || value <= 0) {
    return absl::InvalidArgumentError(absl::StrCat("invalid page_token '", token, "'"));
  }
  return value;
}

std::string MakePageToken(std::int64_t after) {
  return after == 0 ? std::string() : absl::StrCat(after);
}

absl::StatusOr<int> PageSize(int requested) {
  if (requested < 0) return absl::InvalidArgumentError("page_size must not be negative");
  if (requested == 0) return 50;
  return std::min(requested, 1000);
}

std::string NewId(const char* prefix) {
  static std::mutex mu;
  static std::mt19937_64 rng{std::random_device{}()};
  std::lock_guard lock(mu);
  return absl::StrFormat("%s%016x", prefix, rng());
}

}  // namespace seaplan::server
