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
#pragma once

#include <cstdint>

#include "formats/bc6h/bc6h_tables.h"

namespace blocklab {
namespace bc6h {

struct BlockTarget {
  bool is_signed = false;
  int half[kTexels][3] = {};        // source half bits as signed magnitudes (unsigned format: negatives are 0)
  double target[kTexels][3] = {};   // the interpolation-domain value whose final unquantisation is `half` (centre)
  double log_half[kTexels][3] = {}; // log_domain(half)
  double weight[kTexels][3] = {};   // squared slope of log_domain at `half`: 1 for normal halves, more below
};

// The error domain of a half bit pattern (signed magnitude; see above).
double log_domain(int half);

// Source texels (linear RGB floats) -> half bits and interpolation-domain targets.
BlockTarget make_block_target(const float (*rgb)[4], bool is_signed);
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
