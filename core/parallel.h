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

}  // namespace blocklab
