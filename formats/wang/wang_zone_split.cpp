// Zone splits of the `wang` format (formats/wang/wang_zone_split.h).
#include "formats/wang/wang_zone_split.h"

#include <algorithm>
#include <cmath>

#include "core/error.h"
#include "formats/wang/wang_sorted_values.h"
#include "formats/wang/wang_zone_problem.h"
#include "solvers/registry.h"

namespace blocklab {
namespace wang {

namespace {

constexpr std::size_t kMaxProblemSamples = 16384;
constexpr std::size_t kResidualQuantiles = 513;
constexpr std::int64_t kLuminanceLatticePoints = 4097;
constexpr std::int64_t kResidualLatticePoints = 1025;

// At most kMaxProblemSamples texels at a fixed stride, each weighted by the stride.
std::vector<ZoneSample> stride_samples(const std::vector<double>& values, const std::vector<double>& weights) {
  const std::size_t n = values.size();
  const std::size_t count = std::min(n, kMaxProblemSamples);
  std::vector<ZoneSample> samples;
  samples.reserve(count);
  const double scale = static_cast<double>(n) / static_cast<double>(count);
  for (std::size_t k = 0; k < count; ++k) {
    const std::size_t index = k * n / count;
    samples.push_back({values[index], weights[index] * scale});
  }
  return samples;
}

// Number of sorted values <= t.
double count_at_most(const std::vector<double>& sorted, double t) {
  return static_cast<double>(std::upper_bound(sorted.begin(), sorted.end(), t) - sorted.begin());
}

double eq2_two_zones(const std::vector<double>& sorted, double low, double t1, double high) {
  const double below = count_at_most(sorted, t1);
  const double above = static_cast<double>(sorted.size()) - below;
  return below * (t1 - low) / 256.0 + above * (high - t1) / 256.0;
}

double eq2_three_zones(const std::vector<double>& sorted, double low, double s1, double s2, double high) {
  const double first = count_at_most(sorted, s1);
  const double second = count_at_most(sorted, s2) - first;
  const double third = static_cast<double>(sorted.size()) - first - second;
  return first * (s1 - low) / 32.0 + second * (s2 - s1) / 64.0 + third * (high - s2) / 32.0;
}

// Split fraction of a point in [lo, hi] (0 for an empty range).
double fraction_of(double value, double lo, double hi) {
  return hi > lo ? std::clamp((value - lo) / (hi - lo), 0.0, 1.0) : 0.0;
}

template <int kZones>
std::vector<double> solve_split(const ZoneSplitError<kZones>& error, std::int64_t lattice_points,
                                const std::vector<double>& start, const SplitSearch& search) {
  const auto problem = make_zone_split_problem(error, lattice_points);
  const SolveResult result = find_solver(search.solver).solve(problem, search.options, start.data(), search.seed);
  if (result.summary.termination == Termination::failed || result.parameters.size() != start.size()) return start;
  std::vector<double> x = result.parameters;
  for (int k = 0; k < problem.dim(); ++k) x[k] = problem.lattice(k).point(problem.lattice(k).nearest_index(x[k]));
  return x;
}

}  // namespace

void check_split_solver_name(const std::string& name, const std::string& key, const std::string& who) {
  if (name == "linear") return;
  try {
    find_solver(name);
  } catch (const Error& error) {
    fail(who, "option '" + key + "': " + error.what() + " (or 'linear')");
  }
}

SplitResult fit_luminance_split(const std::vector<double>& luminances, const std::vector<double>& weights,
                                const SplitSearch& search) {
  SplitResult result;
  const std::vector<double> sorted = sorted_values(luminances);
  result.low = sorted.empty() ? 0.0 : sorted.front();
  result.high = sorted.empty() ? 0.0 : sorted.back();
  // Eq. 2 at every distinct value (the last of each run of equal values has the run in n_l).
  double best_t1 = result.low;
  double best = eq2_two_zones(sorted, result.low, best_t1, result.high);
  for (std::size_t k = 0; k < sorted.size(); ++k) {
    if (k + 1 < sorted.size() && sorted[k + 1] == sorted[k]) continue;
    const double below = static_cast<double>(k + 1);
    const double value = below * (sorted[k] - result.low) / 256.0 +
                         (static_cast<double>(sorted.size()) - below) * (result.high - sorted[k]) / 256.0;
    if (value < best) {
      best = value;
      best_t1 = sorted[k];
    }
  }
  ZoneSplitError<2> error;
  error.samples = stride_samples(luminances, weights);
  error.low = result.low;
  error.high = result.high;
  error.levels = {255.0, 255.0};
  double x = fraction_of(best_t1, result.low, result.high);
  double t1 = best_t1;
  if (search.solver != "linear") {
    x = solve_split(error, kLuminanceLatticePoints, {x}, search)[0];
    t1 = zone_bounds(error, &x)[1];
  }
  result.split = {t1};
  result.eq2 = eq2_two_zones(sorted, result.low, t1, result.high);
  // The quantisation error at the split itself (x recomputed so that the bound equals t1 exactly where possible).
  result.quantisation = error(&x);
  return result;
}

SplitResult fit_residual_split(const std::vector<double>& residuals, const std::vector<double>& weights,
                               const SplitSearch& search) {
  SplitResult result;
  const std::vector<double> sorted = sorted_values(residuals);
  result.low = sorted.empty() ? 0.0 : sorted.front();
  result.high = sorted.empty() ? 0.0 : sorted.back();
  std::vector<double> candidates;
  for (std::size_t q = 0; q < kResidualQuantiles && !sorted.empty(); ++q)
    candidates.push_back(sorted[q * (sorted.size() - 1) / (kResidualQuantiles - 1)]);
  candidates.erase(std::unique(candidates.begin(), candidates.end()), candidates.end());
  double best_s1 = result.low, best_s2 = result.high;
  double best = eq2_three_zones(sorted, result.low, best_s1, best_s2, result.high);
  for (std::size_t i = 0; i < candidates.size(); ++i)
    for (std::size_t j = i; j < candidates.size(); ++j) {
      const double value = eq2_three_zones(sorted, result.low, candidates[i], candidates[j], result.high);
      if (value < best) {
        best = value;
        best_s1 = candidates[i];
        best_s2 = candidates[j];
      }
    }
  ZoneSplitError<3> error;
  error.samples = stride_samples(residuals, weights);
  error.low = result.low;
  error.high = result.high;
  error.levels = {31.0, 63.0, 31.0};
  std::vector<double> x = {fraction_of(best_s1, result.low, result.high),
                           fraction_of(best_s2, best_s1, result.high)};
  double s1 = best_s1, s2 = best_s2;
  if (search.solver != "linear") {
    x = solve_split(error, kResidualLatticePoints, x, search);
    const auto bounds = zone_bounds(error, x.data());
    s1 = bounds[1];
    s2 = bounds[2];
  }
  result.split = {s1, s2};
  result.eq2 = eq2_three_zones(sorted, result.low, s1, s2, result.high);
  result.quantisation = error(x.data());
  return result;
}

}  // namespace wang
}  // namespace blocklab
