// The bit reader of the `munkberg` oracles (munkberg_reference_decode.cpp, ext_s3tc_reference_decode.cpp,
// two_plane_reference_decode.cpp, dct_reference_decode.cpp), which transcribe the layout tables (munkberg_layout.h
// file comment, each mode's block header) bit by bit. pack/unpack and the decoders read through core/bits.h; the
// oracles read through this one loop only, so they share no bit-level code with what they check.
#pragma once

#include <cstdint>

namespace blocklab::munkberg {

// Bit k of the block is bit (k mod 8) of byte k / 8; a field of `width` bits at `position` has its LSB at position.
inline unsigned reference_field(const std::uint8_t* bytes, int position, int width) {
  unsigned value = 0;
  for (int b = 0; b < width; ++b) {
    const int k = position + b;
    value |= ((bytes[k / 8] >> (k % 8)) & 1u) << b;
  }
  return value;
}

}  // namespace blocklab::munkberg
