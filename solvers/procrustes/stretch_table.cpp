// The stretch table of solvers/procrustes/stretch_table.h ("Practical HDR Texture Compression" (2008) section 7.2's
// f(c) = c^alpha).
#include "solvers/procrustes/stretch_table.h"

#include <cmath>
#include <cstdint>
#include <cstring>
#include <memory>
#include <mutex>
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

const StretchTable& shared_stretch_table(double alpha) {
  static std::mutex mutex;
  static std::vector<std::unique_ptr<const StretchTable>> tables;
  const std::lock_guard<std::mutex> lock(mutex);
  for (const auto& table : tables)
    if (table->alpha() == alpha) return *table;
  tables.push_back(std::make_unique<StretchTable>(alpha));
  return *tables.back();
}

}  // namespace blocklab
