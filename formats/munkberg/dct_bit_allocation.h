// Bit allocation of the fixed-rate DCT mode (Munkberg et al. 2008, section 6.2: "These estimated variances were used
// to find a bit allocation table that minimizes the average reconstruction error using Lagrange minimization
// [Den69, Say96]"). Discrete Lagrangian form (Everett 1963; Shoham and Gersho 1988): for a multiplier lambda every
// coefficient independently takes argmin_b D_k(b) + lambda b; the rate falls as lambda grows, so a bisection finds
// the largest allocation within the budget, which is optimal among allocations of its own rate (it lies on the
// lower convex hull of every D_k); the few bits left below the budget go, one step at a time, to the step with the
// largest distortion decrease per bit that still fits.
#pragma once

#include <vector>

namespace blocklab::munkberg {

// distortion[k][b]: the expected squared error of coefficient k with b bits (b = 0 .. distortion[k].size() - 1).
// Returns bits[k] with sum exactly `budget` (Error if the budget exceeds every coefficient's maximum together).
// Ties go to the lower coefficient index, so the result is deterministic.
std::vector<int> lagrangian_bit_allocation(const std::vector<std::vector<double>>& distortion, int budget);

// The exact constrained optimum of the same problem (dynamic programming over coefficients and spent bits; ties to
// the lexicographically smallest allocation from coefficient 0): the reference the Lagrangian allocation is measured
// against (tests; the training uses the paper's Lagrangian method).
std::vector<int> exact_bit_allocation(const std::vector<std::vector<double>>& distortion, int budget);

}  // namespace blocklab::munkberg
