// Figure 8 of Munkberg et al. 2008, section 7.3 (per-block log-luminance range); see luminance_range_histogram.h.
#include "formats/munkberg/analysis/luminance_range_histogram.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "core/blocks.h"
#include "formats/munkberg/munkberg_color_spaces.h"
#include "core/error.h"

namespace blocklab::munkberg {

namespace {
constexpr const char* kOwner = "munkberg luminance histogram";
}

double range_for_precision_bits(int bits) {
  if (bits < 1 || bits > 30) fail(kOwner, "precision bits must be in [1, 30], got " + std::to_string(bits));
  // Eq. 16 for the half range with k bits equals eq. 16 for the block range with the index bits.
  return std::ldexp(kHalfLogLuminanceSpan, kLuminanceIndexBits - bits);
}

BlockLuminanceRanges block_log_luminance_ranges(const Image& image) {
  BlockLuminanceRanges out;
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x) {
      const float* p = image.texel(x, y);
      const double luminance = kRec601WeightR * p[0] + kRec601WeightG * p[1] + kRec601WeightB * p[2];
      // Black: Y = 0 exactly (also a negative Y, which the input policy never lets through).
      if (!(luminance > 0.0)) ++out.black_texels;
    }
  const BlockGrid grid(image.width, image.height);
  out.blocks = grid.block_count();
  out.ranges.reserve(out.blocks);
  for (std::size_t b = 0; b < out.blocks; ++b) {
    const BlockTexels block = load_block(image, grid, b);
    double lo = 0.0, hi = 0.0;
    bool any = false;
    for (const auto& t : block.rgba) {
      const Rgb<double> rgb{t[0], t[1], t[2]};
      const double luminance = kRec601WeightR * rgb.r + kRec601WeightG * rgb.g + kRec601WeightB * rgb.b;
      // Black texels are excluded (eq. 3 codes them apart; their log is -infinity).
      if (!(luminance > 0.0)) continue;
      const double log_luminance = rgb_to_logyuv(rgb).log_luminance;
      lo = any ? std::min(lo, log_luminance) : log_luminance;
      hi = any ? std::max(hi, log_luminance) : log_luminance;
      any = true;
    }
    // An all-black block has no range: counted apart, not as range 0.
    if (!any) {
      ++out.black_blocks;
      continue;
    }
    out.ranges.push_back(hi - lo);
  }
  return out;
}

std::vector<std::uint64_t> range_histogram(const std::vector<double>& ranges, double bin_width, int bins) {
  if (!(bin_width > 0.0) || !std::isfinite(bin_width)) fail(kOwner, "bin width must be a finite number > 0");
  if (bins < 1) fail(kOwner, "the histogram needs at least one bin, got " + std::to_string(bins));
  std::vector<std::uint64_t> counts(static_cast<std::size_t>(bins), 0);
  for (double r : ranges) {
    // A NaN range has no bin (and would make the float-to-int conversion below undefined).
    if (std::isnan(r)) fail(kOwner, "a block range is NaN");
    // floor(r / w) clamped to the last bin (the overflow bin), and to 0 for a (never produced) negative range.
    const double position = std::floor(r / bin_width);
    const int bin = position >= bins - 1 ? bins - 1 : position <= 0.0 ? 0 : static_cast<int>(position);
    ++counts[static_cast<std::size_t>(bin)];
  }
  return counts;
}

double fraction_within(const std::vector<double>& ranges, double limit) {
  // No blocks: 0 rather than 0/0.
  if (ranges.empty()) return 0.0;
  const auto within = std::count_if(ranges.begin(), ranges.end(), [limit](double r) { return r <= limit; });
  return static_cast<double>(within) / static_cast<double>(ranges.size());
}

}  // namespace blocklab::munkberg
