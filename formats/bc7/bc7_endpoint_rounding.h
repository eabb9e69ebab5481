// Rounding of least-squares BC7 endpoints to the mode's lattice for FIXED indices, channel by channel.
//
// With the indices fixed, the decoded value of texel i in lane c is interpolate(E0_c, E1_c, w_i) (KDFS "BPTC"
// interpolation on the expanded endpoints), so the weighted squared error is a sum of independent per-lane terms:
// each lane's pair of codes can be chosen on its own. For every lane the two lattice codes that bracket each ideal
// endpoint are tried (2 x 2 pairs, scored with the decoder's exact integer interpolation), instead of rounding each
// endpoint to its nearest code independently of the indices. P-bits couple the lanes (one bit per endpoint or per
// subset): with `all_pbits` every P-bit combination the lattice allows is rounded this way and the best total
// kept (the P-bits chosen by the error of the rounded endpoints, not by a search over re-fits; SPECS.md 2.5 item
// 4); otherwise the one combination nearest to the ideal endpoints (pbit_candidates) is rounded.
// This is the quantisation step of the least-squares "cluster fit" loop (Castano, "High Quality DXT Compression
// using CUDA", 2007, section on least-squares endpoint optimisation with fixed indices), made exact for BC7's
// lattice and rounding.
#pragma once

#include <cstdint>

#include "formats/bc7/bc7_quantise.h"

namespace blocklab {
namespace bc7 {

// Quantised endpoints minimising sum_i sum_c weights[c] (texels[i][c] - decoded_i,c)^2 over the bracketing codes
// of `ideal` (every lane with weights[c] > 0) and the P-bit combinations (see all_pbits), for the member indices
// `indices` (index_bits wide). Lanes with weight 0 are rounded to the nearest code. Writes the error of the
// result (for these indices) to *error.
QuantisedEndpoints round_endpoints_for_indices(const float (*texels)[4], int count, const std::uint8_t* indices,
                                               int index_bits, const float ideal[2][4], const EndpointLattice& lattice,
                                               const float weights[4], bool all_pbits, float* error);

}  // namespace bc7
}  // namespace blocklab
