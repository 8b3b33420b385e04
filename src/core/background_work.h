// Work in the background of an interactive picture (relight studio's full
// analysis behind its preview, an export's final render): it takes the
// cores the picture leaves.
#pragma once

#include <functional>

namespace relight {

// Runs `work` on this thread so that the interactive renders go first: the
// thread at a lower OS priority (nice 10, and kept so: lowering it back
// needs a privilege, so the thread should serve only such work) and the
// work's parallel loops in a low-priority TBB arena, so that TBB's worker
// threads take the interactive renders' tasks first whenever both have work.
void run_giving_way(const std::function<void()>& work);

}  // namespace relight
