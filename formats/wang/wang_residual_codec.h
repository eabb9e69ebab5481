// The residual half of the `wang` encoder: tex1's colour block for one 4x4 block, given the decoded eq. 4
// luminance L_a of its texels (the alpha blocks are fitted first, as in the paper: S = L - L', eq. 5).
//
//   codec=bc3  the plain BC3 colour encoder (formats/common/s3tc_color_fit.h, squared RGB error, 4-colour) on the eq. 6
//              targets of S (or T): what a general DXT encoder does, treating the 1D residual as a 3D colour.
//   codec=1d   Wang et al. 2007 section 3.5 ("1D quantity split in three channels"): the residual palette is fitted
//              as two 1D endpoint values s0, s1 (entries s0, s1, (2 s0 + s1)/3, (s0 + 2 s1)/3) by weighted Lloyd
//              rounds on the texels' residuals, and only then split into RGB565 colours: every 565 colour has the
//              1D value dot(colour, r_ranges) + smin (ResidualTable, sorted), the `residual_candidates` colours
//              nearest to s0 and to s1 are tried in pairs, and the pair with the least ResidualBlockError (the
//              log-domain error of the decoded, clamped luminance, wang_block_problem.h) wins. With `solver` other than builtin, the 6D
//              ResidualBlockError is solved by that solver from the one-candidate answer.
#pragma once

#include <cstddef>
#include <cstdint>
#include <utility>
#include <vector>

#include "formats/bc1/bc1_block.h"
#include "formats/common/block_solver.h"
#include "formats/wang/wang_block_problem.h"
#include "formats/wang/wang_luminance_codec.h"
#include "formats/wang/wang_presets.h"

namespace blocklab {
namespace wang {

// The 1D residual value of each of the 65536 RGB565 colours (as an endpoint: bit-replicated, exact 8-bit), sorted.
struct ResidualTable {
  std::vector<std::pair<double, std::uint16_t>> sorted;   // (value, packed 565 word)
};
ResidualTable build_residual_table(const ResidualBlockError& error);

struct ResidualFit {
  Bc1Params color;        // canonical BC3 colour block (4-colour)
  double error = 0.0;     // ResidualBlockError with the block's own codes
};

// `error` holds the block's L, L_a, weights and the residual constants; `zones` the eq. 6 zones (codec=bc3 targets).
ResidualFit fit_residual_block(const ResidualBlockError& error, const ResidualTable& table, const Zones& zones,
                               const SearchEffort& effort, Codec codec, const BlockSolverSetup& solver,
                               std::size_t block_index);

// The 1D residual value of each of the 4 codes of a colour block (fetched 8-bit colours dotted with the ranges,
// plus smin).
void residual_entries(const ResidualBlockError& error, const Bc1Params& color, double entries[4]);
// The block's error under a colour block with the codes it holds.
double residual_error_with_codes(const ResidualBlockError& error, const Bc1Params& color);

}  // namespace wang
}  // namespace blocklab
