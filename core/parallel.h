// Deterministic parallel loops over blocks (oneTBB).
//
// Every iteration writes only its own output slot, so the result does not depend on the scheduling; reductions
// are done afterwards in index order by the caller. `threads` = 0 means all hardware threads.
#pragma once

#include <cstddef>
#include <functional>

namespace blocklab {

int resolve_thread_count(int threads);   // 0 -> hardware concurrency, otherwise threads (must be >= 1)

// Calls body(i) for i in [0, count) on up to `threads` threads.
void parallel_for_index(std::size_t count, int threads, const std::function<void(std::size_t)>& body);

// The number of workers parallel_for_worker_index runs with for `threads` (resolve_thread_count, capped by TBB's
// allowed parallelism): worker indices are in [0, parallel_worker_count(threads)).
int parallel_worker_count(int threads);
// Calls body(i, worker) for i in [0, count) on up to `threads` threads, `worker` naming the thread that runs it: no
// two calls with the same worker index run at once, so state kept per worker index (a workspace of scratch buffers,
// astcenc's working-buffer model) needs no lock. Which worker runs which i depends on the scheduling, so such state
// must never change a result (buffers cleared before use).
void parallel_for_worker_index(std::size_t count, int threads, const std::function<void(std::size_t, int)>& body);

}  // namespace blocklab
