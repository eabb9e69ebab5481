// The search-time BC7 decoder: symbolic Params -> 16 texels (DESIGN.md "decode<T>"), bit-exact with the KDFS
// "BPTC" decoding procedure (interpolation ((64 - w) * E0 + w * E1 + 32) >> 6 on 8-bit expanded endpoints,
// rotation applied after interpolation). The arithmetic is integer; T is the scalar type the 8-bit results are
// delivered in (std::uint8_t, int, float, double, ceres::Jet, Interval: any type constructible from int), so an
// error functor written on T can compare decoded texels with its own values without conversions.
// The independent oracle is bc7_reference_decode.h (tests: decode(unpack(b)) == reference_decode(b)).
#pragma once

#include <utility>

#include "formats/bc7/bc7_params.h"

namespace blocklab {
namespace bc7 {

// Decodes `params` into out[texel][R, G, B, A] (8-bit code values 0..255 as T). The reserved mode gives 0 in
// every channel (KDFS: decoders "should return 0 for all channels").
template <typename T>
void decode(const Params& params, T (&out)[kTexels][4]) {
  if (params.mode == kReservedMode) {
    for (auto& texel : out)
      for (auto& value : texel) value = T(0);
    return;
  }
  const ModeInfo& info = mode_info(params.mode);
  int expanded[3][2][4];
  for (int subset = 0; subset < info.subset_count; ++subset)
    for (int endpoint = 0; endpoint < 2; ++endpoint)
      for (int channel = 0; channel < 4; ++channel)
        expanded[subset][endpoint][channel] = expanded_endpoint(params, subset, endpoint, channel);
  const std::uint8_t* subsets = partition_subsets(info.subset_count, params.partition);
  // Modes 4 and 5 have two index sets; index selection (mode 4) swaps which one colour uses.
  const bool two_index_sets = info.index2_bits > 0;
  const bool colour_uses_secondary = two_index_sets && params.index_selection == 1;
  const int* colour_weights = index_weights(colour_uses_secondary ? info.index2_bits : info.index_bits);
  const int* alpha_weights =
      index_weights(two_index_sets ? (colour_uses_secondary ? info.index_bits : info.index2_bits) : info.index_bits);
  for (int texel = 0; texel < kTexels; ++texel) {
    const int subset = subsets[texel];
    const int colour_index = colour_uses_secondary ? params.indices2[texel] : params.indices[texel];
    const int alpha_index =
        two_index_sets ? (colour_uses_secondary ? params.indices[texel] : params.indices2[texel]) : params.indices[texel];
    int value[4];
    for (int channel = 0; channel < 3; ++channel)
      value[channel] = interpolate(expanded[subset][0][channel], expanded[subset][1][channel], colour_weights[colour_index]);
    value[3] = interpolate(expanded[subset][0][3], expanded[subset][1][3], alpha_weights[alpha_index]);
    // Rotation 1..3 swaps alpha with R, G or B after interpolation; 0 is no rotation.
    if (params.rotation > 0) std::swap(value[3], value[params.rotation - 1]);
    for (int channel = 0; channel < 4; ++channel) out[texel][channel] = T(value[channel]);
  }
}

}  // namespace bc7
}  // namespace blocklab
