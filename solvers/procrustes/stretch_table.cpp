// The stretch table of solvers/procrustes/stretch_table.h (Munkberg et al. 2008 section 7.2's f(c) = c^alpha).
#include "solvers/procrustes/stretch_table.h"

#include <cmath>
#include <cstdint>
#include <cstring>
#include <memory>
#include <vector>

namespace blocklab {

StretchTable::StretchTable(double alpha) : alpha_(alpha) {
  floor_value_ = std::pow(kStretchFloor, alpha);
  for (int e = -30; e <= 0; ++e) power_of_two_[static_cast<std::size_t>(e + 30)] = std::pow(2.0, alpha * e);
  const int intervals = 1 << kIntervalBits;
  for (int i = 0; i < intervals; ++i) {
    // Taylor coefficients of m^alpha at the interval centre c: f^(k)(c) / k! = binom(alpha, k) c^(alpha - k).
    const double centre = 1.0 + (i + 0.5) / intervals;
    double coefficient = std::pow(centre, alpha);
    std::array<double, 5>& t = taylor_[static_cast<std::size_t>(i)];
    for (int k = 0; k < 5; ++k) {
      t[static_cast<std::size_t>(k)] = coefficient;
      coefficient *= (alpha - k) / ((k + 1) * centre);
    }
  }
}

double StretchTable::operator()(double c) const {
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

const StretchTable& thread_stretch_table(double alpha) {
  thread_local std::vector<std::unique_ptr<StretchTable>> tables;
  for (const auto& table : tables)
    if (table->alpha() == alpha) return *table;
  tables.push_back(std::make_unique<StretchTable>(alpha));
  return *tables.back();
}

}  // namespace blocklab
