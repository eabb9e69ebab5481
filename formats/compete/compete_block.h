// Decoding a `compete` block (compete_layout.h, formats/compete/README.md "Block"): a BC6H two-region block goes to
// the BC6H decoder (formats/bc6h/bc6h_decode.h, UF16), a Munkberg-family block is unpacked to its Munkberg block
// (dropped bits restored) and decoded by that mode's decoder (formats/munkberg/munkberg_modes.h). Both decoders are
// the formats' own, called, not copied; the oracle is compete_reference_decode.h.
#pragma once

#include <cstdint>

#include "core/blocks.h"
#include "formats/munkberg/munkberg_modes.h"

namespace blocklab::compete {

// Decodes one 16-byte block; every pattern decodes (to finite, non-negative texels, alpha 1).
BlockTexels decode_block(const std::uint8_t* bytes, const munkberg::ModeContext& context);

}  // namespace blocklab::compete
