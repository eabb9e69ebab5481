// The colour-space planes of `mavridis` held in 8-bit textures (Mavridis & Papaioannou 2012, section 3.5: "when
// operating with 8-bit textures on the GPU, which is the focus of this paper, YCoCg-R preserves one more bit of
// chrominance precision compared to YCoCg"; Table 6's first stage, "YCoCg-R", loses PSNR to "the chrominance range
// expansion"). Option `color_storage=unorm8` applies it to the Y, Co, Cg planes straight after the colour transform,
// before chroma subsampling and the wavelet; the decoder is unchanged (it reconstructs real values, as a shader does).
//
// * YCoCg-R (integer lifting): Y is 0..255 and stored exactly. Co and Cg (-255..255, one extra bit) are stored with
//   the plane's minimum as offset: exactly where the plane spans at most 256 values ("in more than half of the cases
//   YCoCg-R can operate entirely in 8-bits without any loss of precision"), otherwise at step 2 ("one bit of
//   chrominance precision will be lost"): the low bit dropped, the value restored to the middle of its pair.
// * YCoCg and YCbCr (real-valued): each value rounded to an 8-bit code, Y on 0..255 and the chroma offset by 128
//   (codes clamped to 0..255), as an RGBA8 texture holds them: YCoCg loses its two fractional bits of Y and Cg and
//   one of Co, the precision the paper says it needs beyond RGB.
#pragma once

#include <algorithm>
#include <cmath>

#include "formats/mavridis/mavridis_plane_codec.h"

namespace blocklab {
namespace mavridis {

// A YCoCg-R chroma plane (integers in -255..255) as an 8-bit texture offset by its minimum.
inline void store_ycocg_r_chroma_unorm8(Plane& plane) {
  if (plane.values.empty()) return;
  const auto [low, high] = std::minmax_element(plane.values.begin(), plane.values.end());
  const double minimum = *low;
  if (*high - minimum <= 255.0) return;   // fits in 256 codes: exact
  for (double& v : plane.values) v = minimum + 2.0 * std::floor((v - minimum) / 2.0) + 0.5;
}

// A real value as the 8-bit code that holds it: value + offset rounded and clamped to 0..255, minus the offset
// (offset 0 for Y, 128 for chroma).
inline double unorm8_code(double value, double offset) {
  return std::clamp(std::round(value + offset), 0.0, 255.0) - offset;
}

// A real-valued plane as 8-bit codes.
inline void store_unorm8(Plane& plane, double offset) {
  for (double& v : plane.values) v = unorm8_code(v, offset);
}

}  // namespace mavridis
}  // namespace blocklab
