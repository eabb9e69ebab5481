// Who computes the cells of a run: this process alone (LocalDispatcher), or the ranks of an MPI job
// (experiments/mpi_dispatch.cpp, compiled only with the CMake option BLOCKLAB_MPI).
//
// MPI model (`mpirun -np N blocklab run CONFIG`): rank 0 plans the run (validates the config, hashes the images,
// keys the cells, writes config.yaml / resolved.json / provenance.json and scans the cache) and sends the plan to
// every rank; each rank checks that its own expansion of the config gives the same cell keys. Rank 0 then hands the
// cells still to compute out one at a time to whichever rank asks next (cells differ in cost by 1000x, so a static
// split would leave ranks idle), and computes cells itself on a second thread while its main thread serves the
// others. Every rank writes each finished cell into the run folder's cell store exactly as a single process does
// (experiments/run_folder.h), so a killed job resumes from the store with nothing lost or duplicated; rank 0 then
// reads the store and writes results.jsonl / results.csv. A cell that fails is recorded with status "error" by
// the rank that ran it, and the others go on; an Error outside a cell (a full disk) stops the hand-out and is
// rethrown on rank 0 naming the rank and host.
// Waiting ranks poll with short sleeps instead of MPI's blocking calls, which spin a core that a rank computing
// cells on the same machine needs.
#pragma once

#include <cstddef>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "core/error.h"

namespace blocklab {

enum class CellStatus { ok, error };

// The outcome of running one cell, as a status; an Error thrown by it (not a cell failure) ends the hand-out.
using CellRunner = std::function<CellStatus(std::size_t cell)>;

// Called on rank 0 only, on its main thread, in the order things happen.
struct CellEvents {
  std::function<void(std::size_t cell, int rank)> on_started;
  std::function<void(std::size_t cell, int rank, CellStatus status)> on_finished;
};

// Thrown on ranks other than 0 when rank 0 failed before handing out cells (it reports the reason itself).
class RankZeroFailed : public Error {
 public:
  RankZeroFailed() : Error("rank 0 stopped before the cells were handed out (its error says why)") {}
};

class CellDispatcher {
 public:
  virtual ~CellDispatcher() = default;
  virtual int rank() const { return 0; }
  virtual int ranks() const { return 1; }
  virtual bool is_mpi() const { return false; }
  // For provenance and progress: "1 process" or e.g. "Open MPI v4.1.4, 4 ranks on 2 hosts (a: 2, b: 2)".
  virtual std::string description() const { return "1 process"; }

  // Rank 0 runs `produce` and every rank returns its strings. When it throws, rank 0 rethrows and the other ranks
  // throw RankZeroFailed.
  virtual std::vector<std::string> share(const std::function<std::vector<std::string>()>& produce) { return produce(); }

  // Runs `run_cell` once for every cell of `pending` (indices of the plan), spread over the ranks, and returns on
  // every rank once all are done; rank 0 throws the first Error a rank hit outside a cell.
  virtual void run_cells(const std::vector<std::size_t>& pending, const CellRunner& run_cell,
                         const CellEvents& events);

  // On a rank other than 0 of an MPI job, an error of that rank alone (e.g. it cannot read the config): prints it
  // on stderr naming the rank and host, and aborts the job so rank 0 does not wait for it. No-op otherwise.
  virtual void abort_job_for(const std::string& message) {}
};

// The dispatcher of this process: an MPI one when the build has BLOCKLAB_MPI and the process was started by an MPI
// launcher (mpirun, srun --mpi=pmix), else the local one. A build without MPI started by a launcher with more than
// one process refuses (every process would compute the whole experiment into the same folder).
// Defined in local_dispatch_factory.cpp (builds without MPI) or mpi_dispatch.cpp (BLOCKLAB_MPI): CMake links one.
std::unique_ptr<CellDispatcher> make_cell_dispatcher();

// The MPI library the build uses ("Open MPI v4.1.4, ..."), or "" when built without MPI.
std::string mpi_library_version();

// How many processes an MPI launcher started, from this process's environment: OMPI_COMM_WORLD_SIZE or PMI_SIZE
// when set, else at least rank + 1 from PMIX_RANK / PMI_RANK; 0 when no launcher variable is set.
int mpi_launcher_process_count();

}  // namespace blocklab
