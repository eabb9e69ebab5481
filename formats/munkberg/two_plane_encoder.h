// Encoder of the two-plane mode (formats/munkberg/two_plane_block.h; Munkberg et al. 2008, section 6.3: "To find the
// plane equations, we used exhaustive search and regression"). Luminance: candidate partitions of the texels (every
// threshold of the sorted log-luminances, and a true-black plane for black texels) each fitted by least-squares
// planes and refined by reassigning texels to the nearer quantised plane (Lloyd iterations), then a coordinate
// descent over the six plane codes with the best mask; chroma: shape I's shape fit through the solver library with
// the decoded plane luminance (munkberg_chroma.h), indices by the log2[RGB] error of the decoded texels.
#pragma once

#include <cstdint>

#include "core/blocks.h"
#include "formats/munkberg/munkberg_encoder.h"
#include "formats/munkberg/two_plane_block.h"

namespace blocklab::munkberg {

// The luminance half only: planes and mask minimising the squared log2-luminance error (targets as block_targets,
// true black scored as kBlackLog2). Returns that error.
double fit_two_plane_luminance(const double target[kTexels], TwoPlaneParams* params);

// A lower bound of the mode's block_log2_error whatever its chroma, from the luminance planes `luminance`
// (fit_two_plane_luminance of the block's targets): luminance_texel_bounds with each texel's plane (offset code 0:
// true black).
double two_plane_lower_bound(const BlockTexels& texels, const BlockAnalysis& analysis, const TwoPlaneParams& luminance);

// The whole mode; `error` (optional) receives the block's log2[RGB] error.
// `cache` (optional): shape I's shape solves of this block (same chroma points, settings and block_seed), reused.
// `luminance` (optional): fit_two_plane_luminance's planes and mask for this block, already computed.
TwoPlaneParams encode_two_plane(const BlockTexels& texels, const ShapeSet& shapes, const EncoderSettings& settings,
                                std::uint64_t block_seed, double* error = nullptr, ShapeSolveCache* cache = nullptr,
                                ChromaWorkspace* workspace = nullptr, const TwoPlaneParams* luminance = nullptr);

}  // namespace blocklab::munkberg
