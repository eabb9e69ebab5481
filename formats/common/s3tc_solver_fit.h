// BC1/BC3 colour and BC4/BC3 alpha endpoint searches run by a solver of the library (format option `solver`, see
// formats/common/block_solver.h) instead of the builtin pipelines of s3tc_color_fit.h and bc4_encoder.h.
//
// The Problems are those of s3tc_endpoint_problem.h (endpoints on the RGB565 / 8-bit lattice, error = sum of the
// best palette entry's weighted squared difference per texel, in a fixed mode). Each mode the block may use is
// solved separately from the builtin `fast` answer, the lattice answer is scored with the exact palette error
// (the builtin evaluate_* functions, best code per texel) and the better mode is kept; the block is then written in
// canonical form (canonicalise_bc1 / canonicalise_bc3_color / canonicalise_bc4), which does not change its texels.
#pragma once

#include <cstddef>

#include "formats/bc4/bc4_block.h"
#include "formats/common/block_solver.h"
#include "formats/common/s3tc_color_fit.h"

namespace blocklab {

// settings.allow_three_color decides whether the 3-colour mode competes (BC1) or not (BC3 colour).
Bc1Params fit_color_block_with_solver(const ColorBlock& block, const ColorFitSettings& settings,
                                      const BlockSolverSetup& setup, std::size_t block_index);

// `values` in 8-bit code units [0, 255] as for fit_bc4_block; both modes compete.
Bc4Params fit_bc4_block_with_solver(const float values[16], const BlockSolverSetup& setup, std::size_t block_index);

}  // namespace blocklab
