// Lloyd-Max mid-tread quantisers for the unit-variance Laplacian (formats/munkberg/dct_quantiser_design.h).
#include "formats/munkberg/dct_quantiser_design.h"

#include <cmath>
#include <limits>

#include "core/error.h"

namespace blocklab::munkberg {

namespace {

// Unit variance: density f(x) = (r / 2) exp(-r |x|) with rate r = sqrt(2).
const double kRate = std::sqrt(2.0);

// Moments of f over [lo, hi] with 0 <= lo <= hi (hi may be +infinity): mass, first and second moment, from
// int_lo^hi x^n (r/2) e^{-rx} dx in closed form.
struct Moments {
  double mass = 0.0, first = 0.0, second = 0.0;
};
Moments positive_moments(double lo, double hi) {
  const auto terms = [](double x, double* e, double* e1, double* e2) {
    if (std::isinf(x)) {   // x^n e^{-rx} -> 0 at +infinity
      *e = *e1 = *e2 = 0.0;
      return;
    }
    const double decay = std::exp(-kRate * x);
    *e = 0.5 * decay;
    *e1 = 0.5 * (x + 1.0 / kRate) * decay;
    *e2 = 0.5 * (x * x + 2.0 * x / kRate + 2.0 / (kRate * kRate)) * decay;
  };
  double a0, a1, a2, b0, b1, b2;
  terms(lo, &a0, &a1, &a2);
  terms(hi, &b0, &b1, &b2);
  return {a0 - b0, a1 - b1, a2 - b2};
}

// Moments over any [lo, hi]: split at 0 and mirror the negative part (f is even; the first moment changes sign).
Moments moments(double lo, double hi) {
  Moments out;
  if (hi > 0.0) {
    const Moments p = positive_moments(std::max(lo, 0.0), hi);
    out.mass += p.mass;
    out.first += p.first;
    out.second += p.second;
  }
  if (lo < 0.0) {
    const Moments n = positive_moments(std::max(-hi, 0.0), -lo);
    out.mass += n.mass;
    out.first -= n.first;
    out.second += n.second;
  }
  return out;
}

}  // namespace

std::vector<double> laplacian_midtread_levels(int bits) {
  if (bits < 0 || bits > 8) fail("munkberg dct", "quantiser bits " + std::to_string(bits) + " outside [0, 8]");
  const int count = 1 << bits;
  const int negatives = count / 2 - (count > 1 ? 1 : 0);   // 2^(b-1) - 1 below zero, 2^(b-1) above (b >= 1)
  const int zero = negatives;                              // index of the level held at 0
  std::vector<double> levels(static_cast<std::size_t>(count));
  // Start from a uniform mid-tread grid of step 1 standard deviation over a few levels, scaled down for many levels.
  const double step = 3.0 / std::max(1, count / 2);
  for (int i = 0; i < count; ++i) levels[static_cast<std::size_t>(i)] = step * (i - zero);
  const double infinity = std::numeric_limits<double>::infinity();
  // Lloyd iterations converge linearly, slowly for many levels (the tail cells move little per sweep): up to 10^5
  // sweeps, stopping at a fixed point to 1e-13 (centroids within 1e-7 of the closed-form ones for every table,
  // tested).
  for (int iteration = 0; iteration < 100000; ++iteration) {
    double change = 0.0;
    for (int i = 0; i < count; ++i) {
      if (i == zero) continue;   // mid-tread: the zero level stays exactly 0
      const double lo = i == 0 ? -infinity : 0.5 * (levels[static_cast<std::size_t>(i - 1)] + levels[static_cast<std::size_t>(i)]);
      const double hi = i == count - 1 ? infinity : 0.5 * (levels[static_cast<std::size_t>(i)] + levels[static_cast<std::size_t>(i + 1)]);
      const Moments m = moments(lo, hi);
      // A cell far in the tail may have a mass below double precision: keep the level (no 0/0).
      if (!(m.mass > 0.0)) continue;
      const double centroid = m.first / m.mass;
      change = std::max(change, std::abs(centroid - levels[static_cast<std::size_t>(i)]));
      levels[static_cast<std::size_t>(i)] = centroid;
    }
    if (change < 1e-13) break;
  }
  return levels;
}

double laplacian_quantiser_distortion(const std::vector<double>& levels) {
  const double infinity = std::numeric_limits<double>::infinity();
  double total = 0.0;
  const std::size_t count = levels.size();
  for (std::size_t i = 0; i < count; ++i) {
    const double lo = i == 0 ? -infinity : 0.5 * (levels[i - 1] + levels[i]);
    const double hi = i + 1 == count ? infinity : 0.5 * (levels[i] + levels[i + 1]);
    const Moments m = moments(lo, hi);
    // int (x - y)^2 f = second - 2 y first + y^2 mass
    total += m.second - 2.0 * levels[i] * m.first + levels[i] * levels[i] * m.mass;
  }
  return total;
}

}  // namespace blocklab::munkberg
