// The one zero / negative rule of every log-domain metric (SPECS.md section 1a, "Recommendation").
//
// Implementations disagree on log(0) (astcenc: -inf; piccante: skip the sample; Mantiuk: max(x, 1e-5)), so blocklab
// fixes ONE rule, applied to every R, G, B value of both images before log2:
//     x -> max(x, floor), floor = 2^-24 (the smallest positive half, i.e. the smallest non-zero value an fp16-based
//     HDR format can store); NaN -> floor as well.
// Values in (0, floor) are raised to the floor too. +Inf is left alone (log2 gives +Inf and the metric honestly
// becomes Inf/NaN): the input policy (core/input_policy.h) removes non-finite values before metrics run.
// Every result reports the rule, the floor and how many samples of each image were raised.
#pragma once

#include <cmath>
#include <cstddef>
#include <string>

namespace blocklab {

// 2^-24: smallest positive (subnormal) IEEE half.
inline constexpr double kLogDomainDefaultFloor = 5.9604644775390625e-08;

struct LogDomainZeroRule {
  double floor = kLogDomainDefaultFloor;

  // Returns max(value, floor); NaN also maps to the floor. Counts every value that was changed.
  double apply(float value, std::size_t& clamped_count) const {
    const double x = static_cast<double>(value);
    // NaN compares false with everything, so test "not >= floor" to catch it together with zero, negatives and
    // positive values below the floor.
    if (!(x >= floor)) {
      ++clamped_count;
      return floor;
    }
    return x;
  }

  std::string describe() const { return "x -> max(x, floor) per R,G,B value of both images; NaN -> floor"; }
};

}  // namespace blocklab
