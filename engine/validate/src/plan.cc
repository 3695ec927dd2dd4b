#include "seaplan/validate/plan.h"

#include <cctype>
#include <charconv>
#include <cmath>
#include <system_error>

#include "absl/strings/str_cat.h"

namespace seaplan::validate {
namespace {

// A cursor over one line; columns are 1-based byte offsets.
class LineScanner {
 public:
  LineScanner(std::string_view line, int line_number) : line_(line), line_number_(line_number) {}

  // Skips every character Name() treats as a separator (a stray '\r' in a
  // line is whitespace too).
  void SkipSpace() {
    while (pos_ < line_.size() && std::isspace(static_cast<unsigned char>(line_[pos_]))) ++pos_;
  }
  // True at the end of the line or at a ';' comment.
  bool AtEnd() const { return pos_ >= line_.size() || line_[pos_] == ';'; }
  char Peek() const { return pos_ < line_.size() ? line_[pos_] : '\0'; }
  void Advance() { ++pos_; }
  int column() const { return static_cast<int>(pos_) + 1; }

  absl::Status Error(std::string_view what) const { return ErrorAt(column(), what); }
  absl::Status ErrorAt(int col, std::string_view what) const {
    return absl::InvalidArgumentError(
        absl::StrCat("plan line ", line_number_, ", column ", col, ": ", std::string(what)));
  }

  // A number as std::from_chars reads it; rejects inf and nan.
  absl::StatusOr<double> Number(std::string_view what) {
    SkipSpace();
    const int start_col = column();
    const char* begin = line_.data() + pos_;
    const char* end = line_.data() + line_.size();
    // from_chars does not accept a leading '+'; a plan may carry one.
    if (begin != end && *begin == '+') ++begin;
    double value = 0.0;
    const auto [ptr, ec] = std::from_chars(begin, end, value, std::chars_format::general);
    if (ec == std::errc::result_out_of_range) {
      return ErrorAt(start_col, absl::StrCat(std::string(what), " is out of range"));
    }
    if (ec != std::errc() || ptr == begin) {
      return ErrorAt(start_col,
                     absl::StrCat("expected ", std::string(what), ", found ", Describe()));
    }
    if (!std::isfinite(value)) {
      return ErrorAt(start_col, absl::StrCat(std::string(what), " must be a finite number"));
    }
    pos_ = static_cast<std::size_t>(ptr - line_.data());
    return value;
  }

  // A name: any run of characters other than space, parentheses, brackets and ';'.
  std::string Name() {
    std::string out;
    while (pos_ < line_.size()) {
      const char c = line_[pos_];
      if (std::isspace(static_cast<unsigned char>(c)) || c == '(' || c == ')' || c == '[' ||
          c == ']' || c == ';') {
        break;
      }
      out.push_back(static_cast<char>(std::tolower(static_cast<unsigned char>(c))));
      ++pos_;
    }
    return out;
  }

  std::string Describe() const {
    if (pos_ >= line_.size()) return "end of line";
    if (line_[pos_] == ';') return "a comment";
    return "'" + std::string(line_.substr(pos_, 1)) + "'";
  }

 private:
  std::string_view line_;
  int line_number_;
  std::size_t pos_ = 0;
};

absl::StatusOr<PlanStep> ParseStep(std::string_view line, int line_number) {
  LineScanner scan(line, line_number);
  PlanStep step;
  step.line = line_number;
  SEAPLAN_ASSIGN_OR_RETURN(step.start_s, scan.Number("a start time"));
  scan.SkipSpace();
  if (scan.Peek() == ':') scan.Advance();
  scan.SkipSpace();
  if (scan.Peek() != '(') return scan.Error(absl::StrCat("expected '(', found ", scan.Describe()));
  scan.Advance();
  scan.SkipSpace();
  step.name = scan.Name();
  if (step.name.empty()) {
    return scan.Error(absl::StrCat("expected an action name, found ", scan.Describe()));
  }
  while (true) {
    scan.SkipSpace();
    if (scan.Peek() == ')') {
      scan.Advance();
      break;
    }
    if (scan.AtEnd() || scan.Peek() == '(' || scan.Peek() == '[' || scan.Peek() == ']') {
      return scan.Error(absl::StrCat("expected an argument or ')', found ", scan.Describe()));
    }
    std::string arg = scan.Name();
    // Name() stops only at separators handled above; an empty name would
    // mean no progress, so it is an error rather than a loop.
    if (arg.empty()) return scan.Error(absl::StrCat("unexpected ", scan.Describe()));
    step.args.push_back(std::move(arg));
  }
  scan.SkipSpace();
  if (scan.Peek() == '[') {
    scan.Advance();
    SEAPLAN_ASSIGN_OR_RETURN(step.duration_s, scan.Number("a duration"));
    scan.SkipSpace();
    if (scan.Peek() != ']')
      return scan.Error(absl::StrCat("expected ']', found ", scan.Describe()));
    scan.Advance();
    scan.SkipSpace();
  }
  if (!scan.AtEnd()) {
    return scan.Error(absl::StrCat("unexpected ", scan.Describe(), " after the step"));
  }
  return step;
}

}  // namespace

std::string PlanStep::DisplayName() const {
  std::string out = "(" + name;
  for (const auto& arg : args) absl::StrAppend(&out, " ", arg);
  return out + ")";
}

absl::StatusOr<Plan> ParsePlan(std::string_view text) {
  if (text.substr(0, 3) == "\xEF\xBB\xBF") text.remove_prefix(3);
  Plan plan;
  int line_number = 0;
  while (!text.empty()) {
    ++line_number;
    const std::size_t newline = text.find('\n');
    std::string_view line = text.substr(0, newline);
    text.remove_prefix(newline == std::string_view::npos ? text.size() : newline + 1);
    if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
    LineScanner probe(line, line_number);
    probe.SkipSpace();
    if (probe.AtEnd()) continue;  // blank or comment line
    SEAPLAN_ASSIGN_OR_RETURN(PlanStep step, ParseStep(line, line_number));
    plan.steps.push_back(std::move(step));
  }
  return plan;
}

std::string FormatTime(double value) {
  if (value == 0.0) return "0";  // also folds -0
  char buffer[512];              // fixed notation of the largest double needs ~330 characters
  const auto [ptr, ec] =
      std::to_chars(buffer, buffer + sizeof buffer, value, std::chars_format::fixed);
  if (ec != std::errc()) return std::to_string(value);  // unreachable for finite values
  return std::string(buffer, ptr);
}

std::string FormatPlan(const Plan& plan) {
  std::string out;
  for (const auto& step : plan.steps) {
    absl::StrAppend(&out, FormatTime(step.start_s), ": ", step.DisplayName());
    if (step.duration_s != 0.0) absl::StrAppend(&out, " [", FormatTime(step.duration_s), "]");
    out += '\n';
  }
  return out;
}

}  // namespace seaplan::validate
