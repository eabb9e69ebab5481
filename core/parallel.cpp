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

void parallel_for_index(std::size_t count, int threads, const std::function<void(std::size_t)>& body) {
  int n = resolve_thread_count(threads);
  // More threads than TBB allows (hardware threads, or a tbb::global_control limit) would only make TBB print a
  // warning; results never depend on the count, so asking for fewer is safe.
  const auto allowed = tbb::global_control::active_value(tbb::global_control::max_allowed_parallelism);
  if (static_cast<std::size_t>(n) > allowed) n = static_cast<int>(allowed);
  if (n == 1 || count < 2) {
    for (std::size_t i = 0; i < count; ++i) body(i);
    return;
  }
  tbb::task_arena arena(n);
  arena.execute([&] {
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, count), [&](const tbb::blocked_range<std::size_t>& r) {
      for (std::size_t i = r.begin(); i != r.end(); ++i) body(i);
    });
  });
}

}  // namespace blocklab
