#include "peers.h"

#include <cctype>
#include <cmath>
#include <cstdlib>
#include <sstream>

#include "absl/strings/ascii.h"
#include "absl/strings/str_split.h"
#include "absl/strings/strip.h"

namespace seaplan::bench {

std::vector<Run> ParsePeerRuns(const std::string& markdown) {
  std::vector<Run> runs;
  std::istringstream in(markdown);
  std::string line;
  bool in_table = false;
  while (std::getline(in, line)) {
    if (line.rfind("## ", 0) == 0) {
      in_table = line.find("Every run") != std::string::npos;
      continue;
    }
    if (!in_table || line.empty() || line[0] != '|') continue;
    std::vector<std::string> cells = absl::StrSplit(line, '|');
    // "| a | b |" splits into "", " a ", " b ", "".
    if (cells.size() < 10) continue;
    for (auto& c : cells) c = std::string(absl::StripAsciiWhitespace(c));
    if (cells[1] == "domain" || cells[1].rfind("---", 0) == 0) continue;
    Run r;
    r.domain = cells[1];
    r.problem = cells[2];
    r.planner = cells[3];
    r.solved = cells[4] == "solved";
    auto number = [](const std::string& s) {
      return s == "-" || s.empty() ? -1.0 : std::atof(s.c_str());
    };
    const double wall = number(cells[5]);
    const double first = number(cells[6]);
    r.time_s = first >= 0 ? first : wall;
    r.makespan = number(cells[7]);
    r.actions = static_cast<int>(number(cells[8]));
    runs.push_back(r);
  }
  return runs;
}

bool IsPlanLine(const std::string& line) {
  std::size_t i = line.find_first_not_of(" \t");
  if (i == std::string::npos || !(std::isdigit(static_cast<unsigned char>(line[i])))) return false;
  while (i < line.size() && (std::isdigit(static_cast<unsigned char>(line[i])) || line[i] == '.'))
    ++i;
  i = line.find_first_not_of(" \t", i);
  if (i == std::string::npos || line[i] != ':') return false;
  i = line.find_first_not_of(" \t", i + 1);
  return i != std::string::npos && line[i] == '(';
}

std::string LastPlan(const std::string& text) {
  std::istringstream in(text);
  std::string line, block, last;
  bool in_block = false;
  while (std::getline(in, line)) {
    if (IsPlanLine(line)) {
      if (!in_block) block.clear();
      block += line + "\n";
      in_block = true;
    } else if (in_block) {
      last = block;
      in_block = false;
    }
  }
  if (in_block) last = block;
  return last;
}

double TimeScore(const Run& run, double limit_s) {
  if (!run.solved || run.time_s < 0 || run.time_s > limit_s) return 0;
  if (run.time_s <= 1) return 1;
  return 1 - std::log(run.time_s) / std::log(limit_s);
}

}  // namespace seaplan::bench
