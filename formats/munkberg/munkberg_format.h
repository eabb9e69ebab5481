// `munkberg`: the 8 bpp HDR shape-transform format of Munkberg, Clarberg, Hasselgren, Akenine-Moeller, "Practical
// HDR Texture Compression", CGF 27(6), 2008 (/work/shared/papers/munkberg2008_practical_hdr_texture_compression.txt):
// logYuv (eq. 2, black level eq. 3), 128-bit blocks whose prefix-coded mode selector chooses shape II (the 2006
// layout: 8-bit log-luminance endpoints, 4-bit indices, 2x1-subsampled shape-transform chroma), shape I (3-bit
// luminance indices, one chroma index per texel) or one of section 6's rejected modes: extended S3TC, two-plane
// luminance and the fixed-rate DCT. The option `modes` picks the competing modes: every preset but `paper` lets all
// five compete (modes=all), the section 6 modes tried after the shape modes and skipped where the mode predictor
// (option mode_predictor) estimates they cannot win; `paper` keeps the 2008 format's two shape modes (modes=both).
// Layout: munkberg_layout.h; decoding: munkberg_block.h, ext_s3tc_block.h, two_plane_block.h, dct_block.h; mode
// table: munkberg_modes.h; options and decisions: formats/munkberg/README.md.
#pragma once

#include "formats/format.h"

namespace blocklab {

const Format& munkberg_format();

namespace munkberg {

struct ModeContext;   // munkberg_modes.h

// The mode context (shapes, ext_s3tc space, encoder settings) munkberg_format().encode uses for the options `resolved`
// (resolve_format_options output): what a format built on the Munkberg modes (formats/compete) encodes them with.
ModeContext mode_context_of(const FormatOptions& resolved);

// Speed-ups that never change the bytes (proven by tests that switch them off), kept out of the option list: only
// tests and benchmarks switch them, through encode_with_speedups.
struct ExactSpeedups {
  bool skip_constant = true;     // exactly constant chroma skips the ranked search (ChromaSettings::skip_constant)
  bool skip_mode_bound = true;   // modes whose lower bound cannot win are not encoded (EncoderSettings)
};

// munkberg_format().encode with the exact speed-ups set as given (`resolved`: resolve_format_options output).
EncodedTexture encode_with_speedups(const Image& image, const FormatOptions& resolved, const CodecContext& context,
                                    const ExactSpeedups& speedups);

}  // namespace munkberg

}  // namespace blocklab
