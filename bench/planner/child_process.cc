#include "child_process.h"

#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <spawn.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <fstream>

extern char** environ;

namespace seaplan::bench {
namespace {

// Resident set of `pid` in MB (0 when it is gone).
double ResidentMb(pid_t pid) {
  std::ifstream statm("/proc/" + std::to_string(pid) + "/statm");
  long pages_total = 0, pages_resident = 0;
  if (!(statm >> pages_total >> pages_resident)) return 0;
  return static_cast<double>(pages_resident) * static_cast<double>(::sysconf(_SC_PAGESIZE)) /
         (1024.0 * 1024.0);
}

}  // namespace

ChildResult RunChild(const std::vector<std::string>& args, const ChildLimits& limits,
                     const LineObserver& on_line) {
  ChildResult result;
  int out_pipe[2], err_pipe[2];
  if (::pipe2(out_pipe, O_CLOEXEC) != 0) return result;
  if (::pipe2(err_pipe, O_CLOEXEC) != 0) {
    ::close(out_pipe[0]);
    ::close(out_pipe[1]);
    return result;
  }
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, 0, "/dev/null", O_RDONLY, 0);
  posix_spawn_file_actions_adddup2(&actions, out_pipe[1], 1);
  posix_spawn_file_actions_adddup2(&actions, err_pipe[1], 2);
  std::vector<char*> argv;
  argv.reserve(args.size() + 1);  // and the terminating null
  for (const auto& a : args) argv.push_back(const_cast<char*>(a.c_str()));
  argv.push_back(nullptr);
  const auto start = std::chrono::steady_clock::now();
  auto elapsed = [&] {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  };
  pid_t pid = 0;
  const int spawn_error = posix_spawnp(&pid, argv[0], &actions, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  ::close(out_pipe[1]);
  ::close(err_pipe[1]);
  if (spawn_error != 0) {
    ::close(out_pipe[0]);
    ::close(err_pipe[0]);
    return result;
  }
  result.started = true;

  std::string partial[2];
  std::string* text[2] = {&result.out, &result.err};
  auto take = [&](int stream, const char* data, std::size_t size) {
    const double at = elapsed();
    text[stream]->append(data, size);
    partial[stream].append(data, size);
    std::size_t newline;
    while ((newline = partial[stream].find('\n')) != std::string::npos) {
      if (on_line) on_line(stream == 1, partial[stream].substr(0, newline), at);
      partial[stream].erase(0, newline + 1);
    }
  };
  pollfd fds[2] = {{out_pipe[0], POLLIN, 0}, {err_pipe[0], POLLIN, 0}};
  int open_streams = 2;
  bool killed = false;
  while (open_streams > 0) {
    ::poll(fds, 2, 10);
    for (int s = 0; s < 2; ++s) {
      if (fds[s].fd < 0 || fds[s].revents == 0) continue;
      char buffer[65536];
      const ssize_t n = ::read(fds[s].fd, buffer, sizeof buffer);
      if (n > 0) {
        take(s, buffer, static_cast<std::size_t>(n));
      } else {
        ::close(fds[s].fd);
        fds[s].fd = -1;
        --open_streams;
      }
    }
    if (killed) continue;
    const double rss = ResidentMb(pid);
    if (rss > result.peak_rss_mb) result.peak_rss_mb = rss;
    if (rss > limits.memory_limit_mb) {
      result.killed_for_memory = killed = true;
    } else if (elapsed() > limits.time_limit_s + limits.grace_s) {
      result.killed_for_time = killed = true;
    }
    if (killed) ::kill(pid, SIGKILL);
  }
  int status = 0;
  rusage usage{};
  ::wait4(pid, &status, 0, &usage);
  result.wall_s = elapsed();
  for (int s = 0; s < 2; ++s) {
    if (!partial[s].empty() && on_line) on_line(s == 1, partial[s], result.wall_s);
  }
  result.cpu_s = usage.ru_utime.tv_sec + usage.ru_utime.tv_usec / 1e6 + usage.ru_stime.tv_sec +
                 usage.ru_stime.tv_usec / 1e6;
  // ru_maxrss (KB) catches peaks between two samples.
  result.peak_rss_mb = std::max(result.peak_rss_mb, usage.ru_maxrss / 1024.0);
  if (WIFEXITED(status)) {
    result.exit_code = WEXITSTATUS(status);
  } else if (WIFSIGNALED(status)) {
    result.signal = WTERMSIG(status);
  }
  return result;
}

}  // namespace seaplan::bench
