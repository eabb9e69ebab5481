// The zone split of Wang et al. 2007 as a Problem (core/problem.h): the error of the range quantisation step of
// Fig. 1 ("Range Quantization", section 3.2) measured in the log-relative error of section 3.5 (eq. 9),
//     E = sum_k w_k |v_k - Q(v_k)|,      Q = uniform quantisation to `levels + 1` values in v_k's zone,
// where the samples v_k are luminances (t1 of eq. 3, w_k = count_k / (L_k + c)) or residuals (s1, s2 of eq. 6,
// w_k = count_k / (L_k + c) for S and count_k L'_k / (L_k + c) for the ratio T). Eq. 2 is the paper's proxy for
// this error (the zone width over 2^bits times the zone's count); this is the error itself, the "true reconstruction
// error" of the zone quantisation without the DXT palette. Parameters are the split points as nested fractions on
// [0, 1] (so they can never be out of order): 2 zones b1 = lo + (hi - lo) x0; 3 zones additionally
// b2 = b1 + (hi - b1) x1. A sample on a boundary belongs to the lower zone (as in eq. 3 / eq. 6).
// Templated on the scalar type (double, ceres::Jet, Interval); the rounding uses floor_scalar, so the Jet gradient
// is that of the branch (0 along the rounding steps), and the Interval error encloses it over boxes.
#pragma once

#include <array>
#include <vector>

#include "core/problem.h"
#include "core/scalar.h"
#include "formats/common/s3tc_common.h"

namespace blocklab {
namespace wang {

struct ZoneSample {
  double value = 0.0;
  double weight = 0.0;
};

template <int kZones>
struct ZoneSplitError {
  static constexpr int kDim = kZones - 1;
  std::vector<ZoneSample> samples;
  double low = 0.0, high = 0.0;                 // the whole range [lo, hi]
  std::array<double, kZones> levels{};          // quantisation steps per zone (255 for alpha, 31/63/31 for 565)

  template <typename T>
  T operator()(const T* x) const {
    T bounds[kZones + 1];
    bounds[0] = T(low);
    bounds[kZones] = T(high);
    for (int k = 1; k < kZones; ++k) bounds[k] = bounds[k - 1] + (T(high) - bounds[k - 1]) * x[k - 1];
    // A zone of (nearly) zero width quantises to its lower bound; the floor keeps the division finite.
    const double floor_width = (high - low) * 1e-12 + 1e-300;
    T total = T(0.0);
    for (const ZoneSample& sample : samples) {
      const T value = T(sample.value);
      T error = zone_error(value, bounds[kZones - 1], bounds[kZones], levels[kZones - 1], floor_width);
      for (int zone = kZones - 2; zone >= 0; --zone)
        error = select(less_equal(value, bounds[zone + 1]),
                       zone_error(value, bounds[zone], bounds[zone + 1], levels[zone], floor_width), error);
      total += T(sample.weight) * error;
    }
    return total;
  }

  template <typename T>
  static T zone_error(const T& value, const T& zone_low, const T& zone_high, double zone_levels, double floor_width) {
    const T width = max(zone_high - zone_low, T(floor_width));
    const T offset = value - zone_low;
    const T code = floor_scalar(offset / width * T(zone_levels) + T(0.5));
    return abs(offset - code * width / T(zone_levels));
  }
};

// The split points of a solution x (the same arithmetic as the error, in double).
template <int kZones>
std::array<double, kZones + 1> zone_bounds(const ZoneSplitError<kZones>& error, const double* x) {
  std::array<double, kZones + 1> bounds{};
  bounds[0] = error.low;
  bounds[kZones] = error.high;
  for (int k = 1; k < kZones; ++k) bounds[k] = bounds[k - 1] + (error.high - bounds[k - 1]) * x[k - 1];
  return bounds;
}

// x in [0, 1]^(kZones - 1), each on a uniform lattice of `lattice_points`.
template <int kZones>
ErrorProblem<ZoneSplitError<kZones>> make_zone_split_problem(const ZoneSplitError<kZones>& error,
                                                             std::int64_t lattice_points) {
  Bounds bounds{std::vector<double>(kZones - 1, 0.0), std::vector<double>(kZones - 1, 1.0)};
  std::vector<Lattice> lattices(kZones - 1, Lattice::uniform(0.0, 1.0, lattice_points));
  return make_problem(error, std::move(bounds), std::move(lattices));
}

}  // namespace wang
}  // namespace blocklab
