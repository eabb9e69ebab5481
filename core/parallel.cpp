#include "core/parallel.h"

#include <tbb/blocked_range.h>
#include <tbb/global_control.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <thread>

#include "core/error.h"

namespace blocklab {

int resolve_thread_count(int threads) {
  if (threads < 0) fail("threads", "must be >= 0 (0 = all hardware threads), got " + std::to_string(threads));
  if (threads == 0) {
    const unsigned hw = std::thread::hardware_concurrency();
    return hw == 0 ? 1 : static_cast<int>(hw);
  }
  return threads;
}

int parallel_worker_count(int threads) {
  const int n = resolve_thread_count(threads);
  // More threads than TBB allows (hardware threads, or a tbb::global_control limit) would only make TBB print a
  // warning; results never depend on the count, so asking for fewer is safe.
  const auto allowed = tbb::global_control::active_value(tbb::global_control::max_allowed_parallelism);
  return static_cast<std::size_t>(n) > allowed ? static_cast<int>(allowed) : n;
}

void parallel_for_worker_index(std::size_t count, int threads, const std::function<void(std::size_t, int)>& body) {
  const int n = parallel_worker_count(threads);
  if (n == 1 || count < 2) {
    for (std::size_t i = 0; i < count; ++i) body(i, 0);
    return;
  }
  tbb::task_arena arena(n);
  arena.execute([&] {
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, count), [&](const tbb::blocked_range<std::size_t>& r) {
      // The thread's slot in this arena of n slots: in [0, n), and held by one thread at a time.
      const int worker = tbb::this_task_arena::current_thread_index();
      for (std::size_t i = r.begin(); i != r.end(); ++i) body(i, worker);
    });
  });
}

void parallel_for_index(std::size_t count, int threads, const std::function<void(std::size_t)>& body) {
  parallel_for_worker_index(count, threads, [&](std::size_t i, int) { body(i); });
}

}  // namespace blocklab
