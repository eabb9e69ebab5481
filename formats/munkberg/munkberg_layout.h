// The 128-bit block layout of the `munkberg` format (Munkberg, Clarberg, Hasselgren, Akenine-Moeller, "Practical HDR
// Texture Compression", CGF 27(6), 2008, section 5 and Figure 3; shape II is the layout of Munkberg et al. 2006).
//
// The papers give only the totals: shape II = "two 8-bit end points" + "4 bits" per texel = 80 bits of luminance
// with subsampled shape-transform chrominance in the rest; shape I = 3-bit luminance indices, "16 x 3 + 16 = 64
// bits", leaving 64 bits of chrominance "without subsampling"; "one bit for indicating which of these two modes is
// used per block". The field widths of the chrominance, the subsampling pattern and the field order below are
// blocklab's design (formats/munkberg/README.md gives the rationale). Every width is a named constant and the
// static_asserts (and tests/unit/test_munkberg_layout.cpp) check that each mode's widths sum to 128.
//
// Bit order: core/bits.h (little-endian, fields LSB-first). Field order, both modes (bits 0..47 are shared):
//   [0]        mode bit: 0 = shape II (2006 layout), 1 = shape I (2008 chroma mode)
//   [1, 4)     template shape index (3 bits, 8 shapes)
//   [4, 32)    base colours u0, v0, u1, v1 (7 bits each, value code / 127)
//   [32, 48)   log-luminance endpoints Y0, Y1 (8 bits each)
//   shape II:  [48, 112) 16 x 4-bit luminance indices, texel i at 48 + 4i; [112, 128) 8 x 2-bit chroma indices,
//              group g at 112 + 2g, group g = texels 2g and 2g + 1 (horizontal pairs, 2x1 subsampling)
//   shape I:   [48, 96) 16 x 3-bit luminance indices, texel i at 48 + 3i; [96, 128) 16 x 2-bit chroma indices,
//              texel i at 96 + 2i
#pragma once

namespace blocklab::munkberg {

constexpr int kBlockBits = 128;
constexpr int kBlockBytes = kBlockBits / 8;
constexpr int kTexels = 16;

constexpr int kModeBits = 1;
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

// Field positions (LSB of the field).
constexpr int kModeBitPosition = 0;
constexpr int kShapeIndexPosition = kModeBitPosition + kModeBits;
constexpr int kBaseCoordinatePosition = kShapeIndexPosition + kShapeIndexBits;
constexpr int kLumEndpointPosition = kBaseCoordinatePosition + kBaseCoordinateCount * kBaseCoordinateBits;
constexpr int kLumIndexPosition = kLumEndpointPosition + kLumEndpointCount * kLumEndpointBits;
constexpr int kShape2ChromaIndexPosition = kLumIndexPosition + kTexels * kShape2LumIndexBits;
constexpr int kShape1ChromaIndexPosition = kLumIndexPosition + kTexels * kShape1LumIndexBits;

// Bits of each part per mode (Figure 3's split: shape II 80 luminance bits, shape I 64).
constexpr int kSharedChromaHeaderBits = kShapeIndexBits + kBaseCoordinateCount * kBaseCoordinateBits;   // 31
constexpr int kLumEndpointTotalBits = kLumEndpointCount * kLumEndpointBits;                             // 16
constexpr int kShape2LuminanceBits = kLumEndpointTotalBits + kTexels * kShape2LumIndexBits;              // 80
constexpr int kShape2ChromaBits = kSharedChromaHeaderBits + kShape2ChromaGroups * kChromaIndexBits;      // 47
constexpr int kShape1LuminanceBits = kLumEndpointTotalBits + kTexels * kShape1LumIndexBits;              // 64
constexpr int kShape1ChromaBits = kSharedChromaHeaderBits + kShape1ChromaGroups * kChromaIndexBits;      // 63

constexpr int kShape2TotalBits = kModeBits + kShape2LuminanceBits + kShape2ChromaBits;
constexpr int kShape1TotalBits = kModeBits + kShape1LuminanceBits + kShape1ChromaBits;
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

enum class Mode { shape_ii = 0, shape_i = 1 };

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

}  // namespace blocklab::munkberg
