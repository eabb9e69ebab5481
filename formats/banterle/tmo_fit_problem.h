// The image-level parameter fit of Banterle et al. 2008 as blocklab Problems (core/problem.h): eq. 3,
//   eps(alpha, Lwhite) = sum_ij ( log L_ij - log g([f(L_ij)]_0^255) )^2,
// the log-domain error of the tone-mapped luminance after 8-bit quantisation, and a smooth surrogate of it for
// Levenberg-Marquardt (SPECS.md section 5, item 3).
//
// Parameters: x[0] = log2 alpha, x[1] = log2 Lwhite (SPECS.md section 5, item 1: positivity, conditioning). The
// mean L_H is fixed (it only rescales alpha: f and g depend on alpha / L_H). Logs are base 2 (eq. 3's log up to a
// constant factor, and the unit of the log2[RGB] metric). Zero rule (metrics/zero_rule.h): luminances at or below
// 2^-24 are floored there on both sides, so pixels darker than the floor contribute exactly 0 and are left out.
//
// EVALUATION ON A HISTOGRAM (not on every pixel). eq. 3 depends on the image only through its luminances, so the
// pixels are binned by log2 L into kTmoHistogramBins equal bins over [log2 Lmin, log2 Lmax] of the counted pixels;
// each bin is represented by the mean log2 L of its pixels, weighted by its pixel fraction. One evaluation costs
// 1024 bins instead of width x height pixels (about 20 us instead of 30 ms for 1 MP). Effect on the optimum,
// measured with benchmarks/bench_banterle_fit.cpp (coeff_search on the histogram vs on every pixel, same box, start
// and settings): on a 1024x1024 mirror-tiling of samples/hdr/Desk.exr the optima differ by (0.006, 0.003) in
// (log2 alpha, log2 Lwhite) and the all-pixel eq. 3 at the histogram optimum is 0.044 % above the all-pixel
// optimum; on ../shared/data/hdr/StillLife.exr (1.05 MP) by (0.005, 0.074), +0.27 %. The all-pixel search took
// 17-20 s, the histogram one 0.01-0.02 s.
//
// eq. 3 functor (Eq3Error): per bin b with weight w_b and log luminance l_b,
//   x = 2^(x0 + l_b) / L_H,  code = clamp(round(255 f(x)), 0, 255),  G = g_scaled(code / 255)   (reinhard_operator.h)
//   r_b = sqrt(w_b) * (l_b - log2(max(G L_H / alpha, 2^-24))),      error = sum_b r_b^2  (mean squared log2 error)
// round is floor(v + 0.5) (ties up), with a zero Jet derivative: through the quantiser Levenberg-Marquardt sees only
// the derivative with every code frozen (SPECS.md section 5), which is what `ceres_lm_raw` demonstrates.
//
// Surrogate functor (Eq3Surrogate, C^1): the quantiser replaced by its expected effect. A code error uniform in
// [-1/2, 1/2] / 255 gives the log2 error variance (d log2 g / dL')^2 / (12 * 255^2), and
// d log2 g / dL' = 1 / (ln 2 * L f'(L)) = (1 + x)^2 / (ln 2 * x * (1 + (2 x + x^2) / Lwhite^2)); the clipping
// above L' = 1 is kept exactly: max(0, l_b - log2 g(1)), log2 g(1) = x1 - x0 + log2 L_H. Two residuals per bin:
//   noise_b = sqrt(w_b / 12) / (255 ln 2) * (1 + x)^2 / (x (1 + (2 x + x^2) / Lwhite^2)),
//   clip_b  = sqrt(w_b) * max(0, l_b - (x1 - x0 + log2 L_H)).
#pragma once

#include <array>
#include <cmath>
#include <cstddef>
#include <memory>
#include <vector>

#include "core/problem.h"
#include "core/scalar.h"
#include "formats/banterle/reinhard_operator.h"
#include "formats/common/s3tc_common.h"   // floor_scalar for double, Jet and Interval

namespace blocklab {

constexpr int kTmoHistogramBins = 1024;
// The zero rule's floor: 2^-24 (the smallest positive half), as in metrics/zero_rule.h.
constexpr double kTmoLog2Floor = -24.0;

struct LuminanceHistogram {
  std::array<double, kTmoHistogramBins> log2_luminance{};   // mean log2 L of the bin's pixels (bin centre if empty)
  std::array<double, kTmoHistogramBins> weight{};           // pixel count / counted pixels (sums to 1, or all 0)
  double log2_min = 0.0, log2_max = 0.0;                    // range of the counted pixels
  std::size_t counted = 0;                                  // pixels with L > 2^-24
  std::size_t total = 0;                                    // all pixels
};

// Bins the luminances (any values; <= 2^-24 and NaN are not counted). Deterministic (one sequential pass).
LuminanceHistogram build_luminance_histogram(const std::vector<double>& luminances);

// round(v) = floor(v + 1/2) for every scalar type (Jet: zero derivative; Interval: monotone, exact on doubles).
template <typename T>
T round_half_up(const T& value) { return floor_scalar(value + T(0.5)); }

// eq. 3 on the histogram.
struct Eq3Error {
  static constexpr int kDim = 2;
  static constexpr int kResiduals = kTmoHistogramBins;
  std::shared_ptr<const LuminanceHistogram> histogram;
  double log2_mean = 0.0;   // log2 L_H

  template <typename T>
  void residuals(const T* x, T* r) const {
    using std::exp2;
    using std::log2;
    using std::sqrt;
    const T l_white = exp2(x[1]);
    // log2 of the reconstruction is log2 G + (log2 L_H - x0); the floor 2^-24 on g is 2^(-24 - log2 L_H + x0) on G.
    const T offset = T(log2_mean) - x[0];
    const T floor_scaled = exp2(T(kTmoLog2Floor) - offset);
    for (int b = 0; b < kTmoHistogramBins; ++b) {
      const double w = histogram->weight[static_cast<std::size_t>(b)];
      const double l = histogram->log2_luminance[static_cast<std::size_t>(b)];
      if (w == 0.0) {   // empty bin: contributes nothing (and costs no transcendental)
        r[b] = T(0.0);
        continue;
      }
      const T scaled = exp2(T(l) - offset);
      const T tone_mapped = reinhard_forward_scaled(scaled, l_white);
      const T code = clamp(round_half_up(T(255.0) * tone_mapped), T(0.0), T(255.0));
      const T reconstructed = reinhard_inverse_scaled(code / T(255.0), l_white);
      r[b] = T(sqrt(w)) * (T(l) - (log2(max(reconstructed, floor_scaled)) + offset));
    }
  }

  template <typename T>
  T operator()(const T* x) const {
    return sum_of_squared_residuals<kResiduals>(*this, x);
  }
};

// The smooth surrogate of eq. 3 for Levenberg-Marquardt.
struct Eq3Surrogate {
  static constexpr int kDim = 2;
  static constexpr bool kSmooth = true;
  static constexpr int kResiduals = 2 * kTmoHistogramBins;
  std::shared_ptr<const LuminanceHistogram> histogram;
  double log2_mean = 0.0;

  template <typename T>
  void residuals(const T* x, T* r) const {
    using std::exp2;
    using std::sqrt;
    const T l_white_squared = square(exp2(x[1]));
    const T offset = T(log2_mean) - x[0];
    const T log2_peak = x[1] + offset;   // log2 g(1) = log2 Lwhite + log2 L_H - log2 alpha
    const double noise_scale = 1.0 / (255.0 * std::log(2.0) * std::sqrt(12.0));
    for (int b = 0; b < kTmoHistogramBins; ++b) {
      const double w = histogram->weight[static_cast<std::size_t>(b)];
      const double l = histogram->log2_luminance[static_cast<std::size_t>(b)];
      if (w == 0.0) {   // empty bin
        r[2 * b] = r[2 * b + 1] = T(0.0);
        continue;
      }
      const T scaled = exp2(T(l) - offset);
      const T slope_inverse = square(T(1.0) + scaled) /
                              (scaled * (T(1.0) + (T(2.0) * scaled + square(scaled)) / l_white_squared));
      r[2 * b] = T(std::sqrt(w) * noise_scale) * slope_inverse;
      r[2 * b + 1] = T(std::sqrt(w)) * max(T(0.0), T(l) - log2_peak);
    }
  }

  template <typename T>
  T operator()(const T* x) const {
    return sum_of_squared_residuals<kResiduals>(*this, x);
  }
};

// eq. 3 on every pixel (no histogram): the reference the histogram is measured against (tests, benchmark). Holds
// the log2 luminances of the counted pixels; the error is the mean over them (the histogram's normalisation).
struct Eq3AllPixelsError {
  static constexpr int kDim = 2;
  std::shared_ptr<const std::vector<double>> log2_luminances;
  double log2_mean = 0.0;

  template <typename T>
  T operator()(const T* x) const {
    using std::exp2;
    using std::log2;
    const T l_white = exp2(x[1]);
    const T offset = T(log2_mean) - x[0];
    const T floor_scaled = exp2(T(kTmoLog2Floor) - offset);
    T sum = T(0.0);
    for (double l : *log2_luminances) {
      const T tone_mapped = reinhard_forward_scaled(exp2(T(l) - offset), l_white);
      const T code = clamp(round_half_up(T(255.0) * tone_mapped), T(0.0), T(255.0));
      const T reconstructed = reinhard_inverse_scaled(code / T(255.0), l_white);
      sum = sum + square(T(l) - (log2(max(reconstructed, floor_scaled)) + offset));
    }
    const double count = log2_luminances->empty() ? 1.0 : static_cast<double>(log2_luminances->size());
    return sum / T(count);
  }
};

// log2 L of every luminance above the floor (the input of Eq3AllPixelsError).
std::vector<double> counted_log2_luminances(const std::vector<double>& luminances);

}  // namespace blocklab
