// The stretch table (solvers/procrustes/stretch_table.h): the libm-free f(c) = max(c, kStretchFloor)^alpha of Munkberg
// et al. 2008 section 7.2 against std::pow, and the error bound the shape fit's box enclosure widens by.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include "formats/munkberg/shape_fit/shape_fit_problem.h"
#include "solvers/procrustes/stretch_table.h"

namespace blocklab {
namespace {

// Edges (0 and below-floor values, the floor itself, binade and interval boundaries, 1) and 20,000 random values,
// half uniform on [0, 1], half log-uniform down to 2^-30.
std::vector<double> sample_values(unsigned seed) {
  std::mt19937_64 random(seed);
  std::uniform_real_distribution<double> unit(0.0, 1.0), exponent(-30.0, 0.0);
  std::vector<double> values = {0.0, 1e-300, kStretchFloor, std::nextafter(kStretchFloor, 1.0), 0.5, 0.25,
                                std::nextafter(0.5, 0.0), 1.0 - 1.0 / 256, 1.0, std::nextafter(1.0, 0.0), 0.02,
                                1.0 / 255};
  for (int i = 0; i < 20000; ++i) values.push_back(i % 2 ? unit(random) : std::exp2(exponent(random)));
  return values;
}

TEST(StretchTable, AgreesWithStdPowWithin1e13Relative) {
  for (const double alpha : {0.455, 0.1, 0.75, 1.0}) {
    const StretchTable table(alpha);
    const auto reference = [alpha](double c) { return std::pow(std::max(c, kStretchFloor), alpha); };
    for (const double c : sample_values(12)) {
      const double expected = reference(c);
      EXPECT_LE(std::abs(table(c) - expected), 1e-13 * expected) << "alpha " << alpha << " c " << c;
    }
    EXPECT_EQ(table(0.0), reference(kStretchFloor));
  }
}

// The bound the box enclosure relies on: widened by kRelativeErrorBound, every table value encloses std::pow's,
// with a margin of at least 4x over the largest relative difference seen, for exponents across (0, 1].
TEST(StretchTable, ErrorBoundEnclosesStdPowWithMargin) {
  for (const double alpha : {1e-3, 0.2, 0.455, 0.5, 0.9, 1.0}) {
    const StretchTable table(alpha);
    double largest = 0.0;
    for (const double c : sample_values(13)) {
      const double expected = std::pow(std::max(c, kStretchFloor), alpha);
      const double value = table(c);
      EXPECT_LE(value * (1.0 - StretchTable::kRelativeErrorBound), expected) << "alpha " << alpha << " c " << c;
      EXPECT_GE(value * (1.0 + StretchTable::kRelativeErrorBound), expected) << "alpha " << alpha << " c " << c;
      largest = std::max(largest, std::abs(value / expected - 1.0));
    }
    EXPECT_LE(4.0 * largest, StretchTable::kRelativeErrorBound) << "alpha " << alpha;
  }
}

}  // namespace
}  // namespace blocklab
