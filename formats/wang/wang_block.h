// One `wang` block (Wang et al. 2007 section 3.3): the 4x4 texels of the two DXT5 textures, 32 bytes:
//   bytes  0-15  tex0, a BC3 block: colour = chroma (U, V, W) or (U, V, 0), alpha = tex0.a of eq. 3
//   bytes 16-31  tex1, a BC3 block: colour = residual (eq. 6) or 0, alpha = tex1.a of eq. 3
// Each half is a standard BC3 block (formats/bc3/bc3_block.h), so the two halves written to two .dds files are the
// paper's two DXT5 textures. Decoding: wang_shader.h (the convention) on both halves; the oracle is
// wang_reference_decode.cpp.
#pragma once

#include <cstdint>

#include "core/blocks.h"
#include "formats/bc3/bc3_block.h"
#include "formats/wang/wang_shader.h"

namespace blocklab {
namespace wang {

constexpr int kBlockBytes = 2 * kBc3BlockBytes;

struct BlockParams {
  Bc3Params tex0;
  Bc3Params tex1;
};

// Everything the decoder needs besides the block: the shader constants and the texture's choices.
struct DecodeSetup {
  ShaderConstants constants;
  ColorSpace space = ColorSpace::luvw;
  Residual residual = Residual::s;
};

// Writes the 32 bytes; throws Error("wang: ...") on out-of-range fields (bc3 rules for each half).
void pack_block(const BlockParams& params, std::uint8_t* bytes);
// Reads the 32 bytes (every bit pattern is valid). pack(unpack(b)) == b.
BlockParams unpack_block(const std::uint8_t* bytes);

// The fetched (texture-unit) RGBA of the 16 texels of one BC3 block, from endpoints given as scalars: the BC3
// palettes (formats/common/s3tc_common.h, exact fractions) followed by texture_unit_value.
template <typename T>
void fetch_bc3_texels(const T alpha_endpoints[2], Bc4Mode alpha_mode, const std::array<std::uint8_t, 16>& alpha_codes,
                      const T color0[3], const T color1[3], const std::array<std::uint8_t, 16>& color_codes,
                      T texels[16][4]) {
  T alpha_palette[8];
  bc4_palette(alpha_endpoints[0], alpha_endpoints[1], alpha_mode, alpha_palette);
  T color_palette[4][3];
  bc1_palette(color0, color1, Bc1Mode::four_color, color_palette);
  for (int texel = 0; texel < 16; ++texel) {
    for (int channel = 0; channel < 3; ++channel)
      texels[texel][channel] = texture_unit_value(color_palette[color_codes[texel] & 3][channel]);
    texels[texel][3] = texture_unit_value(alpha_palette[alpha_codes[texel] & 7]);
  }
}

// The templated decoder: RGB of the 16 texels (any scalar type; the endpoints of `params` become T).
template <typename T>
void decode_block(const DecodeSetup& setup, const BlockParams& params, T rgb[16][3]) {
  T fetched[2][16][4];
  const Bc3Params* halves[2] = {&params.tex0, &params.tex1};
  for (int half = 0; half < 2; ++half) {
    const Bc3Params& block = *halves[half];
    const T alpha[2] = {T(static_cast<double>(block.alpha.endpoints[0])),
                        T(static_cast<double>(block.alpha.endpoints[1]))};
    T color[2][3];
    for (int e = 0; e < 2; ++e)
      for (int channel = 0; channel < 3; ++channel)
        color[e][channel] = T(static_cast<double>(block.color.endpoints[e][channel]));
    fetch_bc3_texels(alpha, block.alpha.mode, block.alpha.indices, color[0], color[1], block.color.indices,
                     fetched[half]);
  }
  for (int texel = 0; texel < 16; ++texel)
    shade_texel(setup.constants, setup.space, setup.residual, fetched[0][texel], fetched[1][texel], rgb[texel]);
}

// Steps 1-2 of the convention for one block: the texture unit's RGBA of the 16 texels of tex0 (halves[0]) and tex1
// (halves[1]), both BC3 halves through the BC3 decoder (decode_bc3_params) and texture_unit_value, in float.
void fetch_block_bytes(const std::uint8_t* bytes, BlockTexels halves[2]);

// What Format::decode writes for one block: fetch_block_bytes and the shader in float. Equal bit for bit to
// decode_block<float>.
BlockTexels decode_block_bytes(const DecodeSetup& setup, const std::uint8_t* bytes);

// The oracle (wang_reference_decode.cpp): the 32 bytes read bit by bit, integer palettes and rounding, the shader
// constants and eq. 7 / eq. 8 written out from the paper; shares no code with the decoders above.
BlockTexels reference_decode_block(const Zones& zones, LuminanceSplit split, ColorSpace space, Residual residual,
                                   const std::uint8_t* bytes);

}  // namespace wang
}  // namespace blocklab
