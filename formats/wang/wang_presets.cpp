// Presets of the `wang` encoder (formats/wang/wang_presets.h).
#include "formats/wang/wang_presets.h"

#include "core/error.h"
#include "core/options.h"

namespace blocklab {
namespace wang {

const std::vector<std::string>& preset_names() {
  static const std::vector<std::string> names = {"fast", "medium", "thorough"};
  return names;
}

SearchEffort preset_effort(const std::string& name, const std::string& who) {
  SearchEffort effort;
  if (name == "fast") {
    effort.s3tc = S3tcSearch::fast;
    effort.luminance_start = S3tcSearch::fast;
    effort.descent_passes = 0;
    effort.residual_candidates = 1;
    effort.residual_rounds = 2;
  } else if (name == "medium") {
    // Measured on the 28 HDR images (2026-11-27, formats/wang/README.md "Presets"): against the refined start and
    // steps +-1..16 in 2 passes, the range start and steps +-1, 2 in 3 passes take 20 % less time, with mean
    // log2[RGB] 1.031 -> 1.020, mPSNR 39.84 -> 40.20 dB, psnr_li2005 61.50 -> 61.44 dB (the descent's own error E
    // is not what these metrics measure: a longer descent lowers E and psnr_li2005 but raises log2[RGB]).
    effort.luminance_start = S3tcSearch::fast;
    effort.descent_steps = {1, 2};
    effort.descent_passes = 3;
  } else if (name == "thorough") {
    effort.descent_passes = 8;
    effort.descent_steps = {1, 2, 3, 4, 6, 8, 12, 16, 24, 32, 48, 64, 96, 128};
    effort.search_inactive_channel = true;
    effort.residual_candidates = 8;
    effort.residual_rounds = 8;
  } else {
    fail(who, "option 'effort': unknown effort '" + name + "'; valid values: " + join_names(preset_names()));
  }
  return effort;
}

}  // namespace wang
}  // namespace blocklab
