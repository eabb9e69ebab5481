// `mavridis`: Mavridis & Papaioannou, "Texture compression using wavelet decomposition", Pacific Graphics 2012
// (../shared/papers/mavridis2012_wavelet_texture_compression.txt). LDR textures at the rates of Table 2:
//
//   bpp    Y                              Co, Cg (each)                     payload per 32x32 texels (1024)
//   2      wavelet (one BC3 at 1/2 res)   -     (gray: one channel)         16 BC3 = 256 B              = 2 bpp
//   2.25   wavelet                        box 4:1 per axis, then wavelet    16 + 2 x 1 BC3 = 288 B      = 2.25 bpp
//   3      wavelet                        box 2:1 per axis, then wavelet    16 + 2 x 4 BC3 = 384 B      = 3 bpp
//   5      BC4 (DXT5/A) at full res       box 2:1 per axis, then wavelet    64 BC4 + 2 x 4 BC3 = 640 B  = 5 bpp
// ("wavelet" = the 2 bpp coding of mavridis_plane_codec.h: 8 bpp BC3 over a quarter of the texels.) So a 2:1
// "CoCg sample" of Table 2 is 2:1 along each axis: Co and Cg at 0.5 bpp each (3 bpp) or 0.125 bpp (2.25 bpp).
//
// Storage: the payload is the Y texture's blocks, then Co's, then Cg's, each row-major. Rates of whole bytes per 4x4
// block fill the texture's 4x4 grid: block_bytes 4 (2 bpp), 6 (3 bpp) and 10 (5 bpp); for sizes that are not
// multiples of the coded tiles (8 or 16 texels) the edge-padded coefficient textures can exceed that capacity and
// the bytes beyond it go to side data `tail_bytes` (0..255 each). The other rates (2.25 bpp: 4.5 bytes per 4x4
// block; most levels > 1) store the payload at its true size in 8-byte units (block_bytes 8, stored_block_count =
// payload / 8). bits_per_pixel is the payload rate (README.md, "Decisions").
//
// Colour (section 3.5): RGB (8-bit code values) -> YCoCg-R by the integer lifting of core/color_spaces.h; the
// decoder rounds the decoded Y, Co, Cg and applies the four additions and two shifts. space=ycocg / ycbcr are the
// Table 3 alternatives (real-valued); color_storage=unorm8 holds the planes as 8-bit textures on both sides of the
// wavelet, as the paper's GPU pipeline (mavridis_color_storage.h). Gray (bpp=2) codes Y of the chosen space (the
// source itself when it has one channel) and decodes to a one-channel image. Chroma is upsampled bilinearly (texel
// centres) on decode.
//
// Options: bpp = 5 | 3 | 2.25 | 2;  transform = pi_haar | haar | s_transform;  w (eq. 2, default 0.4);
// space = ycocg_r | ycocg | ycbcr;  color_storage = exact | unorm8;  packing = dxt5 | bc7 (section 3.1: LL, HL+LH, HL-LH in BC7, HH dropped, weights
// 0.6 / 0.2 / 0.2);  preset = fast | medium | thorough (mavridis_presets.h: the clamp / gamma grid of section 3.2
// and the BC3 search effort);  coeff_solver = grid | <solver> and coeff_solver_options (section 3.2's search by a
// solver of the library, mavridis_coefficient_problem.h). Side data (checked on decode, Errors name the key):
// mavridis_format.cpp.
#pragma once

#include <cstddef>

#include "formats/format.h"

namespace blocklab {

const Format& mavridis_format();

// Bytes of the coded planes (Y, then Co, Cg) of a width x height texture at these resolved options: the payload whose
// rate Table 2 states (block_bytes rounds it up to whole bytes per 4x4 block).
std::size_t mavridis_payload_bytes(const FormatOptions& options, int width, int height);

}  // namespace blocklab
