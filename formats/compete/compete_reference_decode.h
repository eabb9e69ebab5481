// The `compete` oracle (formats/compete/README.md, "Block"): a plain transcription of the README's layout table that
// reads the block one bit at a time and shares no code with compete_layout.cpp; the Munkberg block it rebuilds goes
// to the Munkberg modes' own reference decoders (munkberg::reference_decode_any_block), a BC6H block to the
// spec-literal BC6H oracle (bc6h::reference_decode). Tests compare it with compete_block.h bit for bit.
#pragma once

#include <cstdint>

#include "core/blocks.h"
#include "formats/munkberg/munkberg_modes.h"

namespace blocklab::compete {

BlockTexels reference_decode_block(const std::uint8_t* bytes, const munkberg::ModeContext& context);

}  // namespace blocklab::compete
