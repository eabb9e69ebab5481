// Branch-free building blocks for errors written once as a template on the scalar type (DESIGN.md "The one idea").
//
// A templated error must never `if` on a comparison of T values: with ceres::Jet the branch is fine but with an
// Interval the comparison may be undecided. Write instead
//     const auto closer = less(distance_a, distance_b);        // bool for double/float/Jet, Tribool for Interval
//     const T best = select(closer, distance_a, distance_b);   // per-type meaning below
// and use min/max/clamp/abs/square from here (call them unqualified inside namespace blocklab, or qualified).
//
// Per type:
//   double, float   comparisons are the built-in ones (a NaN compares false). select(c, a, b) = c ? a : b.
//                   min(a, b) = b < a ? b : a (ties and a NaN in b give a), max(a, b) = a < b ? b : a,
//                   abs = std::abs, square(x) = x * x.
//   ceres::Jet      comparisons look at the scalar parts only (`.a`); select/min/max/clamp return the whole chosen
//                   Jet, so the derivative is the derivative of the chosen branch (at a tie min/max choose `a`, the
//                   one-sided derivative of that branch). abs is ceres::abs (derivative copysign(1, x) * dx, so
//                   +dx at x = +0). square(x) = x * x (derivative 2 x dx).
//   Interval        comparisons are three-valued (Tribool::yes / no / maybe) and never throw: less(a, b) is `yes`
//                   when every point of a is below every point of b, `no` when none is, `maybe` otherwise or when
//                   an operand is empty. select(yes, a, b) = a, select(no, a, b) = b, select(maybe, a, b) =
//                   hull(a, b) (an enclosure of whichever branch the points take). min/max are the interval
//                   extensions [min lo, min hi] / [max lo, max hi] (exact ranges of min/max over the box); clamp =
//                   min(max(x, lo), hi); abs and square are Boost's (square is the dependency-free x^2, never
//                   negative; x * x is not).
// Conditions of any type combine with logical_and / logical_or / logical_not and are read with certainly /
// possibly (bool: the value itself).
#pragma once

#include <ceres/jet.h>

#include <cmath>
#include <type_traits>

#include "core/interval.h"

namespace blocklab {

// ---- three-valued truth for interval comparisons --------------------------------------------------------------
enum class Tribool : unsigned char { no, yes, maybe };

inline bool certainly(bool condition) { return condition; }
inline bool certainly(Tribool condition) { return condition == Tribool::yes; }
inline bool possibly(bool condition) { return condition; }
inline bool possibly(Tribool condition) { return condition != Tribool::no; }

inline bool logical_not(bool a) { return !a; }
inline Tribool logical_not(Tribool a) {
  return a == Tribool::maybe ? Tribool::maybe : (a == Tribool::yes ? Tribool::no : Tribool::yes);
}
inline bool logical_and(bool a, bool b) { return a && b; }
inline Tribool logical_and(Tribool a, Tribool b) {
  if (a == Tribool::no || b == Tribool::no) return Tribool::no;   // false decides the conjunction
  return (a == Tribool::yes && b == Tribool::yes) ? Tribool::yes : Tribool::maybe;
}
inline bool logical_or(bool a, bool b) { return a || b; }
inline Tribool logical_or(Tribool a, Tribool b) {
  if (a == Tribool::yes || b == Tribool::yes) return Tribool::yes;   // true decides the disjunction
  return (a == Tribool::no && b == Tribool::no) ? Tribool::no : Tribool::maybe;
}

const char* to_string(Tribool value);

// ---- comparisons ---------------------------------------------------------------------------------------------
inline bool less(double a, double b) { return a < b; }
inline bool less_equal(double a, double b) { return a <= b; }
inline bool less(float a, float b) { return a < b; }
inline bool less_equal(float a, float b) { return a <= b; }

template <typename T, int N>
bool less(const ceres::Jet<T, N>& a, const ceres::Jet<T, N>& b) { return a.a < b.a; }
template <typename T, int N>
bool less_equal(const ceres::Jet<T, N>& a, const ceres::Jet<T, N>& b) { return a.a <= b.a; }

inline Tribool less(const Interval& a, const Interval& b) {
  if (is_empty(a) || is_empty(b)) return Tribool::maybe;   // no information: never claim a certain answer
  if (a.upper() < b.lower()) return Tribool::yes;
  if (a.lower() >= b.upper()) return Tribool::no;
  return Tribool::maybe;
}
inline Tribool less_equal(const Interval& a, const Interval& b) {
  if (is_empty(a) || is_empty(b)) return Tribool::maybe;
  if (a.upper() <= b.lower()) return Tribool::yes;
  if (a.lower() > b.upper()) return Tribool::no;
  return Tribool::maybe;
}

template <typename T>
auto greater(const T& a, const T& b) -> decltype(less(b, a)) { return less(b, a); }
template <typename T>
auto greater_equal(const T& a, const T& b) -> decltype(less_equal(b, a)) { return less_equal(b, a); }

// ---- select ----------------------------------------------------------------------------------------------------
template <typename T>
T select(bool condition, const T& if_true, const T& if_false) { return condition ? if_true : if_false; }

inline Interval select(Tribool condition, const Interval& if_true, const Interval& if_false) {
  if (condition == Tribool::yes) return if_true;
  if (condition == Tribool::no) return if_false;
  return boost::numeric::hull(if_true, if_false);   // undecided: enclose both branches
}

// ---- min / max / clamp -----------------------------------------------------------------------------------------
inline double min(double a, double b) { return b < a ? b : a; }
inline double max(double a, double b) { return a < b ? b : a; }
inline float min(float a, float b) { return b < a ? b : a; }
inline float max(float a, float b) { return a < b ? b : a; }

template <typename T, int N>
ceres::Jet<T, N> min(const ceres::Jet<T, N>& a, const ceres::Jet<T, N>& b) { return b.a < a.a ? b : a; }
template <typename T, int N>
ceres::Jet<T, N> max(const ceres::Jet<T, N>& a, const ceres::Jet<T, N>& b) { return a.a < b.a ? b : a; }

// Non-template, so they win over Boost's templates found by argument-dependent lookup.
inline Interval min(const Interval& a, const Interval& b) { return boost::numeric::min(a, b); }
inline Interval max(const Interval& a, const Interval& b) { return boost::numeric::max(a, b); }

// clamp(x, lo, hi) = min(max(x, lo), hi); callers pass lo <= hi.
inline double clamp(double x, double lo, double hi) { return min(max(x, lo), hi); }
inline float clamp(float x, float lo, float hi) { return min(max(x, lo), hi); }
template <typename T, int N>
ceres::Jet<T, N> clamp(const ceres::Jet<T, N>& x, const ceres::Jet<T, N>& lo, const ceres::Jet<T, N>& hi) {
  return min(max(x, lo), hi);
}
inline Interval clamp(const Interval& x, const Interval& lo, const Interval& hi) { return min(max(x, lo), hi); }

// ---- abs / square ----------------------------------------------------------------------------------------------
// ceres::abs is the Jet overload and (through ceres' own `using std::abs`) std::abs for double and float, so one
// using-declaration gives every scalar type an unambiguous abs inside namespace blocklab.
using ceres::abs;
inline Interval abs(const Interval& x) { return boost::numeric::abs(x); }

inline double square(double x) { return x * x; }
inline float square(float x) { return x * x; }
template <typename T, int N>
ceres::Jet<T, N> square(const ceres::Jet<T, N>& x) { return x * x; }
inline Interval square(const Interval& x) { return boost::numeric::square(x); }

// ---- scalar value (for diagnostics and tests) ----------------------------------------------------------------
inline double scalar_value(double x) { return x; }
inline double scalar_value(float x) { return x; }
template <typename T, int N>
double scalar_value(const ceres::Jet<T, N>& x) { return scalar_value(x.a); }

}  // namespace blocklab
