// The working buffers of one `procrustes` solve (procrustes_solver.h), owned by the caller instead of hidden in
// per-thread statics (the working-buffer model of astcenc: one workspace per worker thread, passed down). A block
// loop keeps one per worker and passes it to every solve on that worker, so a solve allocates nothing once the
// buffers have grown to the block's size; a solve given none makes its own. Contents never carry information from
// one solve to the next: every buffer is cleared or overwritten before it is read.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "core/problem.h"
#include "solvers/procrustes/point_clustering.h"
#include "solvers/procrustes/procrustes_refinement.h"
#include "solvers/procrustes/procrustes_screening.h"
#include "solvers/procrustes/start_error_screening.h"

namespace blocklab {

// A candidate's sort key: its bound and its enumeration index (the tie-break that makes the order strict).
struct CandidateKey {
  double bound;
  std::size_t index;
};

// The buffers of the refinement of ranked candidates: the mapped targets (all u values, then all v values), the
// duplicate keys and the per-point nearest-landmark scratch (procrustes_refinement.h).
struct RefinementBuffers {
  std::vector<double> targets;
  std::vector<std::uint64_t> seen;
  std::vector<int> nearest, next_nearest;
};

struct ProcrustesWorkspace {
  std::vector<PointClustering> levels;            // step 1: the cluster levels
  std::vector<ProcrustesCandidate> candidates;    // step 2: every candidate, then the ranked list
  std::vector<ProcrustesCandidate> unsorted;      // step 3: the candidates before the stable sort
  std::vector<CandidateKey> keys;                 // step 3: the sort keys
  RefinementBuffers refinement;                   // step 3: the refinement (search=ranked)
  ScreeningBuffers screening;                     // step 3: search=screened
  StartErrorBuffers start_error;                  // step 3: search=start_error
  std::vector<std::array<double, kLandmarkFitParameterCount>> snapped;   // step 4: the points evaluated so far
};

}  // namespace blocklab
