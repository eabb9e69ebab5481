// The per-worker parallel loop of core/parallel.h (parallel_for_worker_index), which the block loop's workspace
// overload (formats/common/block_codec.h) relies on: every index runs once, worker indices stay below
// parallel_worker_count, and no two bodies with the same worker index run at the same time.
#include <gtest/gtest.h>

#include <atomic>
#include <cstddef>
#include <thread>
#include <vector>

#include "core/parallel.h"

namespace blocklab {
namespace {

TEST(ParallelWorkers, EveryIndexRunsOnceOnAWorkerBelowTheCount) {
  for (const int threads : {1, 2, 4}) {
    const int workers = parallel_worker_count(threads);
    ASSERT_GE(workers, 1);
    ASSERT_LE(workers, threads);
    constexpr std::size_t kCount = 2000;
    std::vector<std::atomic<int>> runs(kCount);
    std::vector<std::atomic<int>> busy(static_cast<std::size_t>(workers));
    std::atomic<int> out_of_range{0}, shared{0};
    parallel_for_worker_index(kCount, threads, [&](std::size_t i, int worker) {
      ++runs[i];
      if (worker < 0 || worker >= workers) {
        ++out_of_range;
        return;
      }
      // A second body on the same worker index while this one runs would find the flag set.
      if (busy[static_cast<std::size_t>(worker)].exchange(1) != 0) ++shared;
      std::this_thread::yield();
      busy[static_cast<std::size_t>(worker)] = 0;
    });
    for (std::size_t i = 0; i < kCount; ++i) EXPECT_EQ(runs[i].load(), 1) << "index " << i;
    EXPECT_EQ(out_of_range.load(), 0) << threads << " threads";
    EXPECT_EQ(shared.load(), 0) << threads << " threads";
  }
}

TEST(ParallelWorkers, OneThreadRunsInIndexOrderOnWorkerZero) {
  std::vector<std::size_t> order;
  parallel_for_worker_index(5, 1, [&](std::size_t i, int worker) {
    EXPECT_EQ(worker, 0);
    order.push_back(i);
  });
  EXPECT_EQ(order, (std::vector<std::size_t>{0, 1, 2, 3, 4}));
}

}  // namespace
}  // namespace blocklab
