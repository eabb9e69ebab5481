// `wang`: Wei (Wang), Tong, Guo, "Rendering from compressed high dynamic range textures on programmable graphics
// hardware", I3D 2007 (../shared/papers/wang2007_luvw_two_dxt5.txt). 16 bpp: RGB -> LUVW (eq. 1) or LUV (eq. 10),
// the luminance split over two uniform zones in tex0.a / tex1.a (eq. 3, decoded branch-free by eq. 4), its residual
// over three zones in tex1.rgb (eq. 6, eq. 7), the chroma in tex0.rgb; two DXT5 (BC3) textures, i.e. 32 bytes per
// 4x4 block (wang_block.h), decoded by the section 3.4 shader on the CPU with the texture unit's 8-bit values
// (wang_shader.h states the convention). Per-texture constants: wang_side_data.h.
//
// Options (README.md has the details and measurements):
//   space = luvw | luv              eq. 1 (default) or eq. 10
//   residual = s | ratio | none     eq. 5 S (default), eq. 11 T = S / L', or no residual (tex1.rgb = 0)
//   l_bits = 2x6 | 1x12             two zones (default, eq. 3) or one 12-bit range split 6 + 6 (section 4.3)
//   codec = 1d | bc3                section 3.5's 1D codec (default) or the plain BC3 encoder on the eq. 3 / 6 targets
//   preset = fast | medium | thorough   search effort (wang_presets.h), default medium
//   t1_solver, s_solver = linear | <solver>   zone splits (wang_zone_split.h): eq. 2 linear search (default) or a
//                                   solver of the library on the zone quantisation error; zone_solver_options =
//                                   "key=value, ..." for that solver
//   joint_codes = true | false      1d codec: texels re-pick their three codes together at the end
//                                   (wang_joint_codes.h), default true
//   error_c                         the c of eq. 9 (default 2^-14)
//   solver, solver_options          the 1D codec's block search: builtin (default) or a solver of the library on
//                                   the block Problems of wang_block_problem.h
#pragma once

#include "formats/format.h"
#include "formats/wang/wang_block.h"

namespace blocklab {

const Format& wang_format();

namespace wang {
// The decoder's constants and choices of an encoded wang texture (its options and side data), as Format::decode
// uses them. Throws Error("wang: ...") on missing or bad options or side data.
DecodeSetup decode_setup(const EncodedTexture& texture);
}  // namespace wang

}  // namespace blocklab
