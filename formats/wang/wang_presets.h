// Search effort of the `wang` encoder (option `effort`, set by the format's presets of the same names): how hard the 1D codec (wang_luminance_codec.h,
// wang_residual_codec.h) and the BC3 colour encoder of the chroma work. The zone splits (wang_zone_split.h) are
// the same at every preset.
//
//   preset     chroma / bc3 codec   luminance 1D codec                          residual 1D codec
//   fast       S3TC search fast     start only (BC4 range fit of eq. 3 targets)  1 table colour per endpoint,
//              (alpha fit fast)     + joint code choice                          2 Lloyd rounds
//   medium     S3TC search default  BC4 range start + coordinate descent,        3 x 3 table colours, 4 rounds
//   (default)                       steps +-1, 2, 3 passes, active channels only
//   thorough   S3TC search default  refined BC4 start + steps +-1,2,3,4,6,...,   8 x 8 table colours, 8 rounds
//                                   96,128, 8 passes, inactive channel searched
// Every preset's descent runs from every mode pair of the active channels.
#pragma once

#include <string>
#include <vector>

#include "formats/common/s3tc_color_fit.h"

namespace blocklab {
namespace wang {

struct SearchEffort {
  S3tcSearch s3tc = S3tcSearch::standard;   // chroma colour block; the codec=bc3 blocks
  S3tcSearch luminance_start = S3tcSearch::standard;   // the 1D codec's start: BC4 fit (8-value) of the eq. 3 targets
  int descent_passes = 4;                   // luminance coordinate-descent passes (0 = none)
  std::vector<int> descent_steps;           // endpoint steps (+-) tried per endpoint and pass
  bool search_inactive_channel = false;     // also search the alpha channel a single-zone block does not need
  int residual_candidates = 3;              // table colours tried per residual endpoint
  int residual_rounds = 4;                  // 1D Lloyd rounds of the residual palette
};

const std::vector<std::string>& preset_names();
// Throws Error("<who>: option 'effort': ...") on an unknown name.
SearchEffort preset_effort(const std::string& name, const std::string& who);

}  // namespace wang
}  // namespace blocklab
