// Packing, unpacking, canonical forms and the double decoder of one BC1 block (formats/bc1/bc1_block.h).
// Layout from the Khronos Data Format Specification, S3TC chapter (SPECS.md 2.1).
#include "formats/bc1/bc1_block.h"

#include <string>
#include <utility>

#include "core/error.h"

namespace blocklab {

namespace {

void check_fields(const char* who, const Bc1Params& params) {
  for (int e = 0; e < 2; ++e)
    for (int channel = 0; channel < 3; ++channel) {
      const int value = params.endpoints[e][channel];
      if (value < 0 || value > rgb565_channel_max(channel))
        fail(who, "endpoint " + std::to_string(e) + " channel " + std::string(1, "RGB"[channel]) + " = " +
                      std::to_string(value) + " is outside 0.." + std::to_string(rgb565_channel_max(channel)));
    }
  for (int texel = 0; texel < 16; ++texel)
    if (params.indices[texel] > 3)
      fail(who, "texel " + std::to_string(texel) + " code " + std::to_string(params.indices[texel]) +
                    " does not fit in 2 bits");
}

void write_fields(const Bc1Params& params, std::uint8_t* bytes) {
  const unsigned word0 = bc1_endpoint_word(params, 0), word1 = bc1_endpoint_word(params, 1);
  bytes[0] = static_cast<std::uint8_t>(word0 & 0xFFu);   // little-endian u16
  bytes[1] = static_cast<std::uint8_t>(word0 >> 8);
  bytes[2] = static_cast<std::uint8_t>(word1 & 0xFFu);
  bytes[3] = static_cast<std::uint8_t>(word1 >> 8);
  std::uint32_t index_word = 0;
  for (int texel = 0; texel < 16; ++texel) index_word |= static_cast<std::uint32_t>(params.indices[texel]) << (2 * texel);
  for (int b = 0; b < 4; ++b) bytes[4 + b] = static_cast<std::uint8_t>((index_word >> (8 * b)) & 0xFFu);
}

Bc1Params read_fields(const std::uint8_t* bytes) {
  Bc1Params params;
  const unsigned word0 = bytes[0] | (static_cast<unsigned>(bytes[1]) << 8);
  const unsigned word1 = bytes[2] | (static_cast<unsigned>(bytes[3]) << 8);
  params.endpoints[0] = unpack_rgb565(word0);
  params.endpoints[1] = unpack_rgb565(word1);
  const std::uint32_t index_word = bytes[4] | (static_cast<std::uint32_t>(bytes[5]) << 8) |
                                   (static_cast<std::uint32_t>(bytes[6]) << 16) |
                                   (static_cast<std::uint32_t>(bytes[7]) << 24);
  for (int texel = 0; texel < 16; ++texel) params.indices[texel] = static_cast<std::uint8_t>((index_word >> (2 * texel)) & 3u);
  params.mode = word0 > word1 ? Bc1Mode::four_color : Bc1Mode::three_color;
  return params;
}

void swap_endpoints(Bc1Params& params) { std::swap(params.endpoints[0], params.endpoints[1]); }

}  // namespace

void pack_bc1_block(const Bc1Params& params, std::uint8_t* bytes) {
  check_fields("bc1", params);
  const unsigned word0 = bc1_endpoint_word(params, 0), word1 = bc1_endpoint_word(params, 1);
  // The decoder decides the mode from the packed order, so a Params whose mode disagrees would decode differently.
  if (params.mode == Bc1Mode::four_color && !(word0 > word1))
    fail("bc1", "4-colour mode needs color0 > color1 as packed RGB565 (got " + std::to_string(word0) + " and " +
                    std::to_string(word1) + "); canonicalise first");
  if (params.mode == Bc1Mode::three_color && word0 > word1)
    fail("bc1", "3-colour mode needs color0 <= color1 as packed RGB565 (got " + std::to_string(word0) + " and " +
                    std::to_string(word1) + "); canonicalise first");
  write_fields(params, bytes);
}

Bc1Params unpack_bc1_block(const std::uint8_t* bytes) { return read_fields(bytes); }

void pack_bc1_color_bits(const Bc1Params& params, std::uint8_t* bytes) {
  check_fields("bc3", params);
  if (params.mode != Bc1Mode::four_color) fail("bc3", "the colour block of BC3 is always decoded with 4 colours");
  write_fields(params, bytes);
}

Bc1Params unpack_bc3_color_bits(const std::uint8_t* bytes) {
  Bc1Params params = read_fields(bytes);
  params.mode = Bc1Mode::four_color;   // KDFS: BC3 colour codes are 4-colour whatever the endpoint order
  return params;
}

Bc1Params canonicalise_bc1(Bc1Params params) {
  const unsigned word0 = bc1_endpoint_word(params, 0), word1 = bc1_endpoint_word(params, 1);
  if (params.mode == Bc1Mode::four_color) {
    if (word0 > word1) return params;
    if (word0 == word1) {
      // Equal endpoints: the 4-colour palette is one colour four times; only the 3-colour mode can be stored,
      // and its code 0 is that colour.
      params.mode = Bc1Mode::three_color;
      params.indices.fill(0);
      return params;
    }
    swap_endpoints(params);
    static constexpr std::uint8_t kSwapped4[4] = {1, 0, 3, 2};   // C0<->C1 and (2C0+C1)/3 <-> (C0+2C1)/3
    for (auto& index : params.indices) index = kSwapped4[index & 3];
    return params;
  }
  if (word0 <= word1) return params;
  swap_endpoints(params);
  static constexpr std::uint8_t kSwapped3[4] = {1, 0, 2, 3};   // the midpoint and black are symmetric
  for (auto& index : params.indices) index = kSwapped3[index & 3];
  return params;
}

Bc1Params canonicalise_bc3_color(Bc1Params params) {
  params.mode = Bc1Mode::four_color;
  const unsigned word0 = bc1_endpoint_word(params, 0), word1 = bc1_endpoint_word(params, 1);
  if (word0 > word1) return params;
  if (word0 == word1) {
    params.indices.fill(0);   // one colour: code 0 decodes to it in either mode
    return params;
  }
  swap_endpoints(params);
  static constexpr std::uint8_t kSwapped4[4] = {1, 0, 3, 2};
  for (auto& index : params.indices) index = kSwapped4[index & 3];
  return params;
}

BlockTexels decode_bc1_params(const Bc1Params& params) {
  double endpoint0[3], endpoint1[3];
  for (int channel = 0; channel < 3; ++channel) {
    endpoint0[channel] = params.endpoints[0][channel];
    endpoint1[channel] = params.endpoints[1][channel];
  }
  double rgb[16][3];
  bc1_decode(endpoint0, endpoint1, params.mode, params.indices, rgb);
  BlockTexels texels;
  for (int texel = 0; texel < 16; ++texel) {
    for (int channel = 0; channel < 3; ++channel) texels.rgba[texel][channel] = static_cast<float>(rgb[texel][channel]);
    texels.rgba[texel][3] = 1.0f;
  }
  return texels;
}

}  // namespace blocklab
