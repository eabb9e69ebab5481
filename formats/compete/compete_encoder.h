// The `compete` block encoder (formats/compete/README.md, "Encoder"): the cross-paper competition. Every enabled
// family encodes the block with its own encoder, called through its header (BC6H: bc6h::encode_block restricted to
// the two-region modes; Munkberg: each mode's block_mode_models() encoder), each Munkberg block is fitted to its
// `compete` budget (fit_to_budget), and the lowest log2[RGB] block error (munkberg::block_log2_error, the error
// Munkberg et al. 2008 section 6 selects modes by) wins. Trial order: the BC6H family, then the Munkberg modes in
// munkberg::BlockMode order; ties keep the earlier; once the best error is at most good_enough the rest is skipped.
// Deterministic: per-block randomness only from block_seed (the Munkberg encoders' derive_stream_seed).
#pragma once

#include <array>
#include <cstdint>

#include "core/blocks.h"
#include "formats/bc6h/bc6h_mode_search.h"
#include "formats/compete/compete_layout.h"
#include "formats/munkberg/munkberg_modes.h"

namespace blocklab::compete {

struct EncoderSettings {
  bool bc6h_family = true;                                        // the BC6H family
  munkberg::ModeMask munkberg_modes = {true, true, true, true, true};   // the Munkberg modes (BlockMode order)
  munkberg::ModeContext munkberg;   // the Munkberg modes' decoding context and encoder settings
  bc6h::EncoderSettings bc6h;       // only two-region modes may be enabled
  int refit_passes = 1;             // fit_to_budget's index passes
  double good_enough = 0.0;         // skip rule (approximate; 0 = off), block_log2_error units
};

struct BlockChoice {
  int mode = 0;          // compete mode index (compete_layout.h)
  double error = 0.0;    // block_log2_error of the emitted block's decode
};

// Encodes `texels` into out (16 bytes).
BlockChoice encode_block(const BlockTexels& texels, const EncoderSettings& settings, std::uint64_t block_seed,
                         munkberg::ChromaWorkspace* workspace, std::uint8_t* out);

// Makes a Munkberg block (any mode) storable by `compete` (representable()) at the least log2[RGB] error it finds:
// shape II's anchor orientation (lossless), then each halved field set to the best of the replicated codes next to its
// value, then `refit_passes` coordinate-descent passes over the mode's index fields (texel indices / chroma indices /
// mask bits) in the same error. Returns the block's error.
double fit_to_budget(const munkberg::TexelLog2& source_log2, const munkberg::ModeContext& context, int refit_passes,
                     std::uint8_t* munkberg_bytes);

}  // namespace blocklab::compete
