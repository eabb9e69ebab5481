// Deterministic reductions over image rows, and the error-map builder every metric shares.
//
// Rows may be processed in parallel (core/parallel.h, all hardware threads), but every row writes only its own
// partial sums, each row sums its pixels left to right, and the partial sums are then added in row order (top row
// first). The floating-point result is therefore identical for any thread count and any scheduling.
#pragma once

#include <cstddef>
#include <functional>
#include <vector>

#include "core/image.h"

namespace blocklab {

// Returns sum over y = 0..height-1 of row_sum(y), added in row order.
double sum_rows_in_order(int height, const std::function<double(int y)>& row_sum);

// Vector form: row_sums(y, out) adds `accumulator_count` partial sums for row y into out[0..count) (out starts at
// zero). Returns the element-wise sums over all rows, added in row order.
std::vector<double> sum_rows_in_order(int height, std::size_t accumulator_count,
                                      const std::function<void(int y, double* out)>& row_sums);

// A width x height, 3-channel image with R = G = B = pixel_value(x, y) (stored as float) and alpha 1.
Image make_error_map(int width, int height, const std::function<double(int x, int y)>& pixel_value);

}  // namespace blocklab
