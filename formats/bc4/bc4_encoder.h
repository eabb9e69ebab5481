// The BC4 / BC3-alpha encoder: endpoint search for one block of 16 scalar values (8-bit code units, [0, 255]).
//
// Search levels (option `search`):
//   fast        8-value mode with the block's maximum and minimum as endpoints;
//   default     in each mode: start from the range (8-value: max/min; 6-value: max/min of the texels that the
//               constants 0 and 255 do not already serve exactly), alternate optimal codes and the 1-D
//               least-squares endpoints for them (rounded), then every endpoint pair within +-2 of the result;
//   exhaustive  every one of the 256 x 256 endpoint pairs (the order decides the mode, as in the decoder), with
//               early termination of a pair once its partial error exceeds the best so far (exact, not a
//               heuristic: the error is a sum of non-negative terms). Starts from the `default` result.
// Errors are squared differences in 8-bit units on the reference decoding's palette (exact fractions).
#pragma once

#include <cstdint>

#include "formats/bc4/bc4_block.h"
#include "formats/common/s3tc_color_fit.h"   // S3tcSearch

namespace blocklab {

// The encoder; returns a canonical (consistent) block. `six_value_start` false leaves out the default search's 6-value
// start (its answer is then the refined 8-value range fit): for a caller that searches both modes itself from that
// fit, such as the `wang` 1D codec's descent from every mode pair.
Bc4Params fit_bc4_block(const float values[16], S3tcSearch search, bool six_value_start = true);

// Squared error of the values under (endpoint0, endpoint1, mode) with the best code per texel (written to `indices`
// when not null; ties to the lower code).
float evaluate_bc4_candidate(const float values[16], int endpoint0, int endpoint1, Bc4Mode mode, std::uint8_t* indices);

}  // namespace blocklab
