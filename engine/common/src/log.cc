#include "seaplan/common/log.h"

#include "spdlog/sinks/stdout_color_sinks.h"

namespace seaplan::log {
namespace {

// Route the default logger to stderr so stdout stays free for program output.
void EnsureStderrLogger() {
  static const bool installed = [] {
    auto logger = spdlog::stderr_color_mt("seaplan");
    logger->set_pattern("%Y-%m-%dT%H:%M:%S.%e %^%l%$ %v");
    spdlog::set_default_logger(logger);
    return true;
  }();
  (void)installed;
}

}  // namespace

void SetLevel(Level level) {
  EnsureStderrLogger();
  switch (level) {
    case Level::kDebug:
      spdlog::set_level(spdlog::level::debug);
      break;
    case Level::kInfo:
      spdlog::set_level(spdlog::level::info);
      break;
    case Level::kWarn:
      spdlog::set_level(spdlog::level::warn);
      break;
    case Level::kError:
      spdlog::set_level(spdlog::level::err);
      break;
    case Level::kOff:
      spdlog::set_level(spdlog::level::off);
      break;
  }
}

bool ParseLevel(std::string_view name, Level* level) {
  if (name == "debug")
    *level = Level::kDebug;
  else if (name == "info")
    *level = Level::kInfo;
  else if (name == "warn")
    *level = Level::kWarn;
  else if (name == "error")
    *level = Level::kError;
  else if (name == "off")
    *level = Level::kOff;
  else
    return false;
  return true;
}

}  // namespace seaplan::log
