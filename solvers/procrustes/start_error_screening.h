// The `start_error` candidate search of the `procrustes` solver (option search=start_error; procrustes_solver.h
// step 3; "Practical HDR Texture Compression" (2008) section 7.1, eqs. 12-15, with the clamp and the stretch of section
// 7.2).
//
// Which candidates to refine: docs/solver-bench.md measured, on 200 certified blocks per image and error kind, that
// the start error of a candidate predicts what it becomes after the clamp-aware refinement far better than the
// Procrustes bound does. The best of 6 candidates refined by start error is about as close to the optimum as the
// best of 12 refined by bound: closer for the linear error, within 1 % for the stretched one. The start error is the
// refinement measure (RefineMeasure, procrustes_refinement.h) at the candidate's base points clamped to [0, 1]^4:
// sum_i w_i min_k |f(p_i) - f(clamp(L_k(x)))|^2, the stretch f of the stretched error included.
// Measuring it for all ~61 candidates must cost less than the refinements it saves, so it runs in single precision,
// four points per SSE2 register: it only orders candidates; the refinement and the Problem's own error (step 4)
// stay in double. Deterministic: the same operations in the same order on every machine (SSE2 is baseline x86-64,
// IEEE single precision, no fast-math); a portable scalar loop does the same operations elsewhere.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "solvers/procrustes/procrustes_refinement.h"

namespace blocklab {

// The mapped points and weights in the kernel's layout: single precision, padded to a multiple of 4 points with
// weight 0 (a padded point adds 0 x its distance; its coordinates are 0, so the distance is finite).
struct StartErrorPoints {
  std::vector<float> u, v, weight;   // 4 * quads entries each
  std::size_t quads = 0;

  // `targets` as RefineMeasure expects them (all mapped u, then all mapped v); weights.size() points.
  void assign(const std::vector<double>& targets, const std::vector<double>& weights);
};

// The working buffers of refine_by_start_error (owned by the caller, e.g. ProcrustesWorkspace; cleared before use).
struct StartErrorBuffers {
  StartErrorPoints packed;                    // the targets in single precision
  std::vector<std::uint64_t> order_keys;      // per candidate: start_error_key
  std::vector<ProcrustesCandidate> chosen;    // the refined candidates so far
  std::vector<std::uint64_t> seen;            // duplicate keys of the refinement
  std::vector<int> nearest, next_nearest;     // per point: the refinement's assignment scratch
};

// The start error of a candidate (header comment) in single precision. NaN when a coordinate or weight is NaN
// (the caller orders NaN last).
float candidate_start_error(const StartErrorPoints& points, const RefineMeasure& measure, const LandmarkRows& rows,
                            const ProcrustesCandidate& candidate);
// The same without SSE2, operation for operation (the kernel where SSE2 is missing; a test checks both agree bit for
// bit).
float candidate_start_error_portable(const StartErrorPoints& points, const RefineMeasure& measure,
                                     const LandmarkRows& rows, const ProcrustesCandidate& candidate);

// The order in which candidates are refined: ascending start error, ties by index, NaN after every number (and
// after +inf). start_error_key packs both into one integer that compares in that order (index < 2^32 - 1).
std::uint64_t start_error_key(float start_error, std::size_t index);
// A taken candidate's key: larger than every key start_error_key gives.
constexpr std::uint64_t kTakenStartErrorKey = ~std::uint64_t{0};
// The index of the smallest key not yet taken, whose key becomes kTakenStartErrorKey; keys.size() when every one is
// taken. A refinement takes ~5 of ~61 candidates, so one scan per take is cheaper than sorting all keys.
std::size_t take_lowest_start_error(std::vector<std::uint64_t>& keys);

// The whole search=start_error step: every candidate's start error, then the lowest ones refined
// (refine_procrustes_candidate, `iterations` rounds) until `refined` distinct ones are; a duplicate (same first
// assignment and clamp pattern as an earlier one) does not count. `candidates` is replaced by the refined ones, in
// the order taken. Without refinement (refined = 0 or iterations = 0) it keeps the max(1, refined) lowest start
// points as they are. `targets` as RefineMeasure expects them; `buffers` is the caller's scratch.
void refine_by_start_error(const std::vector<double>& targets, const std::vector<double>& weights,
                           const RefineMeasure& measure, const LandmarkCoefficients& landmarks, int refined,
                           int iterations, std::vector<ProcrustesCandidate>& candidates, StartErrorBuffers& buffers);

}  // namespace blocklab
