// The 128-bit block layout of the `munkberg` format (Munkberg, Clarberg, Hasselgren, Akenine-Moeller, "Practical HDR
// Texture Compression", CGF 27(6), 2008, section 5 and Figure 3; shape II is the layout of Munkberg et al. 2006) and
// the MODE SELECTOR shared with the rejected modes of section 6 (ext_s3tc_block.h, two_plane_block.h).
//
// The papers give only the totals: shape II = "two 8-bit end points" + "4 bits" per texel = 80 bits of luminance
// with subsampled shape-transform chrominance in the rest; shape I = 3-bit luminance indices, "16 x 3 + 16 = 64
// bits", leaving 64 bits of chrominance "without subsampling"; "one bit for indicating which of these two modes is
// used per block". The field widths of the chrominance, the subsampling pattern, the field order and the selector
// code below are blocklab's design (formats/munkberg/README.md gives the rationale). Every width is a named constant
// and the static_asserts (and tests/unit/test_munkberg_layout.cpp) check that each mode's widths sum to 128.
//
// Mode selector: a prefix code on the first bits (LSB-first, core/bits.h order), so every 128-bit pattern is exactly
// one mode's block:
//   bit 0 = 0                    shape II   (1 selector bit: the 2006 layout keeps all 127 payload bits)
//   bits 0,1 = 1,0               shape I    (2 selector bits; the bit is won back losslessly, see the anchor below)
//   bits 0,1,2 = 1,1,0           ext_s3tc   (3 selector bits; ext_s3tc_block.h)
//   bits 0..3 = 1,1,1,0          two_plane  (4 selector bits; two_plane_block.h)
//   bits 0..3 = 1,1,1,1          dct        (4 selector bits; dct_block.h)
//
// Shape I anchor: swapping the endpoint codes e0 <-> e1 and every index l -> 7 - l decodes to the same texels
// (q = (7 - l) e0 + l e1 is symmetric), so the encoder stores the orientation in which texel 0's index is <= 3 and
// texel 0 has a 2-bit index field (the S3TC/BC7 "anchor index" trick): shape I keeps the paper's full 64-bit
// luminance precision with 63 stored bits.
//
// Field order (LSB of each field first):
//   shape II:  [0] selector 0; [1, 4) template shape index; [4, 32) base colours u0, v0, u1, v1 (7 bits each,
//              value code / 127); [32, 48) log-luminance endpoints Y0, Y1 (8 bits each); [48, 112) 16 x 4-bit
//              luminance indices, texel i at 48 + 4i; [112, 128) 8 x 2-bit chroma indices, group g at 112 + 2g,
//              group g = texels 2g and 2g + 1 (horizontal pairs, 2x1 subsampling)
//   shape I:   [0, 2) selector; [2, 5) shape index; [5, 33) base colours; [33, 49) Y0, Y1; [49, 51) texel 0's
//              luminance index (2 bits, anchor); [51, 96) texels 1..15, 3 bits each, texel i at 51 + 3 (i - 1);
//              [96, 128) 16 x 2-bit chroma indices, texel i at 96 + 2i
#pragma once

#include <cstdint>

namespace blocklab::munkberg {

constexpr int kBlockBits = 128;
constexpr int kBlockBytes = kBlockBits / 8;
constexpr int kTexels = 16;

// Mode selector (prefix code, see the file comment). Values are the selector bits read LSB-first.
constexpr int kShape2SelectorBits = 1;
constexpr unsigned kShape2Selector = 0b0u;
constexpr int kShape1SelectorBits = 2;
constexpr unsigned kShape1Selector = 0b01u;      // bit 0 = 1, bit 1 = 0
constexpr int kExtS3tcSelectorBits = 3;
constexpr unsigned kExtS3tcSelector = 0b011u;    // bits 1, 1, 0
constexpr int kTwoPlaneSelectorBits = 4;
constexpr unsigned kTwoPlaneSelector = 0b0111u;  // bits 1, 1, 1, 0
constexpr int kDctSelectorBits = 4;
constexpr unsigned kDctSelector = 0b1111u;       // bits 1, 1, 1, 1
constexpr int kMaxSelectorBits = 4;
// Kraft sum of the prefix code is exactly 1 (1/2 + 1/4 + 1/8 + 1/16 + 1/16): every bit pattern is a block of some
// mode.
static_assert((1 << (kMaxSelectorBits - kShape2SelectorBits)) + (1 << (kMaxSelectorBits - kShape1SelectorBits)) +
                      (1 << (kMaxSelectorBits - kExtS3tcSelectorBits)) +
                      (1 << (kMaxSelectorBits - kTwoPlaneSelectorBits)) +
                      (1 << (kMaxSelectorBits - kDctSelectorBits)) ==
                  (1 << kMaxSelectorBits),
              "the mode selector is a complete prefix code");
constexpr int kShapeIndexBits = 3;
constexpr int kShapeCount = 1 << kShapeIndexBits;
constexpr int kBaseCoordinateBits = 7;                  // per base-colour coordinate (u0, v0, u1, v1)
constexpr int kBaseCoordinateCount = 4;
constexpr int kBaseCoordinateMax = (1 << kBaseCoordinateBits) - 1;   // 127: code c decodes to c / 127
constexpr int kLumEndpointBits = 8;                     // "quantizing the minimum and maximum log-luminance ... to 8 bits"
constexpr int kLumEndpointCount = 2;
constexpr int kLumEndpointMax = (1 << kLumEndpointBits) - 1;          // 255
constexpr int kChromaIndexBits = 2;                     // "a 2-bit index is used to indicate the nearest chrominance point"

// Shape II (Munkberg 2006): 4-bit luminance indices, chroma subsampled 2x1.
constexpr int kShape2LumIndexBits = 4;
constexpr int kShape2ChromaGroups = 8;                  // 16 texels in horizontal pairs
constexpr int kShape2TexelsPerGroup = kTexels / kShape2ChromaGroups;
// Shape I (Munkberg 2008): 3-bit luminance indices, one chroma index per texel.
constexpr int kShape1LumIndexBits = 3;
constexpr int kShape1ChromaGroups = kTexels;

enum class Mode { shape_ii = 0, shape_i = 1 };

constexpr int selector_bits(Mode mode) { return mode == Mode::shape_ii ? kShape2SelectorBits : kShape1SelectorBits; }
constexpr unsigned selector_value(Mode mode) { return mode == Mode::shape_ii ? kShape2Selector : kShape1Selector; }

// Shape I's texel 0 luminance index: 2 stored bits, the MSB is 0 by the anchor convention (file comment).
constexpr int kShape1AnchorIndexBits = kShape1LumIndexBits - 1;
constexpr int kShape1AnchorIndexMax = (1 << kShape1AnchorIndexBits) - 1;   // 3

// Field positions (LSB of the field), per mode: everything after the selector is shifted by its length.
constexpr int shape_index_position(Mode mode) { return selector_bits(mode); }
constexpr int base_coordinate_position(Mode mode) { return shape_index_position(mode) + kShapeIndexBits; }
constexpr int lum_endpoint_position(Mode mode) {
  return base_coordinate_position(mode) + kBaseCoordinateCount * kBaseCoordinateBits;
}
constexpr int lum_index_position(Mode mode) { return lum_endpoint_position(mode) + kLumEndpointCount * kLumEndpointBits; }
// Stored width of texel i's luminance index (shape I's anchor texel 0 has one bit fewer).
constexpr int lum_index_stored_bits(Mode mode, int texel) {
  return mode == Mode::shape_i && texel == 0 ? kShape1AnchorIndexBits
                                             : (mode == Mode::shape_ii ? kShape2LumIndexBits : kShape1LumIndexBits);
}
constexpr int kShape2ChromaIndexPosition = lum_index_position(Mode::shape_ii) + kTexels * kShape2LumIndexBits;
constexpr int kShape1ChromaIndexPosition =
    lum_index_position(Mode::shape_i) + kShape1AnchorIndexBits + (kTexels - 1) * kShape1LumIndexBits;

// Bits of each part per mode (Figure 3's split: shape II 80 luminance bits, shape I 64, of which 63 are stored).
constexpr int kSharedChromaHeaderBits = kShapeIndexBits + kBaseCoordinateCount * kBaseCoordinateBits;   // 31
constexpr int kLumEndpointTotalBits = kLumEndpointCount * kLumEndpointBits;                             // 16
constexpr int kShape2LuminanceBits = kLumEndpointTotalBits + kTexels * kShape2LumIndexBits;              // 80
constexpr int kShape2ChromaBits = kSharedChromaHeaderBits + kShape2ChromaGroups * kChromaIndexBits;      // 47
constexpr int kShape1LuminanceBits = kLumEndpointTotalBits + kTexels * kShape1LumIndexBits;              // 64
constexpr int kShape1StoredLuminanceBits = kShape1LuminanceBits - (kShape1LumIndexBits - kShape1AnchorIndexBits);
constexpr int kShape1ChromaBits = kSharedChromaHeaderBits + kShape1ChromaGroups * kChromaIndexBits;      // 63

constexpr int kShape2TotalBits = kShape2SelectorBits + kShape2LuminanceBits + kShape2ChromaBits;
constexpr int kShape1TotalBits = kShape1SelectorBits + kShape1StoredLuminanceBits + kShape1ChromaBits;
static_assert(kShape2TotalBits == kBlockBits, "shape II fields must fill the 128-bit block exactly");
static_assert(kShape1TotalBits == kBlockBits, "shape I fields must fill the 128-bit block exactly");
static_assert(kShape2LuminanceBits == 80, "section 5: shape II luminance is 16 x 4 + 2 x 8 = 80 bits");
static_assert(kShape1LuminanceBits == 64, "section 5: shape I luminance is 16 x 3 + 16 = 64 bits");
static_assert(kShape2ChromaIndexPosition + kShape2ChromaGroups * kChromaIndexBits == kBlockBits,
              "shape II chroma indices end at bit 128");
static_assert(kShape1ChromaIndexPosition + kShape1ChromaGroups * kChromaIndexBits == kBlockBits,
              "shape I chroma indices end at bit 128");
static_assert(kShape2TexelsPerGroup * kShape2ChromaGroups == kTexels, "subsampling groups cover the block");

// Log-luminance endpoint code e in [0, 255] stands for Ybar = kLogLumMin + e (kLogLumMax - kLogLumMin) / 255
// (section 7.3: the range of the half type, "approximately [2^-16, 2^16]"). Texel levels interpolate the codes
// exactly: level i of n (n = 15 or 7) has the integer numerator q = (n - i) e0 + i e1 and
// Ybar = kLogLumMin + q (kLogLumMax - kLogLumMin) / (255 n). True black (eq. 3): q == 0, i.e. Ybar == Ybar_min.
constexpr double kLogLumMin = -16.0;
constexpr double kLogLumMax = 16.0;
constexpr double kLogLumRange = kLogLumMax - kLogLumMin;

constexpr int lum_index_bits(Mode mode) { return mode == Mode::shape_ii ? kShape2LumIndexBits : kShape1LumIndexBits; }
// Highest luminance index n: 15 (shape II) or 7 (shape I).
constexpr int lum_levels_minus_one(Mode mode) { return (1 << lum_index_bits(mode)) - 1; }
constexpr int chroma_groups(Mode mode) { return mode == Mode::shape_ii ? kShape2ChromaGroups : kShape1ChromaGroups; }
constexpr int chroma_index_position(Mode mode) {
  return mode == Mode::shape_ii ? kShape2ChromaIndexPosition : kShape1ChromaIndexPosition;
}
// The chroma index group of texel i (i = x + 4y): horizontal pairs in shape II, the texel itself in shape I.
constexpr int chroma_group_of_texel(Mode mode, int texel) {
  return mode == Mode::shape_ii ? texel / kShape2TexelsPerGroup : texel;
}

// Every mode a block can be in, in Format::modes() order (the block_modes index). The selector decides it.
enum class BlockMode { shape_ii = 0, shape_i = 1, ext_s3tc = 2, two_plane = 3, dct = 4 };
constexpr int kBlockModeCount = 5;

// The mode of a 16-byte block, from its selector bits (every pattern is some mode's block).
inline BlockMode block_mode_of(const std::uint8_t* bytes) {
  if ((bytes[0] & 1u) == 0u) return BlockMode::shape_ii;             // selector 0
  if ((bytes[0] & 2u) == 0u) return BlockMode::shape_i;              // selector 1,0
  if ((bytes[0] & 4u) == 0u) return BlockMode::ext_s3tc;             // selector 1,1,0
  return (bytes[0] & 8u) == 0u ? BlockMode::two_plane : BlockMode::dct;   // 1,1,1,0 / 1,1,1,1
}

}  // namespace blocklab::munkberg
