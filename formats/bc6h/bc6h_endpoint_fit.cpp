// BC6H endpoint fitting (bc6h_endpoint_fit.h): targets, principal-axis fit, least squares, quantisation.
#include "formats/bc6h/bc6h_endpoint_fit.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "formats/bc6h/bc6h_half.h"

namespace blocklab {
namespace bc6h {

BlockTarget make_block_target(const float (*rgb)[4], bool is_signed, HdrBlockError error) {
  BlockTarget block;
  block.is_signed = is_signed;
  block.error = error;
  for (int texel = 0; texel < kTexels; ++texel)
    for (int c = 0; c < 3; ++c) {
      float value = rgb[texel][c];
      if (!is_signed && !(value > 0.0f)) value = 0.0f;   // UF16 holds no negatives
      const int half = signed_magnitude(float_to_half_bits(value));
      block.half[texel][c] = half;
      // The final unquantisation maps i to (i * 31) >> 6 (unsigned) or |i| * 31 >> 5 (signed): the centre of the
      // interval of i that gives `half`.
      const double magnitude = (std::abs(half) + 0.5) * (is_signed ? 32.0 : 64.0) / 31.0;
      block.target[texel][c] = half < 0 ? -magnitude : (half == 0 ? 0.0 : magnitude);
      if (error == HdrBlockError::mpsnr_weighted) {
        // The source's half (negatives as 0), like the log2 domain: a block the format reproduces exactly scores 0 and
        // ends the search. The slope of gamma_domain in half bits by a central difference (one-sided at 0).
        const int h = std::min(std::max(half, 0), kLargestFiniteHalf);
        const int below = std::max(h - 1, 0), above = std::min(h + 1, kLargestFiniteHalf);
        const double slope = (gamma_domain(above) - gamma_domain(below)) / (above - below);
        block.source_error_value[texel][c] = gamma_domain(h);
        block.source_unclamped[texel][c] = gamma_domain_unclamped_stops(h);
        block.error_weight[texel][c] = mpsnr_stop_sums().sum_squares[block.source_unclamped[texel][c]];
        block.weight[texel][c] = block.error_weight[texel][c] * slope * slope;
        continue;
      }
      block.source_error_value[texel][c] = log_domain(half);
      // d log_domain / dh = 1024 / (h ln 2) below 1024 (h >= 1), 1 above.
      const double slope = half >= 1024 ? 1.0 : 1024.0 / (std::max(half, 1) * std::log(2.0));
      block.error_weight[texel][c] = error == HdrBlockError::log2_skip && !(value > 0.0f) ? 0.0 : 1.0;
      block.weight[texel][c] = block.error_weight[texel][c] * slope * slope;
    }
  return block;
}

const GammaDomainEntry* gamma_domain_table() {
  static const std::vector<GammaDomainEntry> table = [] {
    std::vector<GammaDomainEntry> entries;
    for (int h = 0; h <= kLargestFiniteHalf; ++h) {
      const double gamma = mpsnr_gamma(half_bits_to_float(static_cast<std::uint16_t>(h)));
      entries.push_back({gamma, mpsnr_unclamped_stops(gamma)});
    }
    return entries;
  }();
  return table.data();
}

namespace {

std::size_t gamma_index(int half) { return static_cast<std::size_t>(std::min(std::max(half, 0), kLargestFiniteHalf)); }

}  // namespace

double gamma_domain(int half) { return gamma_domain_table()[gamma_index(half)].gamma; }
int gamma_domain_unclamped_stops(int half) { return gamma_domain_table()[gamma_index(half)].unclamped; }

const double* log_domain_table() {
  // h for h >= 1024, 1024 log2(h) - 9216 for h = 1..1023 and 0 (as 1), tabulated once (the same doubles on every call).
  static const std::vector<double> table = [] {
    std::vector<double> values(static_cast<std::size_t>(kLargestFiniteHalf) + 1);
    for (int h = 1; h <= kLargestFiniteHalf; ++h)
      values[static_cast<std::size_t>(h)] = h >= 1024 ? h : 1024.0 * std::log2(static_cast<double>(h)) - 9216.0;
    values[0] = values[1];
    return values;
  }();
  return table.data();
}

double log_domain(int half) {
  if (half > kLargestFiniteHalf) return half;
  return log_domain_table()[std::max(half, 0)];
}

double domain_low(bool is_signed) { return is_signed ? -32767.0 : 0.0; }
double domain_high(bool is_signed) { return is_signed ? 32767.0 : 65535.0; }

namespace {

double clamp_domain(double value, bool is_signed) {
  return std::min(std::max(value, domain_low(is_signed)), domain_high(is_signed));
}

}  // namespace

void principal_endpoints(const BlockTarget& block, const std::uint8_t* members, int count, double (&endpoints)[2][3]) {
  double mean[3] = {0.0, 0.0, 0.0};
  for (int i = 0; i < count; ++i)
    for (int c = 0; c < 3; ++c) mean[c] += block.target[members[i]][c];
  for (double& m : mean) m /= count;
  double covariance[3][3] = {};
  for (int i = 0; i < count; ++i) {
    double d[3];
    for (int c = 0; c < 3; ++c) d[c] = block.target[members[i]][c] - mean[c];
    for (int a = 0; a < 3; ++a)
      for (int b = 0; b < 3; ++b) covariance[a][b] += d[a] * d[b];
  }
  // Power iteration from the diagonal's largest direction (deterministic start).
  double axis[3] = {1.0, 1.0, 1.0};
  for (int iteration = 0; iteration < 8; ++iteration) {
    double next[3];
    for (int a = 0; a < 3; ++a) next[a] = covariance[a][0] * axis[0] + covariance[a][1] * axis[1] + covariance[a][2] * axis[2];
    const double length = std::sqrt(next[0] * next[0] + next[1] * next[1] + next[2] * next[2]);
    if (!(length > 1e-12)) break;   // no spread: keep the current axis
    for (int a = 0; a < 3; ++a) axis[a] = next[a] / length;
  }
  double low = 0.0, high = 0.0;
  for (int i = 0; i < count; ++i) {
    double projection = 0.0;
    for (int c = 0; c < 3; ++c) projection += (block.target[members[i]][c] - mean[c]) * axis[c];
    low = std::min(low, projection);
    high = std::max(high, projection);
  }
  const double norm = axis[0] * axis[0] + axis[1] * axis[1] + axis[2] * axis[2];
  const double scale = norm > 0.0 ? 1.0 / norm : 0.0;
  for (int c = 0; c < 3; ++c) {
    endpoints[0][c] = clamp_domain(mean[c] + axis[c] * low * scale, block.is_signed);
    endpoints[1][c] = clamp_domain(mean[c] + axis[c] * high * scale, block.is_signed);
  }
}

void least_squares_endpoints(const BlockTarget& block, const std::uint8_t* members, int count, const double* fractions,
                             double (&endpoints)[2][3]) {
  for (int c = 0; c < 3; ++c) {
    double aa = 0.0, ab = 0.0, bb = 0.0, at = 0.0, bt = 0.0;
    for (int i = 0; i < count; ++i) {
      const double w = block.weight[members[i]][c];
      const double f = fractions[i];
      const double g = 1.0 - f;
      const double t = block.target[members[i]][c];
      aa += w * g * g;
      ab += w * g * f;
      bb += w * f * f;
      at += w * g * t;
      bt += w * f * t;
    }
    const double determinant = aa * bb - ab * ab;
    if (!(std::fabs(determinant) > 1e-9 * (aa * bb))) continue;
    endpoints[0][c] = clamp_domain((at * bb - bt * ab) / determinant, block.is_signed);
    endpoints[1][c] = clamp_domain((bt * aa - at * ab) / determinant, block.is_signed);
  }
}

int quantize_endpoint(double value, int bits, bool is_signed) {
  const int high = is_signed ? (1 << (bits - 1)) - 1 : (1 << bits) - 1;
  const int low = is_signed ? -high : 0;
  // unquantize(q) ~ (q + 1/2) 2^(16 - bits) unsigned, (|q| + 1/2) 2^(16 - bits) signed: invert, then check around.
  const double scale = std::ldexp(1.0, (is_signed ? 15 : 16) - (is_signed ? bits - 1 : bits));
  const double magnitude = std::fabs(value) / scale - 0.5;
  const int guess = static_cast<int>(std::lround(value < 0.0 ? -magnitude : magnitude));
  int best = std::min(std::max(guess, low), high);
  double best_distance = std::fabs(unquantize(best, bits, is_signed) - value);
  for (int candidate = guess - 1; candidate <= guess + 1; ++candidate) {
    if (candidate < low || candidate > high) continue;
    const double distance = std::fabs(unquantize(candidate, bits, is_signed) - value);
    if (distance < best_distance || (distance == best_distance && candidate < best)) {
      best = candidate;
      best_distance = distance;
    }
  }
  return best;
}

}  // namespace bc6h
}  // namespace blocklab
