// Log-luminance encoding of a `munkberg` block: the two 8-bit endpoints and the per-texel indices, found by the
// endpoint neighbourhood search of Munkberg et al. 2008, section 7.3 and Figure 9 ("we search in a small
// neighborhood around the end-points of the luminance range to minimize the error ... rather than just picking the
// min and max").
//
// Error: sum over texels of (decoded Ybar - target Ybar)^2 in log2 units, which is the luminance part of the
// log2[RGB] error (eq. 1: every channel's log2 error is the log-luminance error plus the chroma ratio's). Targets are
// the texels' log2 luminance clamped to [kBlackLog2, kLogLumMax]; a true-black level (q == 0, eq. 3) counts as
// kBlackLog2 = -24, the floor of the log2[RGB] metric (metrics/zero_rule.h), so a black or sub-floor texel prefers
// black and any other texel avoids it.
#pragma once

#include <array>
#include <cstdint>
#include <limits>

#include "formats/munkberg/munkberg_layout.h"

namespace blocklab::munkberg {

// log2 value a true-black texel is scored as (the log2[RGB] metric's floor 2^-24).
constexpr double kBlackLog2 = -24.0;

struct LuminanceFit {
  std::array<int, kLumEndpointCount> lum{};        // e0 <= e1
  std::array<std::uint8_t, kTexels> index{};       // 0 .. n
  double error = 0.0;                              // sum of squared log2 errors
};

// Decoded log2 value of level `l` of endpoints (e0, e1) in `mode`, kBlackLog2 for true black (q == 0).
double scored_level_log2(Mode mode, int e0, int e1, int l);

// The best index of every texel for endpoints (e0, e1) (nearest scored level; ties keep the lower index) and the
// resulting error: the same indices and error as scanning all levels, found from the nearest level in closed form and
// its two neighbours. With a `bound`, the texels are fitted only while the error so far is below it: a fit whose error
// reaches the bound returns early with a partial error >= bound (so the full error is >= bound too) and partial
// indices; below the bound the result is the full one, bit for bit.
LuminanceFit assign_luminance_indices(Mode mode, int e0, int e1, const double target[kTexels],
                                      double bound = std::numeric_limits<double>::infinity());

// Endpoint neighbourhood search: e0 within +-radius of the floor code of the smallest target (and 0, the black
// code, whenever a target is at or below kLogLumMin), e1 within +-radius of the ceiling code of the largest,
// e0 <= e1, every pair scored with its best indices; ties keep the first pair in (e0, e1) lexicographic order.
// radius 0 is the paper's plain min/max quantisation (Figure 9a). `target` are log2 luminances.
LuminanceFit fit_luminance(Mode mode, const double target[kTexels], int radius);

}  // namespace blocklab::munkberg
