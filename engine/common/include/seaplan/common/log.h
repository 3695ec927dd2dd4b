// The one logging facade of seaplan. Libraries log through these functions,
// never to std::cout; the sink (spdlog, stderr by default) is chosen by the
// binary's main. Keep logging out of hot loops.
// Thread-safe: every function may be called from any thread (the sink is
// spdlog's mutex-guarded "_mt" logger; the level is an atomic in spdlog).
#pragma once

#include <string_view>

#include "spdlog/spdlog.h"

namespace seaplan::log {

enum class Level { kDebug, kInfo, kWarn, kError, kOff };

// Sets the process-wide minimum level (binaries call this once from main).
void SetLevel(Level level);
// Parses "debug", "info", "warn", "error", "off"; returns false on an unknown name.
bool ParseLevel(std::string_view name, Level* level);

template <typename... Args>
void Debug(spdlog::format_string_t<Args...> fmt, Args&&... args) {
  spdlog::debug(fmt, std::forward<Args>(args)...);
}
template <typename... Args>
void Info(spdlog::format_string_t<Args...> fmt, Args&&... args) {
  spdlog::info(fmt, std::forward<Args>(args)...);
}
template <typename... Args>
void Warn(spdlog::format_string_t<Args...> fmt, Args&&... args) {
  spdlog::warn(fmt, std::forward<Args>(args)...);
}
template <typename... Args>
void Error(spdlog::format_string_t<Args...> fmt, Args&&... args) {
  spdlog::error(fmt, std::forward<Args>(args)...);
}

}  // namespace seaplan::log
