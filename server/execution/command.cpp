#include "execution/command.hpp"

#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>

extern char** environ;

namespace rupture::server {

namespace {

/// The shared body: `timeout` kills with SIGKILL; `watch` (optional) asks for SIGTERM.
CommandResult runProgram(const std::vector<std::string>& argv, std::chrono::milliseconds timeout,
                         const std::function<bool()>& watch, std::size_t keepErrorBytes) {
  CommandResult result;
  if (argv.empty()) {
    result.error = "no command";
    return result;
  }
  int out[2], err[2];
  if (::pipe2(out, O_CLOEXEC) != 0) {
    result.error = std::string("pipe: ") + std::strerror(errno);
    return result;
  }
  if (::pipe2(err, O_CLOEXEC) != 0) {
    ::close(out[0]);
    ::close(out[1]);
    result.error = std::string("pipe: ") + std::strerror(errno);
    return result;
  }
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_adddup2(&actions, out[1], STDOUT_FILENO);
  posix_spawn_file_actions_adddup2(&actions, err[1], STDERR_FILENO);
  posix_spawn_file_actions_addopen(&actions, STDIN_FILENO, "/dev/null", O_RDONLY, 0);
  std::vector<char*> args;
  for (const std::string& a : argv) args.push_back(const_cast<char*>(a.c_str()));
  args.push_back(nullptr);
  pid_t pid = -1;
  const int spawned = ::posix_spawnp(&pid, args[0], &actions, nullptr, args.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  ::close(out[1]);
  ::close(err[1]);
  if (spawned != 0) {
    ::close(out[0]);
    ::close(err[0]);
    result.error = "cannot run " + argv[0] + ": " + std::strerror(spawned);
    return result;
  }
  const auto deadline = std::chrono::steady_clock::now() + timeout;
  // Asked to stop (watch said so): SIGTERM once, SIGKILL at termDeadline.
  bool terminated = false;
  std::chrono::steady_clock::time_point killDeadline{};
  constexpr auto kWatchPeriod = std::chrono::milliseconds(200);
  constexpr auto kTermGrace = std::chrono::seconds(10);
  pollfd fds[2] = {{out[0], POLLIN, 0}, {err[0], POLLIN, 0}};
  std::string* sinks[2] = {&result.output, &result.error};
  int open = 2;
  bool timedOut = false;
  while (open > 0) {
    const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(deadline - std::chrono::steady_clock::now());
    if (left.count() <= 0) {
      timedOut = true;
      break;
    }
    const auto slice = watch ? std::min(left, std::chrono::duration_cast<std::chrono::milliseconds>(kWatchPeriod)) : left;
    if (::poll(fds, 2, static_cast<int>(slice.count())) < 0 && errno != EINTR) break;
    if (watch) {
      const auto now = std::chrono::steady_clock::now();
      if (!terminated && watch()) {
        ::kill(pid, SIGTERM);
        terminated = true;
        killDeadline = now + kTermGrace;
      } else if (terminated && now > killDeadline) {
        ::kill(pid, SIGKILL);
        killDeadline = now + std::chrono::hours(24);
      }
    }
    for (int i = 0; i < 2; ++i) {
      if (fds[i].fd < 0 || (fds[i].revents & (POLLIN | POLLHUP | POLLERR)) == 0) continue;
      char buffer[4096];
      const ssize_t n = ::read(fds[i].fd, buffer, sizeof buffer);
      if (n > 0) {
        sinks[i]->append(buffer, static_cast<std::size_t>(n));
        if (i == 1 && result.error.size() > 2 * keepErrorBytes) result.error.erase(0, result.error.size() - keepErrorBytes);
      } else if (n == 0 || errno != EINTR) {
        ::close(fds[i].fd);
        fds[i].fd = -1;
        --open;
      }
    }
  }
  for (pollfd& f : fds)
    if (f.fd >= 0) ::close(f.fd);
  if (timedOut) ::kill(pid, SIGKILL);
  int status = 0;
  while (::waitpid(pid, &status, 0) < 0 && errno == EINTR) {
  }
  if (timedOut) {
    result.error += "\n" + argv[0] + ": timed out after " + std::to_string(timeout.count()) + " ms";
    return result;
  }
  result.exitCode = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return result;
}

}  // namespace

CommandResult runCommand(const std::vector<std::string>& argv, std::chrono::milliseconds timeout) {
  return runProgram(argv, timeout, {}, std::string::npos / 4);
}

CommandResult runWatchedCommand(const std::vector<std::string>& argv, const std::function<bool()>& watch,
                                std::size_t keepErrorBytes) {
  return runProgram(argv, std::chrono::hours(24 * 365 * 100), watch, keepErrorBytes);
}

}  // namespace rupture::server
