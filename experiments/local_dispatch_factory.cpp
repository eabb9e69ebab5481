// make_cell_dispatcher for builds without MPI (BLOCKLAB_MPI off; experiments/cell_dispatch.h): always the local
// dispatcher, and a clear refusal when an MPI launcher started several copies of this process.
#include <cstdlib>

#include "experiments/cell_dispatch.h"

namespace blocklab {

std::unique_ptr<CellDispatcher> make_cell_dispatcher() {
  const int processes = mpi_launcher_process_count();
  if (processes > 1) {
    fail("mpirun", "this blocklab was built without MPI (CMake option BLOCKLAB_MPI; install libopenmpi-dev and "
                   "rebuild), so each of the " + std::to_string(processes) +
                   " processes would compute the whole experiment; start one process, or split the cells with "
                   "--shard i/n (docs/cluster.md)");
  }
  return std::make_unique<CellDispatcher>();
}

std::string mpi_library_version() { return ""; }

}  // namespace blocklab
