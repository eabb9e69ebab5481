// Joint code choice of the `wang` encoder: once both textures' endpoints are fixed (alpha blocks of tex0 and tex1,
// residual colour block of tex1), every texel picks its three codes (tex0.a, tex1.a, tex1.rgb) together, 8 x 8 x 4
// combinations, for the least log-domain error of the shown eq. 7 (or eq. 11) luminance D = max(L', 0),
// ResidualBlockError::texel_error (eq. 9 where D >= L; a black D for a non-black texel costs L / c). The paper
// fits the alpha palettes first and the residual of what they decode second (eq. 5); choosing
// the codes jointly afterwards lets an alpha code compensate the residual palette's offset (a residual entry is never
// exactly 0 unless a 565 colour happens to decode to 0), which matters most for dark texels. Only codes change, so
// the endpoints' fits stand; a texel's error never increases (its sequential codes are among the combinations).
#pragma once

#include <array>

#include "formats/wang/wang_block.h"
#include "formats/wang/wang_block_problem.h"

namespace blocklab {
namespace wang {

// `residual` carries L, weights, ranges, rmin and ratio (its `decoded` is ignored); `luminance` the eq. 4 constants.
// Rewrites the alpha codes of params.tex0 / params.tex1 and the colour codes of params.tex1 in place and returns the
// block's error.
double choose_codes_jointly(const LuminanceBlockError& luminance, const ResidualBlockError& residual,
                            BlockParams& params);

}  // namespace wang
}  // namespace blocklab
