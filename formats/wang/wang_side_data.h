// Per-texture side data of the `wang` format (EncodedTexture::side_data, stored in the .blk JSON header): the
// constants of the section 3.4 shader, as the zones they come from (wang_shader.h derives the float constants).
//   luminance_zones        [tmin, t1, tmax]           l_bits=2x6: eq. 3 zones; tmin <= t1 <= tmax
//   luminance_range        [tmin, tmax]               l_bits=1x12: the one uniform range; tmin <= tmax
//   residual_zones         [smin, s1, s2, smax]       residual=s|ratio: eq. 6 zones of S (or T); non-decreasing
//   luminance_split_error  [eq2, quantisation]        record of the t1 search (2x6 only, optional; not decoded):
//                                                     eq. 2 at the chosen t1 and the zone quantisation error
//                                                     (wang_zone_problem.h)
//   residual_split_error   [eq2, quantisation]        the same for (s1, s2) (optional; not decoded)
// Every value must be finite with magnitude <= 1e30 (so the float constants and their sums stay finite). Any other
// key, a missing key, a wrong count or an unordered zone list is an Error naming the key and the values.
#pragma once

#include <string>

#include "formats/format.h"
#include "formats/wang/wang_shader.h"

namespace blocklab {
namespace wang {

struct SideData {
  Zones zones;
  bool has_split_records = false;
  double luminance_split_eq2 = 0.0, luminance_split_quantisation = 0.0;
  double residual_split_eq2 = 0.0, residual_split_quantisation = 0.0;
};

void store_side_data(const SideData& data, LuminanceSplit split, Residual residual, EncodedTexture& texture);
// Reads and validates; throws Error("<who>: side data ...").
SideData read_side_data(const EncodedTexture& texture, LuminanceSplit split, Residual residual,
                        const std::string& who);

}  // namespace wang
}  // namespace blocklab
