// libFuzzer target: a simulation scenario file (clients/sim/core/scenario.h)
// -> Scenario -> the executor's configuration, as seaplan-sim reads one.
// Any text ends in an InvalidArgument "file:line: ..." or a configuration,
// never a crash; a parsed scenario's paths resolve and its positions project.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string_view>

#include "scenario.h"
#include "seaplan/common/log.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const bool quiet = [] {
    seaplan::log::SetLevel(seaplan::log::Level::kOff);  // a line per input drowns the fuzzer's
    return true;
  }();
  (void)quiet;
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  auto scenario = seaplan::sim::ParseScenario(text, "/fuzz/run.scenario");
  if (!scenario.ok()) {
    if (scenario.status().code() != absl::StatusCode::kInvalidArgument) std::abort();
    return 0;
  }
  (void)seaplan::sim::ResolvePath(*scenario, scenario->domain_path, "/shared");
  (void)seaplan::sim::ResolvePath(*scenario, scenario->chart_path, "");
  const auto frame = seaplan::chart::LocalFrame::ForCentre(scenario->locations.front().second);
  auto config = seaplan::sim::MakeExecutorConfig(*scenario, frame, scenario->ship_object);
  if (config.ok()) seaplan::sim::PerturbConfig(size, &config.value());
  return 0;
}
