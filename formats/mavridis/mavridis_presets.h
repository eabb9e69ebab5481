// Presets of the `mavridis` encoder (option `effort`, set by the format's presets of the same names): the section 3.2 brute-force grid of the clamped outlier
// fraction and the gamma of the wavelet bands, searched per plane on the real decoded error with the `fast` BC3
// fit, and the BC3 / BC4 search effort of the final blocks.
//
//   preset     clamp grid                     gamma grid           final BC3 / BC4 search   BC7 (packing=bc7)
//   fast       0.26 (the paper's typical)     0.86 (the paper's)   fast, no search          1 partition, 1 round, no P-bit search
//   medium     0, 0.1, 0.2, 0.3, 0.4          0.7, 0.8, 0.9, 1     default                  4 partitions, 2 rounds, P-bits (bc7's defaults)
//   thorough   0, 0.05, ..., 0.5              0.6, 0.65, ..., 1    default                  16 partitions, 3 rounds, P-bits
//   none       0 (exact range)                1 (linear)           default                  as medium  (effort=none only, no preset)
#pragma once

#include <string>
#include <vector>

#include "core/error.h"
#include "core/options.h"
#include "formats/common/s3tc_color_fit.h"

namespace blocklab {
namespace mavridis {

struct SearchEffort {
  std::vector<double> clamps, gammas;
  S3tcSearch final_search = S3tcSearch::standard;
  // The BC7 packing's encoder (formats/bc7/bc7_mode_search.h EncoderSettings): partitions fitted per partitioned
  // mode, least-squares rounds per subset, P-bit search.
  int bc7_partitions = 4, bc7_refine_iterations = 2;
  bool bc7_pbit_search = true;
};

inline const std::vector<std::string>& preset_names() {
  static const std::vector<std::string> names = {"fast", "medium", "thorough"};
  return names;
}

// The values of option `effort`: the presets' and `none` (no section 3.2 optimisation: clamp 0, gamma 1, the
// exact coefficient ranges mapped linearly; medium's BC3 / BC4 / BC7 search), the baseline of the search's gain.
inline const std::vector<std::string>& effort_names() {
  static const std::vector<std::string> names = {"fast", "medium", "thorough", "none"};
  return names;
}

inline std::vector<double> grid(double first, double step, int count) {
  std::vector<double> values;
  for (int k = 0; k < count; ++k) values.push_back(first + step * k);
  return values;
}

inline SearchEffort preset_effort(const std::string& name, const std::string& who) {
  SearchEffort effort;
  if (name == "fast") {
    effort.clamps = {0.26};
    effort.gammas = {0.86};
    effort.final_search = S3tcSearch::fast;
    effort.bc7_partitions = 1;
    effort.bc7_refine_iterations = 1;
    effort.bc7_pbit_search = false;
  } else if (name == "medium") {
    effort.clamps = grid(0.0, 0.1, 5);
    effort.gammas = grid(0.7, 0.1, 4);
  } else if (name == "thorough") {
    effort.clamps = grid(0.0, 0.05, 11);
    effort.gammas = grid(0.6, 0.05, 9);
    effort.bc7_partitions = 16;
    effort.bc7_refine_iterations = 3;
  } else if (name == "none") {
    effort.clamps = {0.0};
    effort.gammas = {1.0};
  } else {
    fail(who, "option 'effort': unknown effort '" + name + "'; valid values: " + join_names(effort_names()));
  }
  return effort;
}

}  // namespace mavridis
}  // namespace blocklab
