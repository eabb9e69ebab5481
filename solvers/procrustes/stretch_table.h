// The stretch f(c) = max(c, kStretchFloor)^alpha of "Practical HDR Texture Compression" (2008) section 7.2 on [0, 1],
// without a libm call. Two users: the refinement measures of the `procrustes` solver
// (solvers/procrustes/procrustes_refinement.h, procrustes_screening.h), where std::pow was ~40 % of a stretched solve's
// time, and the box enclosures of stretched errors (a format's interval bound), which widen each value by
// kRelativeErrorBound to keep them rigorous.
#pragma once

#include <array>
#include <cstdint>
#include <cstring>

#include "core/problem.h"

namespace blocklab {

// f(c) = max(c, kStretchFloor)^alpha on [0, 1] (the stretch of "Practical HDR Texture Compression" (2008) section 7.2)
// without a libm call: c = m 2^e with m in [1, 2) and e in [-30, 0] (c >= kStretchFloor = 2^-30), so c^alpha = 2^(alpha
// e) m^alpha; the first factor is a table of 31 values and m^alpha a degree-4 Taylor polynomial around the centre of
// m's 1/128-wide interval (remainder <= |prod_{j<5} (alpha - j)| / 5! * 256^-5 < 2e-13 relative for alpha in (0, 1],
// ~3e-14 at alpha = 0.455; tests/unit/test_stretch_table.cpp checks it against std::pow). Every table entry comes from
// std::pow.
class StretchTable {
 public:
  // A bound on |operator()(c) / f(c) - 1| for every c in [0, 1] and alpha in (0, 1], with margin: the Taylor
  // remainder (< 2e-13, above) plus the polynomial's rounding and the 1-ulp std::pow behind each table entry
  // (< 1e-15 together). Also bounds the distance to std::pow's own value (1 ulp from f), so an enclosure widened by
  // it contains a point error computed with std::pow.
  static constexpr double kRelativeErrorBound = 1e-12;

  explicit StretchTable(double alpha);
  double alpha() const { return alpha_; }
  // c in [0, 1] (values below the floor, 0 included, give f(kStretchFloor); NaN is not allowed). Inline: the
  // refinements and the start-error kernel call it for every landmark coordinate they map.
  double operator()(double c) const;

 private:
  static constexpr int kIntervalBits = 7;   // 128 intervals of the mantissa
  double alpha_ = 1.0;
  double floor_value_ = 0.0;                                          // pow(kStretchFloor, alpha)
  std::array<double, 31> power_of_two_{};                             // 2^(alpha e), e = -30 .. 0
  std::array<std::array<double, 5>, 1 << kIntervalBits> taylor_{};    // per interval: m^alpha around its centre
};

inline double StretchTable::operator()(double c) const {
  // Below the floor (0 included) the stretch is constant: f(floor).
  if (!(c > kStretchFloor)) return floor_value_;
  std::uint64_t bits;
  std::memcpy(&bits, &c, sizeof bits);
  // c in (2^-30, 1]: a normal number with unbiased exponent e in [-30, 0]; m = 1.mantissa in [1, 2).
  const int e = static_cast<int>(bits >> 52) - 1023;
  const std::uint64_t mantissa = bits & ((std::uint64_t{1} << 52) - 1);
  const std::uint64_t one_bits = std::uint64_t{1023} << 52;
  const std::uint64_t m_bits = one_bits | mantissa;
  double m;
  std::memcpy(&m, &m_bits, sizeof m);
  const std::size_t interval = static_cast<std::size_t>(mantissa >> (52 - kIntervalBits));
  const double centre = 1.0 + (static_cast<double>(interval) + 0.5) / (1 << kIntervalBits);
  const double t = m - centre;   // exact: both in [1, 2] on the same binade grid
  const std::array<double, 5>& p = taylor_[interval];
  const double mantissa_power = p[0] + t * (p[1] + t * (p[2] + t * (p[3] + t * p[4])));
  return power_of_two_[static_cast<std::size_t>(e + 30)] * mantissa_power;
}

// The table of `alpha`, built on first use (31 + 128 pows) and shared by every thread: a table never changes once
// built, and it lives as long as the process, so the reference stays valid while tables of other exponents are built
// (one per distinct alpha, ~5 KB each). Constant data, not scratch: looking it up takes a lock, so callers look it
// up once per solve (RefineMeasure) or per problem, never per evaluation.
const StretchTable& shared_stretch_table(double alpha);

}  // namespace blocklab
