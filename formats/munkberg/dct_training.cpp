// Training of the DCT mode's tables (formats/munkberg/dct_training.h; Munkberg et al. 2008, section 6.2).
#include "formats/munkberg/dct_training.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "core/error.h"
#include "formats/munkberg/dct_bit_allocation.h"
#include "formats/munkberg/dct_encoder.h"
#include "formats/munkberg/dct_quantiser_design.h"

namespace blocklab::munkberg {

long long accumulate_dct_statistics(const Image& image, DctTrainingStatistics* statistics) {
  long long added = 0;
  for (int by = 0; by + 4 <= image.height; by += 4)
    for (int bx = 0; bx + 4 <= image.width; bx += 4) {
      BlockTexels texels;
      for (int i = 0; i < kTexels; ++i) {
        const float* p = image.pixels.data() + (static_cast<std::size_t>(by + i / 4) * static_cast<std::size_t>(image.width) +
                                                static_cast<std::size_t>(bx + i % 4)) * 4;
        for (int c = 0; c < 4; ++c) texels.rgba[i][c] = p[c];
      }
      const DctChannelSamples targets = dct_block_targets(texels, kDctBlackTarget);
      for (int c = 0; c < kDctChannelCount; ++c) {
        const std::array<double, kDctCoefficientCount> coefficients = forward_dct(targets[static_cast<std::size_t>(c)]);
        for (int k = 0; k < kDctCoefficientCount; ++k) {
          // DC: its distance to the middle of the range (the 0-bit reconstruction); AC: the coefficient itself.
          const double centre = k == 0 ? 0.5 * (kDctDcMin[static_cast<std::size_t>(c)] + kDctDcMax[static_cast<std::size_t>(c)]) : 0.0;
          const double d = coefficients[static_cast<std::size_t>(k)] - centre;
          statistics->sum_square[static_cast<std::size_t>(c)][static_cast<std::size_t>(k)] += d * d;
        }
      }
      ++added;
    }
  statistics->blocks += added;
  return added;
}

namespace {

// Unit-variance Laplacian quantisers (index: bits), designed once.
const std::vector<std::vector<double>>& unit_levels() {
  static const std::vector<std::vector<double>> levels = [] {
    std::vector<std::vector<double>> out;
    for (int b = 0; b <= kDctMaxAcBits; ++b) out.push_back(laplacian_midtread_levels(b));
    return out;
  }();
  return levels;
}

}  // namespace

std::vector<std::vector<double>> dct_distortion_curves(const std::array<double, kDctCoefficientCount>& mean_square,
                                                       int channel) {
  const std::size_t cc = static_cast<std::size_t>(channel);
  std::vector<std::vector<double>> distortion(kDctCoefficientCount);
  for (int k = 0; k < kDctCoefficientCount; ++k) {
    const std::size_t kk = static_cast<std::size_t>(k);
    if (k == 0) {
      distortion[kk].push_back(mean_square[kk]);
      for (int b = 1; b <= kDctMaxDcBits; ++b) {
        const double step = (kDctDcMax[cc] - kDctDcMin[cc]) / static_cast<double>((1 << b) - 1);
        distortion[kk].push_back(std::min(mean_square[kk], step * step / 12.0));
      }
    } else {
      for (int b = 0; b <= kDctMaxAcBits; ++b)
        distortion[kk].push_back(mean_square[kk] * laplacian_quantiser_distortion(unit_levels()[static_cast<std::size_t>(b)]));
    }
  }
  return distortion;
}

DctTables design_dct_tables(const DctTrainingStatistics& statistics, const DctTrainingProvenance& provenance) {
  if (statistics.blocks <= 0) fail("munkberg dct training", "no whole 4x4 block in the training images");
  DctTables tables;
  tables.provenance = provenance;
  tables.provenance.blocks = statistics.blocks;
  for (int c = 0; c < kDctChannelCount; ++c) {
    const std::size_t cc = static_cast<std::size_t>(c);
    DctChannelTable& table = tables.channel[cc];
    table.dc_min = kDctDcMin[cc];
    table.dc_max = kDctDcMax[cc];
    for (int k = 0; k < kDctCoefficientCount; ++k)
      table.mean_square[static_cast<std::size_t>(k)] =
          statistics.sum_square[cc][static_cast<std::size_t>(k)] / static_cast<double>(statistics.blocks);
    const std::vector<int> bits = lagrangian_bit_allocation(dct_distortion_curves(table.mean_square, c), kDctChannelBudget[cc]);
    for (int k = 0; k < kDctCoefficientCount; ++k) {
      const std::size_t kk = static_cast<std::size_t>(k);
      table.bits[kk] = bits[kk];
      if (k == 0 || bits[kk] == 0) continue;
      // A coefficient that never varied in training still gets distinct levels (the table must be strictly
      // increasing): its scale is floored at 1e-6, far below any step that matters.
      const double sigma = std::max(std::sqrt(table.mean_square[kk]), 1e-6);
      for (const double level : unit_levels()[static_cast<std::size_t>(bits[kk])]) table.levels[kk].push_back(level * sigma);
    }
  }
  return tables;
}

}  // namespace blocklab::munkberg
