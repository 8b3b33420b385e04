// Runs a piece of work in a forked child process, so that a crash, a hang or
// a memory bomb inside it — a third-party file reader on a malformed file —
// ends the child and not relight. The child hands back what it made as bytes.
#pragma once

#include <chrono>
#include <cstdint>
#include <functional>
#include <string>

namespace relight {

struct ChildLimits {
  std::chrono::seconds time{60};
  // Address space the child may take beyond what it shares with the parent
  // at the fork (RLIMIT_AS is set to the parent's size plus this); 0: none.
  uint64_t memory_bytes = 0;
};

struct ChildResult {
  bool ok = false;
  bool cancelled = false;  // cancelled() said so while the child ran; the child was killed
  std::string bytes;       // what work() returned, when ok
  std::string failure;     // otherwise: "crashed (signal 11)", "did not finish within 60 s", ...
};

// Forks; the child runs work() and writes its result back through a pipe.
// The child is killed once limits.time has passed, or as soon as cancelled()
// returns true (polled every 50 ms and on every signal the parent takes, so
// a Ctrl-C ends the wait at once). The child dies with its parent, ignores
// the terminal's Ctrl-C (the parent decides), and holds no descriptor of the
// parent's pipes beyond its own end.
ChildResult run_in_child(const std::function<std::string()>& work, const ChildLimits& limits,
                         const std::function<bool()>& cancelled = {});

}  // namespace relight
