// The error of filtering before the colour transform (Munkberg et al. 2008, section 4) measured on a real image.
// The paper shows it only as difference images (Figure 2); blocklab measures it.
//
// Every texel of the image becomes a logYuv texel (eq. 2, linear luminance with the eq. 3 black level; no
// quantisation, so only the filter's error is measured). For every 2x2 quad of neighbouring texels and every
// sample position (s, t) with s, t in {(j + 1/2) / m : j = 0..m-1} (m = `magnification`: m = 2 is the interior of
// a GPU's bilinear 2x magnification, the positions 1/4 and 3/4; m = 1 the quad's centre, every weight 1/4), the
// bilinear weights ((1-s)(1-t), s(1-t), (1-s)t, st) filter the quad three ways:
//   reference   in linear RGB after the transform (eq. 7),
//   plain       Y, u, v before the transform (eq. 9),
//   normalised  Y', u', v', c before the transform (section 4's shift trick).
// Each test filter is compared to the reference with the log2[RGB] error of the paper (section 2) in blocklab's
// definition (metrics/log2rgb.cpp: sqrt(sum over samples and R, G, B of (log2 ref - log2 test)^2 / samples), every
// value floored at 2^-24 as in metrics/zero_rule.h).
#pragma once

#include <cstddef>

#include "core/image.h"
#include "formats/munkberg/analysis/logyuv_filtering.h"

namespace blocklab::munkberg {

struct FilterErrorStatistics {
  double log2_rmse = 0.0;                 // log2[RGB] RMSE (astcenc normalisation: per sample, summed over R, G, B)
  double max_log2 = 0.0;                  // largest per-sample sqrt(sum_c (log2 difference)^2)
  double fraction_above_1_percent = 0.0;  // samples with some channel off by more than 1 % (|log2| > log2 1.01)
  double rms_relative_red = 0.0;          // RMS of |R_test - R_ref| / R_ref over samples with R_ref > 0
};

struct FilteringMeasurement {
  std::size_t samples = 0;                // m^2 (W - 1)(H - 1)
  std::size_t quads = 0;                  // (W - 1)(H - 1)
  std::size_t shifted_quads = 0;          // quads where some texel got k != 0
  double fraction_quads_ratio_above_2 = 0.0;   // quads whose max / min luminance exceeds 2 (black quads excluded)
  FilterErrorStatistics plain;
  FilterErrorStatistics normalised;
};

// Throws Error when the image is smaller than 2x2 or magnification is outside [1, 16]. Deterministic (rows in
// order, one pass).
FilteringMeasurement measure_logyuv_filtering(const Image& image, int magnification, ShiftRule rule,
                                              ShiftReference reference);

}  // namespace blocklab::munkberg
