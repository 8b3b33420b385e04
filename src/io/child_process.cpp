#include "io/child_process.h"

#include <fcntl.h>
#include <poll.h>
#include <sys/prctl.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <new>

namespace relight {

namespace {

// The child's exit statuses beyond 0 (done).
constexpr int kThrew = 3;
constexpr int kOutOfMemory = 4;
constexpr int kParentGone = 5;

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

// The process's address space now, in bytes (VmSize; 0 where unknown).
uint64_t address_space_bytes() {
  unsigned long long pages = 0;
  std::FILE* statm = std::fopen("/proc/self/statm", "r");
  if (!statm) return 0;
  if (std::fscanf(statm, "%llu", &pages) != 1) pages = 0;
  std::fclose(statm);
  return pages * uint64_t(::sysconf(_SC_PAGESIZE));
}

// In the child, before the work: its address space may grow by `budget`
// beyond what it inherited (the parent's libraries, heap and thread stacks,
// which differ between relight, relight-studio and a sanitizer build). An
// allocation past it fails, and a failed operator new ends the child with
// kOutOfMemory instead of throwing into a reader that might go on with
// half its data.
void limit_memory(uint64_t budget) {
  if (budget == 0) return;
  const uint64_t now = address_space_bytes();
  if (now == 0) return;
  const rlimit limit{rlim_t(now + budget), rlim_t(now + budget)};
  ::setrlimit(RLIMIT_AS, &limit);
  std::set_new_handler([] { ::_exit(kOutOfMemory); });
}

[[noreturn]] void run_child(const std::function<std::string()>& work, const ChildLimits& limits, pid_t parent,
                            int out) {
  // Killed when the parent dies (the thread that forked it, which waits for
  // it below, so the same thing); the parent may have died before this took
  // effect, leaving the child to a new parent.
  ::prctl(PR_SET_PDEATHSIG, SIGKILL);
  if (::getppid() != parent) ::_exit(kParentGone);
  // No exception, exit handler or leak check of the parent's may run here,
  // hence _exit; a crash ends it quietly (no sanitizer or fuzzer report of
  // its own), for the parent to report. A Ctrl-C reaches the whole process
  // group: the parent decides, and kills the child if it is to stop.
  for (const int sig : {SIGSEGV, SIGBUS, SIGFPE, SIGILL, SIGABRT}) ::signal(sig, SIG_DFL);
  ::signal(SIGINT, SIG_IGN);
  limit_memory(limits.memory_bytes);
  int status = 0;
  try {
    write_all(out, work());
  } catch (const std::bad_alloc&) {
    status = kOutOfMemory;
  } catch (...) {
    status = kThrew;
  }
  ::close(out);
  ::_exit(status);
}

std::string failure_of(int status, const ChildLimits& limits) {
  if (WIFSIGNALED(status)) return "crashed (signal " + std::to_string(WTERMSIG(status)) + ")";
  if (WIFEXITED(status) && WEXITSTATUS(status) == kOutOfMemory)
    return "ran out of its memory limit (" + std::to_string(limits.memory_bytes >> 20) + " MB)";
  return "failed (exit status " + std::to_string(WEXITSTATUS(status)) + ")";
}

}  // namespace

ChildResult run_in_child(const std::function<std::string()>& work, const ChildLimits& limits,
                         const std::function<bool()>& cancelled) {
  ChildResult result;
  int fds[2];
  // Close-on-exec: a program another thread starts meanwhile must not hold
  // the write end open (the parent would wait for an end that never comes).
  if (::pipe2(fds, O_CLOEXEC) != 0) {
    result.failure = std::string("could not start (pipe: ") + std::strerror(errno) + ")";
    return result;
  }
  const pid_t parent = ::getpid();
  const pid_t pid = ::fork();
  if (pid < 0) {
    ::close(fds[0]);
    ::close(fds[1]);
    result.failure = std::string("could not start (fork: ") + std::strerror(errno) + ")";
    return result;
  }
  if (pid == 0) {
    ::close(fds[0]);
    run_child(work, limits, parent, fds[1]);
  }

  ::close(fds[1]);
  const auto deadline = std::chrono::steady_clock::now() + limits.time;
  char buffer[1 << 16];
  bool timed_out = false;
  for (;;) {
    if (cancelled && cancelled()) {
      result.cancelled = true;
      break;
    }
    const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(deadline - std::chrono::steady_clock::now());
    if (left.count() <= 0) {
      timed_out = true;
      break;
    }
    // A signal (Ctrl-C) interrupts the poll: the loop then checks cancelled().
    pollfd p{fds[0], POLLIN, 0};
    const int ready = ::poll(&p, 1, int(std::min<long long>(left.count(), 50)));
    if (ready < 0 && errno != EINTR) break;
    if (ready <= 0) continue;
    const ssize_t n = ::read(fds[0], buffer, sizeof buffer);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) break;  // end of the child's output
    result.bytes.append(buffer, size_t(n));
  }
  ::close(fds[0]);
  if (timed_out || result.cancelled) ::kill(pid, SIGKILL);
  int status = 0;
  while (::waitpid(pid, &status, 0) < 0 && errno == EINTR) {
  }
  if (result.cancelled) {
    result.failure = "was cancelled";
  } else if (timed_out) {
    result.failure = "did not finish within " + std::to_string(limits.time.count()) + " s";
  } else if (WIFEXITED(status) && WEXITSTATUS(status) == 0) {
    result.ok = true;
  } else {
    result.failure = failure_of(status, limits);
  }
  return result;
}

}  // namespace relight
