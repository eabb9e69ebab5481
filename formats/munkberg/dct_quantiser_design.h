// Non-uniform mid-tread quantisers for Laplacian sources, the AC quantisers of the fixed-rate DCT mode (Munkberg et
// al. 2008, section 6.2: "non-uniform midtread quantization [Say96] optimized for the Laplacian distributions given
// by the estimated variances"). Lloyd-Max design (K. Sayood, Introduction to Data Compression, section 9.6.1): the
// decision thresholds are the midpoints of neighbouring levels and every level is the centroid of its cell, iterated
// to a fixed point; the moments of the Laplacian over a cell are in closed form. Mid-tread: one level is held at
// exactly 0 (a dropped coefficient costs nothing); with 2^b levels (b bits, every code used) the remaining 2^b - 1
// split into 2^(b-1) - 1 negative and 2^(b-1) positive levels.
#pragma once

#include <vector>

namespace blocklab::munkberg {

// The 2^bits levels (ascending, one exactly 0) for a zero-mean Laplacian of unit variance; bits in [0, 8]
// (bits = 0: the single level 0). Scale by the standard deviation for another variance.
std::vector<double> laplacian_midtread_levels(int bits);

// Mean squared error of nearest-level quantisation of a unit-variance Laplacian with `levels` (ascending).
double laplacian_quantiser_distortion(const std::vector<double>& levels);

}  // namespace blocklab::munkberg
