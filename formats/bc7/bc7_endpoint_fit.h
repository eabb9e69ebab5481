// Endpoint fitting for one BC7 subset: principal axis (PCA) start, quantisation to the mode's lattice with P-bit
// choice, index assignment on the decoded palette, and least-squares endpoint refinement with index
// re-assignment (the classic "cluster fit" loop of BC7 encoders; cf. Castano, NVTT BC7 / Waveren "Real-Time DXT
// Compression" for the PCA start, and SPECS.md 2.5 item 4 for P-bits in the error).
//
// This is the builtin closed-form path. The same subset problem is also available as a core/problem.h Problem
// (bc7_endpoint_problem.h) so that the solver library can replace the least-squares step.
#pragma once

#include <cstdint>

#include "formats/bc7/bc7_quantise.h"

namespace blocklab {
namespace bc7 {

struct SubsetFitSettings {
  int index_bits = 2;                  // 2, 3 or 4
  EndpointLattice lattice;
  float weights[4] = {1, 1, 1, 1};     // per-lane error weights (0 for lanes that do not count)
  int refine_iterations = 2;           // least-squares refinement rounds after the PCA start
  bool pbit_search = true;             // try every P-bit combination on the final endpoints
  int polish_passes = 0;               // lattice polish passes on the result (bc7_endpoint_polish.h)
};

struct SubsetFit {
  QuantisedEndpoints endpoints;
  std::uint8_t indices[16] = {};       // index of each member texel, in the order the texels were given
  float error = 0.0f;                  // weighted squared error of the decoded subset
};

// Fits the `count` (1..16) member texels texels[i][lane] (values 0..255).
SubsetFit fit_subset(const float (*texels)[4], int count, const SubsetFitSettings& settings);

// Assigns the best index to each texel for the quantised endpoints (decoded palette, exact interpolation) and
// returns the weighted squared error.
float assign_indices(const float (*texels)[4], int count, const QuantisedEndpoints& endpoints, int index_bits,
                     const float weights[4], std::uint8_t* indices);

// Least-squares endpoints for fixed indices: minimises sum_i (x_i - ((1 - f_i) E0 + f_i E1))^2 per lane with
// f_i = weight(index_i) / 64, clamped to [0, 255]. Returns false (endpoints untouched) when all texels use the
// same weight (the system is singular).
bool least_squares_endpoints(const float (*texels)[4], int count, const std::uint8_t* indices, int index_bits,
                             float (&ideal)[2][4]);

// Swaps the two endpoints and mirrors the indices (i -> 2^bits - 1 - i): decodes to exactly the same texels,
// because the weight tables are symmetric (w[2^b - 1 - i] = 64 - w[i]). Used to give an anchor index MSB 0.
void swap_endpoints(SubsetFit& fit, int index_bits, int count);

}  // namespace bc7
}  // namespace blocklab
