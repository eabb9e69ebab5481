// The local cell dispatcher (contract in experiments/cell_dispatch.h): every cell in this process, in order.
#include "experiments/cell_dispatch.h"

#include <cstdlib>

namespace blocklab {

namespace {

int environment_count(const char* name) {
  const char* value = std::getenv(name);
  if (value == nullptr || *value == '\0') return -1;
  char* end = nullptr;
  const long count = std::strtol(value, &end, 10);
  return (*end == '\0' && count > 0 && count < (1L << 30)) ? static_cast<int>(count) : -1;
}

}  // namespace

void CellDispatcher::run_cells(const std::vector<std::size_t>& pending, const CellRunner& run_cell,
                               const CellEvents& events) {
  for (const std::size_t cell : pending) {
    if (events.on_started) events.on_started(cell, 0);
    const CellStatus status = run_cell(cell);
    if (events.on_finished) events.on_finished(cell, 0, status);
  }
}

int mpi_launcher_process_count() {
  for (const char* name : {"OMPI_COMM_WORLD_SIZE", "PMI_SIZE"}) {
    const int count = environment_count(name);
    if (count > 0) return count;
  }
  // PMIx (srun --mpi=pmix, Open MPI 5) names only the rank: rank r means at least r + 1 processes.
  for (const char* name : {"PMIX_RANK", "PMI_RANK"}) {
    if (std::getenv(name) == nullptr) continue;
    const int rank = environment_count(name);
    return rank > 0 ? rank + 1 : 1;
  }
  return 0;
}

}  // namespace blocklab
