// The zero / negative rules of the log-domain metrics (SPECS.md section 1a, "Recommendation").
//
// Implementations disagree on log(0) (astcenc: -inf; piccante: skip the sample; Mantiuk: max(x, 1e-5)). blocklab's
// default, used unless a config asks otherwise, is ONE rule applied to every R, G, B value of both images before log2:
//     floor: x -> max(x, floor), floor = 2^-24 (the smallest positive half, i.e. the smallest non-zero value an
//     fp16-based HDR format can store); NaN -> floor as well.
// Values in (0, floor) are raised to the floor too. +Inf is left alone (log2 gives +Inf and the metric honestly
// becomes Inf/NaN): the input policy (core/input_policy.h) removes non-finite values before metrics run.
// The second, opt-in rule reproduces the piccante library (F. Banterle's, `include/metrics/log_rmse.hpp`), i.e. the
// rule behind Banterle et al. 2008's numbers, whose eq. 8 (log2 of a ratio) is undefined at 0:
//     skip: a channel value where either image is <= 0 (or NaN) is left out of the sum; the rest use plain log2.
// Every result reports the rule and how many samples of each image were raised (floor) or left out (skip).
#pragma once

#include <cmath>
#include <cstddef>
#include <string>

namespace blocklab {

// 2^-24: smallest positive (subnormal) IEEE half.
inline constexpr double kLogDomainDefaultFloor = 5.9604644775390625e-08;

struct LogDomainZeroRule {
  enum class Mode { floor, skip };
  Mode mode = Mode::floor;
  double floor = kLogDomainDefaultFloor;   // used by Mode::floor only

  // Mode::skip: true when the pair (reference, test) enters the sum, i.e. both values are > 0 (NaN is not > 0).
  static bool both_positive(float reference, float test) { return reference > 0.0f && test > 0.0f; }

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

  std::string describe() const {
    if (mode == Mode::skip)
      return "skip: R,G,B values where either image is <= 0 or NaN are left out; mean over the counted values x 3 "
             "(piccante / Banterle 2008)";
    return "x -> max(x, floor) per R,G,B value of both images; NaN -> floor";
  }
};

}  // namespace blocklab
