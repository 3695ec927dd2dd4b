// Waiting for a child process the test started (a server, nginx) to be
// ready, without waiting out the whole timeout when it has already died.
// Header-only: the benchmarks that start servers use it without the test
// library.
#pragma once

#include <sys/types.h>
#include <sys/wait.h>

#include <chrono>
#include <functional>
#include <thread>

namespace seaplan::testing {

enum class ChildReadiness {
  kReady,     // `ready` held
  kExited,    // the child ended first (it is reaped)
  kTimedOut,  // still running, not ready
};

// Polls `ready` every 50 ms until it holds, child `pid` exits, or `timeout`
// passes.
inline ChildReadiness WaitUntilChildReady(pid_t pid, std::chrono::milliseconds timeout,
                                          const std::function<bool()>& ready) {
  constexpr std::chrono::milliseconds kPoll{50};
  const auto give_up = std::chrono::steady_clock::now() + timeout;
  while (true) {
    if (ready()) return ChildReadiness::kReady;
    int status = 0;
    if (waitpid(pid, &status, WNOHANG) == pid) return ChildReadiness::kExited;
    if (std::chrono::steady_clock::now() >= give_up) return ChildReadiness::kTimedOut;
    std::this_thread::sleep_for(kPoll);
  }
}

}  // namespace seaplan::testing
