// Deterministic row-ordered reductions and the error-map builder (see row_reduction.h).
#include "metrics/row_reduction.h"

#include "core/parallel.h"

namespace blocklab {

namespace {
constexpr int kAllHardwareThreads = 0;
}

double sum_rows_in_order(int height, const std::function<double(int y)>& row_sum) {
  std::vector<double> partial(static_cast<std::size_t>(height), 0.0);
  parallel_for_index(partial.size(), kAllHardwareThreads,
                     [&](std::size_t y) { partial[y] = row_sum(static_cast<int>(y)); });
  double total = 0.0;
  for (const double p : partial) total += p;   // fixed row order: the result does not depend on the threads
  return total;
}

std::vector<double> sum_rows_in_order(int height, std::size_t accumulator_count,
                                      const std::function<void(int y, double* out)>& row_sums) {
  std::vector<double> partial(static_cast<std::size_t>(height) * accumulator_count, 0.0);
  parallel_for_index(static_cast<std::size_t>(height), kAllHardwareThreads, [&](std::size_t y) {
    row_sums(static_cast<int>(y), partial.data() + y * accumulator_count);
  });
  std::vector<double> total(accumulator_count, 0.0);
  for (std::size_t y = 0; y < static_cast<std::size_t>(height); ++y)
    for (std::size_t k = 0; k < accumulator_count; ++k) total[k] += partial[y * accumulator_count + k];
  return total;
}

Image make_error_map(int width, int height, const std::function<double(int x, int y)>& pixel_value) {
  Image map(width, height, 3);
  parallel_for_index(static_cast<std::size_t>(height), kAllHardwareThreads, [&](std::size_t row) {
    const int y = static_cast<int>(row);
    for (int x = 0; x < width; ++x) {
      const float v = static_cast<float>(pixel_value(x, y));
      float* texel = map.texel(x, y);
      texel[0] = texel[1] = texel[2] = v;
    }
  });
  return map;
}

}  // namespace blocklab
