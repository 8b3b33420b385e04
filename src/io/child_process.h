// Runs a piece of work in a forked child process, so that a crash or a hang
// inside it — a third-party file reader on a malformed file — ends the child
// and not relight. The child hands back what it made as bytes.
#pragma once

#include <chrono>
#include <functional>
#include <string>

namespace relight {

struct ChildResult {
  bool ok = false;
  std::string bytes;    // what work() returned, when ok
  std::string failure;  // otherwise: "crashed (signal 11)", "did not finish within 60 s", ...
};

// Forks; the child runs work() and writes its result back through a pipe.
// The child is killed once `timeout` has passed.
ChildResult run_in_child(const std::function<std::string()>& work, std::chrono::seconds timeout);

}  // namespace relight
