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
#include "core/interval.h"

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

// ---- the round-trip and enclosure checks every colour space gets ----------------------------------------------
// `round_trip` maps an Rgb<double> (or Rgb<float>) through the space and back; the checks stop at the first
// failure and name the sample.

// `samples` random HDR texels (RgbSampler(seed); black texels are skipped: each space tests black on its own) come
// back within `tolerance` of their largest channel.
template <typename RoundTrip>
::testing::AssertionResult round_trips_random_hdr_texels(RoundTrip round_trip, std::uint64_t seed, double tolerance,
                                                         int samples = 200000) {
  RgbSampler sampler(seed);
  for (int i = 0; i < samples; ++i) {
    const Rgb<double> rgb = sampler.texel();
    if (largest_channel(rgb) == 0.0) continue;
    ::testing::AssertionResult near = channels_near(rgb, round_trip(rgb), tolerance, largest_channel(rgb));
    if (!near) return near << " (sample " << i << ")";
  }
  return ::testing::AssertionSuccess();
}

// Every edge texel comes back within `tolerance` of its largest channel.
template <typename RoundTrip>
::testing::AssertionResult round_trips_edge_texels(RoundTrip round_trip, double tolerance) {
  for (const Rgb<double>& rgb : edge_texels()) {
    const ::testing::AssertionResult near = channels_near(rgb, round_trip(rgb), tolerance, largest_channel(rgb));
    if (!near) return near;
  }
  return ::testing::AssertionSuccess();
}

// The same in float: `samples` random texels converted to float, through the space in float and back, within
// `tolerance` of the float input's largest channel (a black texel, unless skipped, must come back exactly black).
enum class BlackTexels { skip, include };
template <typename RoundTripFloat>
::testing::AssertionResult round_trips_in_float(RoundTripFloat round_trip, std::uint64_t seed, double tolerance,
                                                BlackTexels black, int samples = 100000) {
  RgbSampler sampler(seed);
  for (int i = 0; i < samples; ++i) {
    const Rgb<double> rgb = sampler.texel();
    if (black == BlackTexels::skip && largest_channel(rgb) == 0.0) continue;
    const Rgb<float> rgb_float{static_cast<float>(rgb.r), static_cast<float>(rgb.g), static_cast<float>(rgb.b)};
    const Rgb<float> back = round_trip(rgb_float);
    const Rgb<double> input{rgb_float.r, rgb_float.g, rgb_float.b};
    ::testing::AssertionResult near =
        channels_near(input, Rgb<double>{back.r, back.g, back.b}, tolerance, largest_channel(input));
    if (!near) return near << " (sample " << i << ")";
  }
  return ::testing::AssertionSuccess();
}

// An RGB box as {r_lo, r_hi, g_lo, g_hi, b_lo, b_hi}, as an interval texel.
inline Rgb<Interval> box_texel(const double (&box)[6]) {
  return Rgb<Interval>{Interval(box[0], box[1]), Interval(box[2], box[3]), Interval(box[4], box[5])};
}

// `points` random points of the box (seeded) each satisfy `in_enclosure(point)`: the caller converts the point and
// checks every component against the enclosure it computed from box_texel(box).
template <typename InEnclosure>
::testing::AssertionResult box_encloses_its_points(const double (&box)[6], std::uint64_t seed, InEnclosure in_enclosure,
                                                   int points = 2000) {
  std::mt19937_64 engine(seed);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  for (int i = 0; i < points; ++i) {
    const Rgb<double> point{box[0] + unit(engine) * (box[1] - box[0]), box[2] + unit(engine) * (box[3] - box[2]),
                            box[4] + unit(engine) * (box[5] - box[4])};
    if (!in_enclosure(point))
      return ::testing::AssertionFailure() << std::hexfloat << "point (" << point.r << ", " << point.g << ", "
                                           << point.b << ") of the box falls outside its enclosure";
  }
  return ::testing::AssertionSuccess();
}

}  // namespace blocklab::color_testing
