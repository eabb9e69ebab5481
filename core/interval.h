// blocklab::Interval: the closed interval of doubles used by branch-and-bound to bound an error over a box.
//
// Implements SPECS.md section 6 ("Interval arithmetic in C++"): Boost.Interval (header-only, Boost 1.74) with a
// custom rounding policy, `OutwardRounding`, and Boost's non-throwing `checking_base` policy.
//
// ROUNDING STRATEGY (why outward nextafter)
//   Every bound is computed in the default round-to-nearest mode and then moved outward to the neighbouring double
//   (lower bound towards -inf, upper bound towards +inf), exactly what std::nextafter(x, -+inf) gives; `next_down`
//   and `next_up` below are branch-light bit-twiddling equivalents (tests check them against std::nextafter).
//   * Arithmetic (+ - * /): IEEE 754 round-to-nearest is within half an ulp of the exact result, so one ulp outward
//     is on the correct side of the exact value (also across a binade boundary, where the spacing halves).
//     A result that is certainly exact is not widened: a sum/difference of 0 (x + y == 0 only by exact
//     cancellation, and gradual underflow makes tiny sums exact) and a product/quotient with a zero operand.
//     A product/quotient that underflows to zero is widened only on the side its sign allows, so square(x) and
//     products of same-sign factors never get a negative lower bound.
//   * sqrt: IEEE 754 requires a correctly rounded sqrt (SSE2 sqrtsd), so one ulp outward is rigorous.
//   * exp, log, exp2, log2: glibc "does not aim for correctly rounded results" (glibc manual, Errors in Math
//     Functions); its known maximum errors for these are a few ulp at most (SPECS.md section 6; glibc's per-target
//     libm-test-ulps tables). Bounds are widened by kTranscendentalUlps = 4 ulps, checked against long double on
//     10^5 random arguments per function in tests/unit/test_interval.cpp; exp/exp2 lower bounds are clamped at 0.
//   Nothing switches the FPU rounding mode: SPECS.md measured a mode save/restore per operation at ~90x the cost of
//   a double evaluation; this policy costs a few integer operations per bound.
//
// WHAT IT GUARANTEES
//   For every operation provided here, on non-empty finite inputs, the result contains the exact real result of
//   the operation applied to every point of the argument intervals (inclusion), as long as the process runs in
//   round-to-nearest with gradual underflow (no FTZ/DAZ) and glibc's libm errors stay within 4 ulp.
//   The build uses -frounding-math (top-level CMake) so GCC does not constant-fold differently from run time.
// WHAT IT DOES NOT GUARANTEE
//   * Tightness: bounds are up to 1 ulp (arithmetic) or 4 ulps (transcendentals) wider than a correctly rounded
//     interval library (e.g. MPFI) would give; exactly representable results of + - * / are widened too, except
//     the zero cases above.
//   * Rigour of libm itself: the transcendental margin relies on glibc's documented error bounds, not a proof.
//   * Other Boost functions (sin, cos, tan, ...) are not provided by this policy and do not compile.
//
// CHECKING POLICY (empty intervals and NaN)
//   `checking_base<double>`: nothing throws. An empty interval is represented with NaN bounds; creating one from
//   a NaN or from lower > upper yields the empty interval; every Boost operation returns empty on an empty
//   argument, and log/log2/sqrt return empty when the whole argument lies outside their domain (an argument that
//   only partly lies outside is clipped: log([-1, 1]) = [-inf, 0]). `is_empty(x)` tests for it. Problem (core/
//   problem.h) turns an empty error enclosure into [-inf, +inf] ("no information") so a search never prunes on it.
//   Comparison operators (<, <=, ...) of Boost intervals THROW when the operands overlap: never use them; use the
//   three-valued comparisons of core/scalar.h (less, less_equal, ...), which never throw.
//
// FUNCTIONS: + - * / with intervals and doubles, exp, log, exp2, log2, sqrt, square, pow(x, int), min, max, abs
// (Boost's interval extensions), pow(x, y) for real y (exp(y log x), see kPowBaseFloor; one widened std::pow per
// bound for a constant y > 0), hull, width, midpoint.
// Inside templated errors use square(x), never x * x (x * x of [-0.9, 1] is [-0.9, 1]; square gives [0, 1]).
#pragma once

#include <boost/numeric/interval.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <string>

namespace blocklab {

// The neighbouring double towards +inf (next_up) / -inf (next_down); equal to std::nextafter(x, +-inf) for every
// double: NaN stays NaN, +inf stays +inf under next_up and becomes DBL_MAX under next_down, next_up(+-0) is the
// smallest positive subnormal.
inline double next_up(double x) {
  if (!(x < std::numeric_limits<double>::infinity())) return x;   // NaN and +inf have no larger neighbour
  if (x == 0.0) return std::numeric_limits<double>::denorm_min(); // both +0 and -0 step to the smallest subnormal
  std::uint64_t bits;
  std::memcpy(&bits, &x, sizeof bits);
  // Positive doubles order like their bit patterns, negative ones in reverse (sign-magnitude encoding).
  bits = x > 0.0 ? bits + 1 : bits - 1;
  double result;
  std::memcpy(&result, &bits, sizeof result);
  return result;
}

inline double next_down(double x) { return -next_up(-x); }

// Number of ulps by which exp/log/exp2/log2 bounds are widened (glibc's maximum errors are a few ulp at most).
constexpr int kTranscendentalUlps = 4;

// Smallest base pow(x, y) evaluates through exp(y log x): the smallest normal double, 2^-1022. The part of a base
// interval below it is not fed to log (log(0) = -inf would make y * log x an indeterminate 0 * inf); its
// contribution is added exactly by its limit instead (see pow below).
constexpr double kPowBaseFloor = std::numeric_limits<double>::min();

// Boost.Interval rounding policy: round-to-nearest, then outward by whole ulps (see the file comment).
// Construction and destruction are trivial: no rounding-mode state is saved or restored.
struct OutwardRounding {
  using unprotected_rounding = OutwardRounding;   // required by boost::numeric::interval_lib::unprotect

  static double widen_down(double value, int ulps) {
    for (int i = 0; i < ulps; ++i) value = next_down(value);
    return value;
  }
  static double widen_up(double value, int ulps) {
    for (int i = 0; i < ulps; ++i) value = next_up(value);
    return value;
  }

  void init() {}
  template <class U> double conv_down(const U& v) { return static_cast<double>(v); }   // double -> double: exact
  template <class U> double conv_up(const U& v) { return static_cast<double>(v); }

  // A zero sum is exact (only exact cancellation or an exactly-zero operand pair produces it under gradual
  // underflow), so it is not widened.
  double add_down(double x, double y) { const double r = x + y; return r == 0.0 ? r : next_down(r); }
  double add_up(double x, double y) { const double r = x + y; return r == 0.0 ? r : next_up(r); }
  double sub_down(double x, double y) { const double r = x - y; return r == 0.0 ? r : next_down(r); }
  double sub_up(double x, double y) { const double r = x - y; return r == 0.0 ? r : next_up(r); }

  double mul_down(double x, double y) {
    const double r = x * y;
    if (r != 0.0) return next_down(r);
    if (x == 0.0 || y == 0.0) return 0.0;   // exact zero product
    // Underflow to zero: a same-sign product is a tiny positive number, so 0 is a valid lower bound.
    return std::signbit(x) == std::signbit(y) ? 0.0 : -std::numeric_limits<double>::denorm_min();
  }
  double mul_up(double x, double y) {
    const double r = x * y;
    if (r != 0.0) return next_up(r);
    if (x == 0.0 || y == 0.0) return 0.0;   // exact zero product
    // Underflow to zero: an opposite-sign product is a tiny negative number, so 0 is a valid upper bound.
    return std::signbit(x) != std::signbit(y) ? 0.0 : std::numeric_limits<double>::denorm_min();
  }
  double div_down(double x, double y) {
    const double r = x / y;
    if (r != 0.0) return next_down(r);
    if (x == 0.0 || std::isinf(y)) return 0.0;   // exact zero quotient (0 / y, finite x / inf)
    return std::signbit(x) == std::signbit(y) ? 0.0 : -std::numeric_limits<double>::denorm_min();
  }
  double div_up(double x, double y) {
    const double r = x / y;
    if (r != 0.0) return next_up(r);
    if (x == 0.0 || std::isinf(y)) return 0.0;   // exact zero quotient
    return std::signbit(x) != std::signbit(y) ? 0.0 : std::numeric_limits<double>::denorm_min();
  }
  // Boost uses median only for midpoints, which need not be rigorous.
  double median(double x, double y) { return x * 0.5 + y * 0.5; }

  // IEEE 754 sqrt is correctly rounded: one ulp outward suffices. sqrt is non-negative.
  double sqrt_down(double x) { const double r = std::sqrt(x); return r == 0.0 ? 0.0 : next_down(r); }
  double sqrt_up(double x) { const double r = std::sqrt(x); return r == 0.0 ? 0.0 : next_up(r); }
  double int_down(double x) { return std::floor(x); }   // exact
  double int_up(double x) { return std::ceil(x); }      // exact

  // exp and exp2 are positive: the widened lower bound is clamped at 0 (exp(-inf) = 0 exactly).
  double exp_down(double x) { const double r = widen_down(std::exp(x), kTranscendentalUlps); return r < 0.0 ? 0.0 : r; }
  double exp_up(double x) { return widen_up(std::exp(x), kTranscendentalUlps); }
  double exp2_down(double x) { const double r = widen_down(std::exp2(x), kTranscendentalUlps); return r < 0.0 ? 0.0 : r; }
  double exp2_up(double x) { return widen_up(std::exp2(x), kTranscendentalUlps); }
  // log(1) = log2(1) = 0 exactly in glibc and in exact arithmetic; other values are widened. Callers pass x > 0.
  double log_down(double x) { return x == 1.0 ? 0.0 : widen_down(std::log(x), kTranscendentalUlps); }
  double log_up(double x) { return x == 1.0 ? 0.0 : widen_up(std::log(x), kTranscendentalUlps); }
  double log2_down(double x) { return x == 1.0 ? 0.0 : widen_down(std::log2(x), kTranscendentalUlps); }
  double log2_up(double x) { return x == 1.0 ? 0.0 : widen_up(std::log2(x), kTranscendentalUlps); }
};

using IntervalPolicies =
    boost::numeric::interval_lib::policies<OutwardRounding, boost::numeric::interval_lib::checking_base<double>>;

// The interval type. Because OutwardRounding lives in namespace blocklab, argument-dependent lookup finds the
// blocklab functions below (exp2, log2, pow, ...) for unqualified calls inside templated errors.
using Interval = boost::numeric::interval<double, IntervalPolicies>;

inline bool is_empty(const Interval& x) { return boost::numeric::empty(x); }
inline Interval whole_line() { return Interval::whole(); }
inline Interval empty_interval() { return Interval::empty(); }

// exp2(x) = 2^x, monotone increasing.
inline Interval exp2(const Interval& x) {
  if (is_empty(x)) return Interval::empty();
  OutwardRounding rnd;
  return Interval(rnd.exp2_down(x.lower()), rnd.exp2_up(x.upper()), true);
}

// log2(x), monotone increasing on x > 0. Empty when x lies entirely at or below 0; the part of x at or below 0 is
// clipped (lower bound -inf), like Boost's log.
inline Interval log2(const Interval& x) {
  if (is_empty(x) || !(x.upper() > 0.0)) return Interval::empty();
  OutwardRounding rnd;
  const double lower = x.lower() > 0.0 ? rnd.log2_down(x.lower()) : -std::numeric_limits<double>::infinity();
  return Interval(lower, rnd.log2_up(x.upper()), true);
}

// x^y for real y on the part of x that is >= 0 (a negative part is outside pow's real domain and is clipped; an
// x entirely below 0 gives the empty interval). Evaluated as exp(y * log(x)) on x clipped to [kPowBaseFloor, inf);
// when x reaches below kPowBaseFloor (in particular x = 0) the exact limit behaviour is added by hull:
// y > 0 adds 0 (x^y -> 0), y < 0 adds +inf (x^y -> inf), y spanning 0 gives [0, inf].
inline Interval pow(const Interval& x, const Interval& y) {
  if (is_empty(x) || is_empty(y) || x.upper() < 0.0) return Interval::empty();
  const Interval floored(std::max(x.lower(), kPowBaseFloor), std::max(x.upper(), kPowBaseFloor), true);
  Interval result = boost::numeric::exp(y * boost::numeric::log(floored));
  if (x.lower() < kPowBaseFloor) {
    if (y.lower() > 0.0) {
      // For x in [0, floor) and y > 0, x^y lies in [0, floor^y], and floor^y is already inside `result`.
      result = Interval(0.0, result.upper(), true);
    } else if (y.upper() < 0.0) {
      // For x in (0, floor) and y < 0, x^y lies in [floor^y, inf).
      result = Interval(result.lower(), std::numeric_limits<double>::infinity(), true);
    } else {
      // y spans 0: x^y ranges over (0, inf) near x = 0 (and pow(0, 0) = 1).
      result = Interval(0.0, std::numeric_limits<double>::infinity(), true);
    }
  }
  return result;
}
// x^y for a constant exponent y > 0: increasing in x on x >= 0, so each bound is one std::pow of the matching end
// (the part of x below 0 is clipped, an x entirely below 0 gives the empty interval; 0^y = 0 exactly), widened by
// kTranscendentalUlps like exp/log: glibc's pow is documented within 1 ulp (libm-test-ulps for x86_64), and the
// bounds are checked against long double in tests/unit/test_interval.cpp. Half the libm calls of exp(y log x) and
// a tighter result. Other exponents (y <= 0, NaN, inf) take the general path above.
inline Interval pow(const Interval& x, double y) {
  if (!(y > 0.0 && y < std::numeric_limits<double>::infinity())) return pow(x, Interval(y));
  if (is_empty(x) || x.upper() < 0.0) return Interval::empty();
  const double lower = x.lower() > 0.0 ? x.lower() : 0.0, upper = x.upper();
  // Both bounds are >= 0: the widened lower bound is clamped at 0, and 0^y = 0 needs no widening.
  const double lower_power = lower == 0.0 ? 0.0 : OutwardRounding::widen_down(std::pow(lower, y), kTranscendentalUlps);
  const double upper_power = upper == 0.0 ? 0.0 : OutwardRounding::widen_up(std::pow(upper, y), kTranscendentalUlps);
  return Interval(lower_power < 0.0 ? 0.0 : lower_power, upper_power, true);
}
// pow(x, int) is Boost's exact-power version (found by ADL; it wins over the real-exponent one for int arguments).

// Upper bound of the width (upper - lower rounded up, so one ulp above an exact difference); midpoint is rounded
// to nearest and lies inside x (x/2 + y/2 is monotone in both halves), for bisection of finite boxes. The midpoint
// of the whole line is 0 (Boost would give inf - inf = NaN); a half-infinite interval gives its infinite end.
inline double width(const Interval& x) { return boost::numeric::width(x); }
inline double midpoint(const Interval& x) {
  if (x.lower() == -std::numeric_limits<double>::infinity() && x.upper() == std::numeric_limits<double>::infinity())
    return 0.0;
  return boost::numeric::median(x);
}
inline bool contains(const Interval& x, double value) { return !is_empty(x) && x.lower() <= value && value <= x.upper(); }

// "[lower, upper]" with 17 significant digits, or "empty".
std::string to_string(const Interval& x);

}  // namespace blocklab
