#include "core/background_work.h"

#include <sys/resource.h>
#include <tbb/task_arena.h>
#include <unistd.h>

namespace relight {

void run_giving_way(const std::function<void()>& work) {
  // Linux gives each thread its own nice value, set by the thread's id.
  constexpr int kNice = 10;
  const auto thread = id_t(gettid());
  if (getpriority(PRIO_PROCESS, thread) < kNice) setpriority(PRIO_PROCESS, thread, kNice);
  tbb::task_arena arena(tbb::task_arena::automatic, 1, tbb::task_arena::priority::low);
  arena.execute(work);
}

}  // namespace relight
