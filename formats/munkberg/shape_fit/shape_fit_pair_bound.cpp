// The pair bound of the shape fit's box enclosure (formats/munkberg/shape_fit/shape_fit_pair_bound.h).
#include "formats/munkberg/shape_fit/shape_fit_pair_bound.h"

#include <algorithm>
#include <limits>

#include "formats/munkberg/shape_fit/outward_bounds.h"

namespace blocklab::shape_fit_detail {

void LandmarkDifferences::set(int k, int l, bool u_coordinate, double lower, double upper) {
  double(&lowers)[kShapeLandmarkCount][kShapeLandmarkCount] = u_coordinate ? u_lower : v_lower;
  double(&uppers)[kShapeLandmarkCount][kShapeLandmarkCount] = u_coordinate ? u_upper : v_upper;
  lowers[k][l] = lower;
  uppers[k][l] = upper;
  // M_l - M_k = -(M_k - M_l): negation is exact.
  lowers[l][k] = -upper;
  uppers[l][k] = -lower;
}

namespace {

// Distance from the interval [a, b] (a <= b) to the enclosure [lower, upper], rounded down: 0 when they meet.
double gap_below(double a, double b, double lower, double upper) {
  return std::max(0.0, std::max(widen_down(lower - b), widen_down(a - upper)));
}

}  // namespace

double pair_lower_bound(const ShapeFitError& error, int i, int j, const double* i_lower, const double* j_lower,
                        const LandmarkDifferences& differences) {
  const std::size_t ii = static_cast<std::size_t>(i), jj = static_cast<std::size_t>(j);
  const double wi = error.weights[ii], wj = error.weights[jj];
  // w_i w_j / (w_i + w_j), rounded down: exactly 1/2 for unit weights (the default).
  const double factor =
      wi == 1.0 && wj == 1.0 ? 0.5 : std::max(0.0, widen_down(widen_down(wi * wj) / widen_up(wi + wj)));
  // t_i - t_j, enclosed (one rounding each).
  const double du = error.target_u[ii] - error.target_u[jj], dv = error.target_v[ii] - error.target_v[jj];
  const double du_lower = widen_down(du), du_upper = widen_up(du);
  const double dv_lower = widen_down(dv), dv_upper = widen_up(dv);
  // The points' own natural bounds, weighted (unit weights need no product).
  double i_weighted[kShapeLandmarkCount], j_weighted[kShapeLandmarkCount];
  for (int k = 0; k < kShapeLandmarkCount; ++k) {
    i_weighted[k] = wi == 1.0 ? i_lower[k] : std::max(0.0, widen_down(wi * i_lower[k]));
    j_weighted[k] = wj == 1.0 ? j_lower[k] : std::max(0.0, widen_down(wj * j_lower[k]));
  }
  double best = std::numeric_limits<double>::infinity();
  for (int k = 0; k < kShapeLandmarkCount; ++k)
    for (int l = 0; l < kShapeLandmarkCount; ++l) {
      const double natural = widen_down(i_weighted[k] + j_weighted[l]);
      // The (k, l) term is max(natural, coupled) >= natural: it cannot lower the minimum so far.
      if (natural >= best) continue;
      const double gap_u = gap_below(du_lower, du_upper, differences.u_lower[k][l], differences.u_upper[k][l]);
      const double gap_v = gap_below(dv_lower, dv_upper, differences.v_lower[k][l], differences.v_upper[k][l]);
      const double coupled = widen_down(factor * widen_down(widen_down(gap_u * gap_u) + widen_down(gap_v * gap_v)));
      best = std::min(best, std::max(natural, coupled));
    }
  // Rounding may leave a bound a hair below 0; every term is >= 0.
  return std::max(0.0, best);
}

}  // namespace blocklab::shape_fit_detail
