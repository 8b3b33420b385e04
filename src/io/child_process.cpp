#include "io/child_process.h"

#include <poll.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <csignal>
#include <cstring>

namespace relight {

namespace {

// Writes everything or gives up (the parent has gone).
void write_all(int fd, const std::string& bytes) {
  size_t done = 0;
  while (done < bytes.size()) {
    const ssize_t n = ::write(fd, bytes.data() + done, bytes.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) return;
    done += size_t(n);
  }
}

}  // namespace

ChildResult run_in_child(const std::function<std::string()>& work, std::chrono::seconds timeout) {
  ChildResult result;
  int fds[2];
  if (::pipe(fds) != 0) {
    result.failure = std::string("could not start (pipe: ") + std::strerror(errno) + ")";
    return result;
  }
  const pid_t pid = ::fork();
  if (pid < 0) {
    ::close(fds[0]);
    ::close(fds[1]);
    result.failure = std::string("could not start (fork: ") + std::strerror(errno) + ")";
    return result;
  }
  if (pid == 0) {
    // The child: no exception, exit handler or leak check of the parent's
    // may run here, hence _exit; a crash ends it quietly (no sanitizer or
    // fuzzer report of its own), for the parent to report.
    for (const int sig : {SIGSEGV, SIGBUS, SIGFPE, SIGILL, SIGABRT}) ::signal(sig, SIG_DFL);
    ::close(fds[0]);
    int status = 0;
    try {
      write_all(fds[1], work());
    } catch (...) {
      status = 3;
    }
    ::close(fds[1]);
    ::_exit(status);
  }

  ::close(fds[1]);
  const auto deadline = std::chrono::steady_clock::now() + timeout;
  char buffer[1 << 16];
  bool timed_out = false;
  for (;;) {
    const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(deadline - std::chrono::steady_clock::now());
    if (left.count() <= 0) {
      timed_out = true;
      break;
    }
    pollfd p{fds[0], POLLIN, 0};
    const int ready = ::poll(&p, 1, int(std::min<long long>(left.count(), 1000)));
    if (ready < 0 && errno != EINTR) break;
    if (ready <= 0) continue;
    const ssize_t n = ::read(fds[0], buffer, sizeof buffer);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) break;  // end of the child's output
    result.bytes.append(buffer, size_t(n));
  }
  ::close(fds[0]);
  if (timed_out) ::kill(pid, SIGKILL);
  int status = 0;
  while (::waitpid(pid, &status, 0) < 0 && errno == EINTR) {
  }
  if (timed_out) {
    result.failure = "did not finish within " + std::to_string(timeout.count()) + " s";
  } else if (WIFSIGNALED(status)) {
    result.failure = "crashed (signal " + std::to_string(WTERMSIG(status)) + ")";
  } else if (!WIFEXITED(status) || WEXITSTATUS(status) != 0) {
    result.failure = "failed (exit status " + std::to_string(WEXITSTATUS(status)) + ")";
  } else {
    result.ok = true;
  }
  return result;
}

}  // namespace relight
