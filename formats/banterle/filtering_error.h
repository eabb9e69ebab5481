// The filtering error of Banterle et al. 2008, section 4.5 ("Analysis of Error for Linear/Bi-Linear
// Interpolation"): the GPU filters the tone-mapped texture (texTMO) and the inverse TMO g (eq. 2) is applied to the
// filtered value, while correct filtering interpolates the HDR values.
//   eq. 5  L(a, b, x)     = x g(a) + (1 - x) g(b)          (filtering the HDR values)
//   eq. 6  L^(a, b, x)    = g(x a + (1 - x) b)             (filtering the tone-mapped values, then g)
//   eq. 7  eps(a, b, x)   = |L - L^|
// and its closed form after substituting eq. 2 (the linear terms of g cancel):
//   eps = | Lwhite^2 L_H / (2 alpha) * (x s(a) + (1 - x) s(b) - s(x a + (1 - x) b)) |,
//   s(q) = sqrt((1 - q)^2 + 4 q / Lwhite^2).
// eps is 0 at x = 0 and x = 1 (no interpolation). g is convex on [0, 1] when Lwhite > 1 (f is then concave), so
// L >= L^ there: the tone-mapped filter darkens.
//
// The image measurement (blocklab's addition; the paper plots eq. 7 only): bilinear 2x magnification, the sample
// positions a GPU uses, of the tone-mapped luminance t = min(f(L), 1) (eq. 1 in double, the quantiser's clip at 1,
// no 8-bit rounding, so only the filter's error is measured). For every 2x2 quad of neighbouring texels and
// (u, v) in {1/4, 3/4}^2: HDR filter  bilinear(g(t)), tone-mapped filter  g(bilinear(t)). Reported: the absolute
// error, the relative error |difference| / HDR filter (samples where both are 0 count as 0), the log2 error (both
// floored at 2^-24, metrics/zero_rule.h), and the quad's interval width max(t) - min(t) (eq. 7's |b - a|).
#pragma once

#include <cstddef>
#include <vector>

#include "core/image.h"
#include "formats/banterle/reinhard_estimate.h"

namespace blocklab {

struct FilteringCurvePoint {
  double x = 0.0;                     // interpolation factor (weight of a)
  double tone_mapped = 0.0;           // x a + (1 - x) b
  double hdr_filtered = 0.0;          // eq. 5
  double tone_mapped_filtered = 0.0;  // eq. 6
  double error = 0.0;                 // eq. 7 (through g)
  double closed_form_error = 0.0;     // eq. 7 (the paper's simplified expression)
  double relative_error = 0.0;        // error / eq. 5 (0 when eq. 5 is 0)
};

// eq. 7 by the paper's closed form.
double filtering_error_closed_form(const ReinhardParameters& parameters, double a, double b, double x);

// `samples` >= 2 points x = i / (samples - 1), i = 0..samples-1; a, b in [0, 1]. Throws Error otherwise.
std::vector<FilteringCurvePoint> filtering_error_curve(const ReinhardParameters& parameters, double a, double b,
                                                       int samples);

struct FilteringMeasurement {
  std::size_t samples = 0;            // 4 (W - 1)(H - 1)
  double mean_interval = 0.0;         // mean quad interval width max(t) - min(t)
  double max_interval = 0.0;
  double fraction_interval_above_0_3 = 0.0;   // quads wider than the paper's "average" interval [0.3, 0.6]
  double rms_error = 0.0;             // absolute (HDR luminance units)
  double max_error = 0.0;
  double mean_signed_error = 0.0;     // HDR filter - tone-mapped filter (> 0: the tone-mapped filter darkens)
  double rms_relative_error = 0.0;
  double max_relative_error = 0.0;
  double fraction_relative_above_1_percent = 0.0;
  double rms_log2_error = 0.0;
  double max_log2_error = 0.0;
};

// Throws Error when the image is smaller than 2x2. Deterministic (one pass in row order).
FilteringMeasurement measure_bilinear_filtering_error(const Image& image, const ReinhardParameters& parameters);

}  // namespace blocklab
