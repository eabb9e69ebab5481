// Shared helpers for the colour-space tests (tests/unit/test_color_*.cpp): a deterministic RGB sampler over the
// fp16 range, the positive half values, and channel-wise comparison with a tolerance relative to the texel scale.
#pragma once

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <random>
#include <vector>

#include "core/color_spaces.h"

namespace blocklab::color_testing {

// Largest finite half: the input policy clamps +inf to it, so it is the largest channel value a format sees.
constexpr double kLargestHalf = 65504.0;
// Smallest positive half (subnormal).
constexpr double kSmallestHalf = 0x1p-24;

// Value of the IEEE 754 binary16 bit pattern `bits` (finite, non-negative patterns only: 0x0000..0x7BFF).
inline double half_value(std::uint16_t bits) {
  const int exponent = bits >> 10;
  const int mantissa = bits & 0x3FF;
  // Subnormal halves have no implicit leading 1 and the exponent of the smallest normal.
  if (exponent == 0) return std::ldexp(static_cast<double>(mantissa), -24);
  return std::ldexp(static_cast<double>(1024 + mantissa), exponent - 25);
}

// Every positive finite half value, ascending (31743 values).
inline std::vector<double> positive_half_values() {
  std::vector<double> values;
  for (std::uint16_t bits = 1; bits <= 0x7BFF; ++bits) values.push_back(half_value(bits));
  return values;
}

// Random HDR texels: each channel log-uniform over [2^-24, 65504], with a 1-in-8 chance of an exact 0, so
// samples cover black channels, saturated colours and the whole fp16 dynamic range.
class RgbSampler {
 public:
  explicit RgbSampler(std::uint64_t seed) : engine_(seed) {}
  double channel() {
    if (std::uniform_int_distribution<int>(0, 7)(engine_) == 0) return 0.0;
    const double log2_value = std::uniform_real_distribution<double>(-24.0, std::log2(kLargestHalf))(engine_);
    return std::exp2(log2_value);
  }
  Rgb<double> texel() { return Rgb<double>{channel(), channel(), channel()}; }
  // Texels whose channels lie within `stops` stops of each other (typical of natural images).
  Rgb<double> texel_within_stops(double stops) {
    const double base = std::uniform_real_distribution<double>(-20.0, 15.0)(engine_);
    std::uniform_real_distribution<double> offset(0.0, stops);
    return Rgb<double>{std::exp2(base + offset(engine_)), std::exp2(base + offset(engine_)),
                       std::exp2(base + offset(engine_))};
  }

 private:
  std::mt19937_64 engine_;
};

// Edge texels every round-trip test covers: pure primaries and grey at the smallest half, at 1 and at 65504.
inline std::vector<Rgb<double>> edge_texels() {
  std::vector<Rgb<double>> texels;
  for (double value : {kSmallestHalf, 1.0, kLargestHalf}) {
    texels.push_back({value, 0.0, 0.0});
    texels.push_back({0.0, value, 0.0});
    texels.push_back({0.0, 0.0, value});
    texels.push_back({value, value, value});
  }
  texels.push_back({kLargestHalf, kSmallestHalf, 0.0});   // maximum dynamic range within one texel
  texels.push_back({kSmallestHalf, kLargestHalf, kSmallestHalf});
  return texels;
}

inline double largest_channel(const Rgb<double>& rgb) { return std::max({rgb.r, rgb.g, rgb.b}); }

// Every channel of `actual` is within `relative_tolerance * scale + absolute_tolerance` of `expected`.
inline ::testing::AssertionResult channels_near(const Rgb<double>& expected, const Rgb<double>& actual,
                                                double relative_tolerance, double scale,
                                                double absolute_tolerance = 0.0) {
  const double bound = relative_tolerance * scale + absolute_tolerance;
  const double errors[3] = {std::abs(actual.r - expected.r), std::abs(actual.g - expected.g),
                            std::abs(actual.b - expected.b)};
  if (errors[0] <= bound && errors[1] <= bound && errors[2] <= bound) return ::testing::AssertionSuccess();
  return ::testing::AssertionFailure() << std::hexfloat << "expected (" << expected.r << ", " << expected.g << ", "
                                       << expected.b << ") got (" << actual.r << ", " << actual.g << ", "
                                       << actual.b << "), allowed error " << bound;
}

}  // namespace blocklab::color_testing
