// BC6H endpoint fitting in the unquantised domain (the 16-bit integers the decoder interpolates, KDFS "BC6H"):
// a block's target values, the principal-axis line fit of a region, the least-squares endpoints for fixed indices, and
// the quantisation of one endpoint value to the nearest code of a mode's endpoint precision.
//
// Error domain: log_domain(h) of the half-float bit pattern h (a signed magnitude). For normal halves (h >= 1024) it is
// h itself, a piecewise-linear log2 with 1024 steps per octave (the mantissa steps); below, where halves are
// subnormal and their bits linear in the value, it continues as 1024 log2(h) - 9216, down to h = 1 (2^-24, the floor of
// the log2[RGB] metric's default zero rule, metrics/zero_rule.h), which 0 and negative values share. So a squared
// difference weighs relative errors alike at every brightness, like the log2[RGB] metric. The decoder interpolates in
// the half-bit domain (scaled by 64/31 unsigned, 32/31 signed), so the fits there are linear least squares, weighted by
// the squared slope of log_domain at each source value.
//
// The error is a choice (option `error`, formats/common/hdr_block_error.h): log2_floor is the domain above; log2_skip
// the same with a weight of 0 on every source value <= 0 (the skip zero rule leaves them out); mpsnr_weighted uses
// gamma_domain(h) = x^(1/2.2) of the half's value x: candidates are scored exactly, stop by stop (mpsnr_stop_error:
// mPSNR's unrounded error), and the line fits weight each source value by W(x), the sum over mPSNR's stops of the
// squared slope of the unclamped tone curves, times the squared slope of gamma_domain in half bits.
#pragma once

#include <cstdint>

#include "formats/bc6h/bc6h_tables.h"
#include "formats/common/hdr_block_error.h"

namespace blocklab {
namespace bc6h {

struct BlockTarget {
  bool is_signed = false;
  HdrBlockError error = HdrBlockError::log2_floor;
  int half[kTexels][3] = {};        // source half bits as signed magnitudes (unsigned format: negatives are 0)
  double target[kTexels][3] = {};   // the interpolation-domain value whose final unquantisation is `half` (centre)
  double source_error_value[kTexels][3] = {};   // the source in the error domain: log_domain(half), or mpsnr's g(x)
  double error_weight[kTexels][3] = {};         // weight of a squared error-domain difference (1 for log2_floor)
  int source_unclamped[kTexels][3] = {};        // mpsnr_weighted: mpsnr_unclamped_stops of source_error_value
  double weight[kTexels][3] = {};   // least-squares weight in the interpolation domain: error_weight times the squared
                                    // slope of the error domain at `half` (log2: 1 for normal halves, more below)
};

inline constexpr int kLargestFiniteHalf = 0x7BFF;   // 65504

// The log2 error domain of a half bit pattern (signed magnitude; see above).
double log_domain(int half);
// log_domain of the halves 0..kLargestFiniteHalf (one lookup per palette entry in the search's inner loop).
const double* log_domain_table();
// mpsnr_weighted's error domain: x^(1/2.2) of the half's value (0 for h <= 0), and its mpsnr_unclamped_stops.
double gamma_domain(int half);
int gamma_domain_unclamped_stops(int half);
// Both, tabulated for the halves 0..kLargestFiniteHalf (one lookup per palette entry in the search's inner loop).
struct GammaDomainEntry {
  double gamma;
  int unclamped;
};
const GammaDomainEntry* gamma_domain_table();
// The error domain of `error` (log_domain or gamma_domain).
inline double error_domain(HdrBlockError error, int half) {
  return error == HdrBlockError::mpsnr_weighted ? gamma_domain(half) : log_domain(half);
}

// Source texels (linear RGB floats) -> half bits, interpolation-domain targets and the error's values and weights.
BlockTarget make_block_target(const float (*rgb)[4], bool is_signed,
                              HdrBlockError error = HdrBlockError::log2_floor);
// Half bits out of the decoder -> signed magnitude (sign bit -> negative), the domain of BlockTarget::half.
constexpr int signed_magnitude(std::uint16_t bits) { return (bits & 0x8000) ? -(bits & 0x7FFF) : bits; }

// Lowest and highest interpolation-domain value of the format: 0..0xFFFF unsigned, -0x7FFF..0x7FFF signed.
double domain_low(bool is_signed);
double domain_high(bool is_signed);

// The line fit of the region `members[0..count)`: the mean plus the principal axis (power iteration on the 3x3
// covariance) scaled to the extreme projections, clamped to the domain. Endpoint 0 is the low end along the axis.
void principal_endpoints(const BlockTarget& block, const std::uint8_t* members, int count, double (&endpoints)[2][3]);

// Least-squares endpoints of the region for fixed interpolation fractions (weight / 64 per member): per channel the
// 2x2 normal equations of sum w ((1 - f) E0 + f E1 - t)^2 with the texels' BlockTarget::weight. Leaves a channel
// unchanged when its system is singular (all fractions equal). Results are clamped to the domain.
void least_squares_endpoints(const BlockTarget& block, const std::uint8_t* members, int count, const double* fractions,
                             double (&endpoints)[2][3]);

// The code of `bits` precision whose unquantize() is nearest to `value` (ties: the lower code). Unsigned codes are
// 0..2^bits - 1; signed codes -(2^(bits-1) - 1)..2^(bits-1) - 1.
int quantize_endpoint(double value, int bits, bool is_signed);

}  // namespace bc6h
}  // namespace blocklab
