// Training of the fixed-rate DCT mode's tables (Munkberg et al. 2008, section 6.2: "we estimated the variance of
// each DCT coefficient over all 4x4 blocks in a set of 18 HDR images ... These estimated variances were used to find
// a bit allocation table that minimizes the average reconstruction error using Lagrange minimization").
//   1. Statistics: over every whole 4x4 block of the training images, the mean square of each coefficient of each
//      channel (targets as the encoder's, dct_block_targets); for DC, of its distance to the middle of its range
//      (what 0 DC bits would cost). AC means are ~0, and the quantisers are centred at 0, so the mean square is the
//      variance the paper's Laplacian model needs.
//   2. Distortion model per coefficient and bit count: AC, the Lloyd-Max mid-tread quantiser of the Laplacian with
//      that variance (dct_quantiser_design.h), D = mean square x its unit-variance distortion; DC, the uniform
//      quantiser's step^2 / 12 (at most the 0-bit cost).
//   3. Per channel, the Lagrangian allocation of the budget (dct_bit_allocation.h), then the AC levels scaled to
//      each coefficient's standard deviation.
// Deterministic: images in the given order, sums in a fixed order, no threads.
#pragma once

#include <array>
#include <vector>

#include "core/image.h"
#include "formats/munkberg/dct_tables.h"

namespace blocklab::munkberg {

struct DctTrainingStatistics {
  std::array<std::array<double, kDctCoefficientCount>, kDctChannelCount> sum_square{};
  long long blocks = 0;
};

// Adds every whole 4x4 block of `image` (finite, non-negative RGB; partial edge blocks are left out). Returns the
// number of blocks added.
long long accumulate_dct_statistics(const Image& image, DctTrainingStatistics* statistics);

// Step 2 for one channel: distortion[k][b] of coefficient k with b bits, from the mean squares (k = 0: DC's distance
// to the middle of the range of `channel`).
std::vector<std::vector<double>> dct_distortion_curves(const std::array<double, kDctCoefficientCount>& mean_square,
                                                       int channel);

// Steps 2 and 3 (Error when no block was accumulated).
DctTables design_dct_tables(const DctTrainingStatistics& statistics, const DctTrainingProvenance& provenance);

}  // namespace blocklab::munkberg
