// The luminance half of the `wang` encoder: the alpha blocks of tex0 and tex1 for one 4x4 block.
//
//   codec=bc3  the plain BC3 alpha encoder (formats/bc4/bc4_encoder.h, squared 8-bit error) on the eq. 3 targets of
//              each texture separately (wang_zone_encoding.h): what a general DXT encoder does with these channels.
//   codec=1d   Wang et al. 2007 section 3.5: both alpha palettes fitted in the 1D domain of L itself with the
//              log-domain error E = |L - L'| / (L + c) (eq. 9) of the DECODED eq. 4 luminance, each texel choosing its
//              best pair of codes (LuminanceBlockError, wang_block_problem.h). Start: the 8-value BC4 fit of the eq. 3
//              targets (range or refined, by preset; the bc3 codec also tries a 6-value start); then (preset)
//              coordinate descent over the endpoints of the channels the block uses (a block inside one zone keeps
//              the other channel at its eq. 3 constant unless the preset searches it too), for every mode pair of
//              those channels, strict improvements only, fixed order (deterministic). With `solver` other than
//              builtin, every mode pair is solved by that solver from the start (solve_block_on_lattice).
#pragma once

#include <cstddef>

#include "formats/bc4/bc4_block.h"
#include "formats/common/block_solver.h"
#include "formats/wang/wang_block_problem.h"
#include "formats/wang/wang_presets.h"
#include "formats/wang/wang_shader.h"

namespace blocklab {
namespace wang {

enum class Codec { one_d, bc3 };

struct LuminanceFit {
  Bc4Params tex0, tex1;   // canonical
  double error = 0.0;     // LuminanceBlockError at the result with the blocks' own codes
};

// `error` holds the block's luminances, weights and eq. 4 constants (its modes and texture_unit are ignored).
LuminanceFit fit_luminance_block(const LuminanceBlockError& error, const Zones& zones, LuminanceSplit split,
                                 const SearchEffort& effort, Codec codec, const BlockSolverSetup& solver,
                                 std::size_t block_index);

// The two terms of eq. 4 per code: part0[i] = fetched tex0.a code i * high, part1[j] = fetched tex1.a code j * low +
// tmin (in double), so the decoded luminance of codes (i, j) is part0[i] + part1[j].
void alpha_parts(const LuminanceBlockError& error, const Bc4Params& tex0, const Bc4Params& tex1, double part0[8],
                 double part1[8]);
// The eq. 4 luminance of each texel decoded from two alpha blocks (fetched 8-bit values, in double).
void decoded_luminance(const LuminanceBlockError& error, const Bc4Params& tex0, const Bc4Params& tex1,
                       double out[16]);
// The block's error under two alpha blocks with the codes they hold (no code choice).
double luminance_error_with_codes(const LuminanceBlockError& error, const Bc4Params& tex0, const Bc4Params& tex1);

}  // namespace wang
}  // namespace blocklab
