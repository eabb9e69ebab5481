// The per-texture zone split of Wang et al. 2007: t1 of eq. 3 and (s1, s2) of eq. 6.
//
//   linear (default)  the paper's search: minimise eq. 2, E(t1) = n_l(t1) (t1 - tmin) / 2^b_l + n_h(t1) (tmax - t1) /
//                     2^b_h with b_l = b_h = 8 (both zones are 8-bit alpha channels, so the bits do not move the
//                     minimum). Between two consecutive sample values E is linear in t1, so the minimum over all t1
//                     is at a sample value: the search visits every distinct luminance (exact, O(n log n)). For S the
//                     same with three zones and 5/6/5 bits (tex1.r, tex1.g, tex1.b), over 513 quantiles of S for
//                     each of s1 <= s2 (the paper: "an optimization procedure similar to Equation 2").
//   <solver>          any solver of the library (solvers/registry.h) on the zone quantisation error of
//                     wang_zone_problem.h (the error the split actually causes, not eq. 2's proxy), started from the
//                     linear answer, on a lattice of 4097 (t1) / 1025 x 1025 (s1, s2) split fractions; the samples
//                     are at most 16384 texels taken at a fixed stride, each weighted by the stride.
// Both results record eq. 2 (resp. its 3-zone analogue) and the quantisation error at the chosen split, over the
// same samples.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "solvers/solver.h"

namespace blocklab {
namespace wang {

struct SplitSearch {
  std::string solver = "linear";   // "linear" or a registered solver name
  SolverOptions options;           // that solver's options (resolved by the solver)
  std::uint64_t seed = 1;
};

struct SplitResult {
  double low = 0.0, high = 0.0;       // the range: min and max of the values
  std::vector<double> split;          // t1, or s1 <= s2
  double eq2 = 0.0;                   // eq. 2 (or its 3-zone analogue) at the split
  double quantisation = 0.0;          // the zone quantisation error (wang_zone_problem.h) at the split
};

// t1 for the luminances, with per-texel weights 1 / (L + c) for the quantisation error.
SplitResult fit_luminance_split(const std::vector<double>& luminances, const std::vector<double>& weights,
                                const SplitSearch& search);
// (s1, s2) for the residuals (S or T) with per-texel weights (1 / (L + c), or L' / (L + c) for T).
SplitResult fit_residual_split(const std::vector<double>& residuals, const std::vector<double>& weights,
                               const SplitSearch& search);

// Throws Error("<who>: option '<key>': ...") unless `name` is "linear" or a registered solver.
void check_split_solver_name(const std::string& name, const std::string& key, const std::string& who);

}  // namespace wang
}  // namespace blocklab
