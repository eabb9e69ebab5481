// Packing, unpacking, canonical forms and the double decoder of one BC4 block (formats/bc4/bc4_block.h).
// Layout from the Khronos Data Format Specification, RGTC chapter (SPECS.md 2.2).
#include "formats/bc4/bc4_block.h"

#include <string>
#include <utility>

#include "core/error.h"

namespace blocklab {

void pack_bc4_block(const Bc4Params& params, std::uint8_t* bytes, const char* who) {
  for (int e = 0; e < 2; ++e)
    if (params.endpoints[e] < 0 || params.endpoints[e] > 255)
      fail(who, "endpoint " + std::to_string(e) + " = " + std::to_string(params.endpoints[e]) +
                    " is outside 0..255");
  for (int texel = 0; texel < 16; ++texel)
    if (params.indices[texel] > 7)
      fail(who, "texel " + std::to_string(texel) + " code " + std::to_string(params.indices[texel]) +
                    " does not fit in 3 bits");
  // The decoder decides the mode from the endpoint order, so a disagreeing mode would decode differently.
  const bool ordered = params.endpoints[0] > params.endpoints[1];
  if (params.mode == Bc4Mode::eight_value && !ordered)
    fail(who, "8-value mode needs red0 > red1 (got " + std::to_string(params.endpoints[0]) + " and " +
                  std::to_string(params.endpoints[1]) + "); canonicalise first");
  if (params.mode == Bc4Mode::six_value && ordered)
    fail(who, "6-value mode needs red0 <= red1 (got " + std::to_string(params.endpoints[0]) + " and " +
                  std::to_string(params.endpoints[1]) + "); canonicalise first");
  bytes[0] = static_cast<std::uint8_t>(params.endpoints[0]);
  bytes[1] = static_cast<std::uint8_t>(params.endpoints[1]);
  std::uint64_t field = 0;
  for (int texel = 0; texel < 16; ++texel) field |= static_cast<std::uint64_t>(params.indices[texel]) << (3 * texel);
  for (int b = 0; b < 6; ++b) bytes[2 + b] = static_cast<std::uint8_t>((field >> (8 * b)) & 0xFFu);   // LE 48 bits
}

Bc4Params unpack_bc4_block(const std::uint8_t* bytes) {
  Bc4Params params;
  params.endpoints = {bytes[0], bytes[1]};
  std::uint64_t field = 0;
  for (int b = 0; b < 6; ++b) field |= static_cast<std::uint64_t>(bytes[2 + b]) << (8 * b);
  for (int texel = 0; texel < 16; ++texel) params.indices[texel] = static_cast<std::uint8_t>((field >> (3 * texel)) & 7u);
  params.mode = bytes[0] > bytes[1] ? Bc4Mode::eight_value : Bc4Mode::six_value;
  return params;
}

Bc4Params canonicalise_bc4(Bc4Params params) {
  const int red0 = params.endpoints[0], red1 = params.endpoints[1];
  if (params.mode == Bc4Mode::eight_value) {
    if (red0 > red1) return params;
    if (red0 == red1) {
      // Equal endpoints: every one of the 8 values is red0; store it as the 6-value mode's code 0.
      params.mode = Bc4Mode::six_value;
      params.indices.fill(0);
      return params;
    }
    std::swap(params.endpoints[0], params.endpoints[1]);
    // Code k (2..7) is ((8-k) r0 + (k-1) r1) / 7; after the swap the same value is code 9-k.
    for (auto& index : params.indices) index = index <= 1 ? static_cast<std::uint8_t>(1 - index)
                                                          : static_cast<std::uint8_t>(9 - index);
    return params;
  }
  if (red0 <= red1) return params;
  std::swap(params.endpoints[0], params.endpoints[1]);
  // Code k (2..5) is ((6-k) r0 + (k-1) r1) / 5 -> code 7-k after the swap; the constants 0 (6) and 1 (7) stay.
  for (auto& index : params.indices)
    index = index <= 1 ? static_cast<std::uint8_t>(1 - index)
          : index <= 5 ? static_cast<std::uint8_t>(7 - index)
                       : index;
  return params;
}

std::array<float, 16> decode_bc4_params(const Bc4Params& params) {
  double values[16];
  bc4_decode(static_cast<double>(params.endpoints[0]), static_cast<double>(params.endpoints[1]), params.mode,
             params.indices, values);
  std::array<float, 16> result;
  for (int texel = 0; texel < 16; ++texel) result[texel] = static_cast<float>(values[texel]);
  return result;
}

}  // namespace blocklab
