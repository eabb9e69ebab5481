// The luminance histogram eq. 3 is evaluated on (formats/banterle/tmo_fit_problem.h).
#include "formats/banterle/tmo_fit_problem.h"

#include <algorithm>

namespace blocklab {

std::vector<double> counted_log2_luminances(const std::vector<double>& luminances) {
  std::vector<double> result;
  result.reserve(luminances.size());
  const double floor_value = std::exp2(kTmoLog2Floor);
  for (double value : luminances)
    if (value > floor_value) result.push_back(std::log2(value));   // NaN and values at the floor are not counted
  return result;
}

LuminanceHistogram build_luminance_histogram(const std::vector<double>& luminances) {
  LuminanceHistogram histogram;
  histogram.total = luminances.size();
  const std::vector<double> logs = counted_log2_luminances(luminances);
  histogram.counted = logs.size();
  if (logs.empty()) {
    // Nothing above the floor: every bin empty, the error is 0 for every parameter.
    for (int b = 0; b < kTmoHistogramBins; ++b) histogram.log2_luminance[static_cast<std::size_t>(b)] = kTmoLog2Floor;
    return histogram;
  }
  const auto [min_it, max_it] = std::minmax_element(logs.begin(), logs.end());
  histogram.log2_min = *min_it;
  histogram.log2_max = *max_it;
  // A single luminance value: give the range a nominal width so the bin arithmetic stays finite.
  const double width = std::max(histogram.log2_max - histogram.log2_min, 1e-6);
  const double bins_per_unit = kTmoHistogramBins / width;
  std::array<double, kTmoHistogramBins> sums{};
  std::array<std::size_t, kTmoHistogramBins> counts{};
  for (double l : logs) {
    int bin = static_cast<int>((l - histogram.log2_min) * bins_per_unit);
    bin = std::min(std::max(bin, 0), kTmoHistogramBins - 1);   // the maximum lands on the last bin
    sums[static_cast<std::size_t>(bin)] += l;
    ++counts[static_cast<std::size_t>(bin)];
  }
  const double counted = static_cast<double>(logs.size());
  for (std::size_t b = 0; b < sums.size(); ++b) {
    histogram.weight[b] = static_cast<double>(counts[b]) / counted;
    histogram.log2_luminance[b] = counts[b] > 0 ? sums[b] / static_cast<double>(counts[b])
                                                : histogram.log2_min + (static_cast<double>(b) + 0.5) / bins_per_unit;
  }
  return histogram;
}

}  // namespace blocklab
