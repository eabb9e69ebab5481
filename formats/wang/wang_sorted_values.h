// Sorting the per-texel values of a texture for the `wang` zone splits (wang_zone_split.h: eq. 2's search over every
// distinct luminance, the residual's quantiles): a least-significant-digit radix sort of the doubles' bit patterns,
// mapped so that unsigned order is numeric order (negatives' bits inverted, positives' sign bit set). For finite
// values the result is the ascending order std::sort gives (equal doubles are the same bits), except that -0.0
// sorts before +0.0; an image's texel count makes this several times faster than a comparison sort.
#pragma once

#include <vector>

namespace blocklab {
namespace wang {

// `values` in ascending order (finite values; NaN is not expected).
std::vector<double> sorted_values(const std::vector<double>& values);

}  // namespace wang
}  // namespace blocklab
