// The fast BC6H decoder on Params (KDFS "BC6H"): endpoint sign extension and the inverse endpoint transform, endpoint
// unquantisation, BC7's interpolation ((64 - w) E0 + w E1 + 32) >> 6 with the 3-/4-bit weights, and the final
// unquantisation to half-float bits. Templated on the format's signedness (UF16 or SF16), so each variant compiles to
// its own straight-line code. The spec-literal oracle is bc6h_reference_decode.h.
#pragma once

#include <cstdint>

#include "formats/bc6h/bc6h_params.h"
#include "formats/bc7/bc7_tables.h"

namespace blocklab {
namespace bc6h {

// The four endpoints (two per subset; one-subset modes use 0 and 1) after sign extension and the inverse transform,
// still quantised (EPB-bit values; signed formats give two's complement values).
template <bool kSigned>
void endpoint_values(const Params& params, int (&endpoints)[4][3]) {
  const ModeInfo& mode = mode_info(params.mode_index);
  const int epb = mode.endpoint_bits;
  const int endpoint_count = 2 * mode.subset_count;
  for (int c = 0; c < 3; ++c) {
    const int base = kSigned ? sign_extend(params.fields[c], epb) : params.fields[c];
    endpoints[0][c] = base;
    for (int e = 1; e < endpoint_count; ++e) {
      const int bits = field_bits(mode, 3 * e + c);
      int value = params.fields[3 * e + c];
      if (kSigned || mode.transformed) value = sign_extend(value, bits);
      if (mode.transformed) {
        value = (base + value) & ((1 << epb) - 1);
        if (kSigned) value = sign_extend(value, epb);
      }
      endpoints[e][c] = value;
    }
  }
}

// Decodes to half-float bit patterns out[texel][R, G, B]; a reserved mode gives 0 everywhere.
template <bool kSigned>
void decode(const Params& params, std::uint16_t (&out)[kTexels][3]) {
  if (params.mode_index == kReservedModeIndex) {
    for (auto& texel : out) texel[0] = texel[1] = texel[2] = 0;
    return;
  }
  const ModeInfo& mode = mode_info(params.mode_index);
  int endpoints[4][3];
  endpoint_values<kSigned>(params, endpoints);
  int unquantized[4][3];
  for (int e = 0; e < 2 * mode.subset_count; ++e)
    for (int c = 0; c < 3; ++c) unquantized[e][c] = unquantize(endpoints[e][c], mode.endpoint_bits, kSigned);
  const int* weights = bc7::index_weights(index_bits(mode.subset_count));
  const std::uint8_t* subsets = bc7::partition_subsets(mode.subset_count, mode.subset_count == 2 ? params.partition : 0);
  for (int texel = 0; texel < kTexels; ++texel) {
    const int subset = subsets[texel];
    const int weight = weights[params.indices[texel]];
    for (int c = 0; c < 3; ++c) {
      const int interpolated =
          ((64 - weight) * unquantized[2 * subset][c] + weight * unquantized[2 * subset + 1][c] + 32) >> 6;
      out[texel][c] = finish_unquantize(interpolated, kSigned);
    }
  }
}

inline void decode(const Params& params, bool is_signed, std::uint16_t (&out)[kTexels][3]) {
  if (is_signed)
    decode<true>(params, out);
  else
    decode<false>(params, out);
}

}  // namespace bc6h
}  // namespace blocklab
