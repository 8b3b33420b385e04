// The child process that runs third-party readers (src/io/child_process.h):
// its pipe is close-on-exec, it dies with its parent, it runs into its
// memory limit instead of taking the machine's, and a cancellation (a
// Ctrl-C) ends the wait and the child at once.
#include "io/child_process.h"
#include "sanitizer.h"

#include <fcntl.h>
#include <gtest/gtest.h>
#include <sys/prctl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <atomic>
#include <csignal>
#include <cstring>
#include <filesystem>
#include <set>
#include <string>
#include <thread>
#include <vector>

namespace relight {
namespace {

namespace fs = std::filesystem;
using test::kAddressSanitizer;

ChildLimits seconds(int s) {
  ChildLimits limits;
  limits.time = std::chrono::seconds(s);
  return limits;
}

TEST(ChildProcess, HandsBackWhatItsWorkReturns) {
  const ChildResult r = run_in_child([] { return std::string("mesh bytes"); }, seconds(60));
  EXPECT_TRUE(r.ok) << r.failure;
  EXPECT_EQ(r.bytes, "mesh bytes");
}

// The descriptors of the pipes this process holds.
std::set<int> pipe_descriptors() {
  std::set<int> fds;
  for (const auto& entry : fs::directory_iterator("/proc/self/fd")) {
    std::error_code ec;
    if (fs::read_symlink(entry.path(), ec).string().rfind("pipe:", 0) == 0)
      fds.insert(std::stoi(entry.path().filename().string()));
  }
  return fds;
}

// In the child, the pipes it holds beyond those the test process had before
// (its end of the result pipe) must be close-on-exec: a program started
// meanwhile would otherwise keep the pipe open and the parent waiting.
TEST(ChildProcess, ItsPipeIsCloseOnExec) {
  const std::set<int> before = pipe_descriptors();
  const ChildResult r = run_in_child(
      [&] {
        std::string flags;
        for (const int fd : pipe_descriptors())
          if (!before.contains(fd)) flags += (::fcntl(fd, F_GETFD) & FD_CLOEXEC) ? 'c' : 'o';
        return flags;
      },
      seconds(60));
  ASSERT_TRUE(r.ok) << r.failure;
  ASSERT_FALSE(r.bytes.empty()) << "the child holds no pipe of its own";
  EXPECT_EQ(r.bytes.find('o'), std::string::npos) << "a pipe without close-on-exec: " << r.bytes;
}

// A process that runs a child which never ends is killed; the child must die
// with it (it is reparented to this test, a subreaper, which reaps it).
TEST(ChildProcess, DiesWithItsParent) {
  ASSERT_EQ(::prctl(PR_SET_CHILD_SUBREAPER, 1), 0);
  int pids[2];
  ASSERT_EQ(::pipe(pids), 0);
  const pid_t parent = ::fork();
  ASSERT_GE(parent, 0);
  if (parent == 0) {
    ::close(pids[0]);
    run_in_child(
        [&] {
          const pid_t self = ::getpid();
          [[maybe_unused]] const ssize_t n = ::write(pids[1], &self, sizeof self);
          for (;;) ::pause();
          return std::string();
        },
        seconds(600));
    ::_exit(0);
  }
  ::close(pids[1]);
  pid_t child = 0;
  ASSERT_EQ(::read(pids[0], &child, sizeof child), ssize_t(sizeof child));
  ::close(pids[0]);
  ::kill(parent, SIGKILL);
  int status = 0;
  ASSERT_EQ(::waitpid(parent, &status, 0), parent);
  // The orphan comes to this process; without PR_SET_PDEATHSIG it would
  // pause for ever (the test then fails on its ctest timeout).
  ASSERT_EQ(::waitpid(child, &status, 0), child);
  EXPECT_TRUE(WIFSIGNALED(status) && WTERMSIG(status) == SIGKILL) << "status " << status;
}

TEST(ChildProcess, RunsIntoItsMemoryLimit) {
  if (kAddressSanitizer) GTEST_SKIP() << "AddressSanitizer's allocator reports and aborts on a failed allocation";
  ChildLimits limits = seconds(60);
  limits.memory_bytes = uint64_t(256) << 20;
  const ChildResult r = run_in_child(
      [] {
        std::vector<char> big(size_t(4) << 30, 1);  // 4 GiB, touched
        return std::string(1, big[12345]);
      },
      limits);
  EXPECT_FALSE(r.ok);
  EXPECT_EQ(r.failure, "ran out of its memory limit (256 MB)");
}

TEST(ChildProcess, WorkWithinItsMemoryLimitIsDone) {
  ChildLimits limits = seconds(60);
  limits.memory_bytes = uint64_t(256) << 20;
  const ChildResult r = run_in_child(
      [] {
        std::vector<char> some(size_t(64) << 20, 1);
        return std::to_string(some.size());
      },
      limits);
  EXPECT_TRUE(r.ok) << r.failure;
  EXPECT_EQ(r.bytes, std::to_string(size_t(64) << 20));
}

std::atomic<bool> g_interrupted{false};
void on_interrupt(int) { g_interrupted = true; }

// As the command line does: SIGINT sets a flag the wait polls. The child
// never finishes on its own (600 s limit): the wait must end with the
// cancellation, the child killed.
TEST(ChildProcess, ACtrlCInTheParentEndsTheWaitAndTheChild) {
  struct sigaction action {};
  action.sa_handler = on_interrupt;
  struct sigaction previous {};
  ASSERT_EQ(::sigaction(SIGINT, &action, &previous), 0);
  g_interrupted = false;
  const pid_t self = ::getpid();
  std::thread interrupt([self] {
    std::this_thread::sleep_for(std::chrono::milliseconds(200));
    ::kill(self, SIGINT);
  });
  const ChildResult r = run_in_child(
      [] {
        for (;;) ::pause();
        return std::string();
      },
      seconds(600), [] { return g_interrupted.load(); });
  interrupt.join();
  ::sigaction(SIGINT, &previous, nullptr);
  EXPECT_TRUE(r.cancelled);
  EXPECT_FALSE(r.ok);
  EXPECT_EQ(r.failure, "was cancelled");
}

}  // namespace
}  // namespace relight
