// Two-plane luminance, a rejected mode of Munkberg et al. 2008 (section 6.3): "two plane equations with a 10-bit
// offset and two 7-bit deltas each. A 16-bit mask was used to select which of the two planes each pixel belongs to
// ... 2 x (10 + 7 + 7) + 16 = 64 ... combined with the chrominance encoding using shape transforms as described in
// Section 5" (shape I's 63-bit chroma: shape index, four 7-bit base coordinates, 16 two-bit indices).
// As a plug-in mode of the `munkberg` format it gives 4 bits to the mode selector (munkberg_layout.h); 64 + 63 + 4 =
// 131, so blocklab's design (README.md, "Modes") takes 2 bits from the plane offsets (9 bits each: a step of
// 32/511 = 0.063 stops, still half the shape modes' 8-bit endpoint step) and wins 1 back losslessly with a MASK
// ANCHOR: swapping the two planes and inverting the mask decodes to the same texels (both planes have the same
// fields and widths), so the encoder stores the orientation in which texel 0 takes plane 0 and texel 0's mask bit is
// implied (canonicalize_mask_anchor), the BC7 anchor trick on the mask.
//
// Plane p: Ybar_p(x, y) = -16 + 32 o_p / 511 + (dx_p (2x - 3) + dy_p (2y - 3)) / 32, i.e. the offset is the value at
// the block centre and the deltas are slopes of dx/16, dy/16 stops per texel (two's complement, -64..63: up to 4
// stops per texel). Offset code 0 is a true-black plane (eq. 3's rule carried to planes; its deltas are ignored).
// Otherwise Ybar is clamped to [-16, 16] and Y = 2^Ybar. Texel i = x + 4y takes plane mask bit i (bit 0 is 0).
//
// LAYOUT (LSB-first): [0, 4) selector 1,1,1,0; [4, 27) plane 0 = offset (9), dx (7), dy (7); [27, 50) plane 1;
// [50, 65) mask bits of texels 1..15, texel i at 49 + i; [65, 68) shape index; [68, 96) base colours u0, v0, u1, v1
// (7 bits each); [96, 128) 16 x 2-bit chroma indices, texel i at 96 + 2i (the same positions as shape I's).
// Chroma decoding is shape I's (munkberg_block.h): landmarks from the base colours and the shape, clamped to [0, 1];
// R = v Y / wr, G = max(0, 1 - u - v) Y / wg, B = u Y / wb.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>

#include "core/blocks.h"
#include "core/color_spaces.h"
#include "core/scalar.h"
#include "formats/munkberg/munkberg_block.h"
#include "formats/munkberg/munkberg_layout.h"
#include "formats/munkberg/munkberg_shapes.h"

namespace blocklab::munkberg {

constexpr int kPlaneCount = 2;
constexpr int kPlaneOffsetBits = 9;
constexpr int kPlaneOffsetMax = (1 << kPlaneOffsetBits) - 1;   // 511
constexpr int kPlaneDeltaBits = 7;
constexpr int kPlaneDeltaMin = -(1 << (kPlaneDeltaBits - 1));  // -64
constexpr int kPlaneDeltaMax = (1 << (kPlaneDeltaBits - 1)) - 1;   // 63
constexpr double kPlaneDeltaDivisor = 32.0;    // Ybar += d (2x - 3) / 32: slope d / 16 stops per texel
constexpr int kPlaneBits = kPlaneOffsetBits + 2 * kPlaneDeltaBits;   // 23
constexpr int kPlaneMaskBits = kTexels - 1;   // texel 0's bit is implied 0 (mask anchor, file comment)
constexpr int kTwoPlaneLuminanceBits = kPlaneCount * kPlaneBits + kPlaneMaskBits;   // 61 stored (paper: 64)
constexpr int kTwoPlaneChromaBits = kShape1ChromaBits;                                // 63
constexpr int kTwoPlanePlanePosition = kTwoPlaneSelectorBits;
constexpr int kTwoPlaneMaskPosition = kTwoPlanePlanePosition + kPlaneCount * kPlaneBits;   // 49
constexpr int kTwoPlaneChromaPosition = kTwoPlaneMaskPosition + kPlaneMaskBits;            // 65
constexpr int kTwoPlaneChromaIndexPosition = kTwoPlaneChromaPosition + kSharedChromaHeaderBits;
constexpr int kTwoPlaneTotalBits = kTwoPlaneSelectorBits + kTwoPlaneLuminanceBits + kTwoPlaneChromaBits;
static_assert(kTwoPlaneTotalBits == kBlockBits, "two-plane fields must fill the 128-bit block exactly");
static_assert(kTwoPlaneChromaIndexPosition + kTexels * kChromaIndexBits == kBlockBits, "chroma indices end at 128");

struct Plane {
  int offset = 0;   // 0 .. 511; 0 = true-black plane
  int dx = 0;       // -64 .. 63
  int dy = 0;
  bool operator==(const Plane& o) const { return offset == o.offset && dx == o.dx && dy == o.dy; }
};

struct TwoPlaneParams {
  std::array<Plane, kPlaneCount> plane{};
  std::uint16_t mask = 0;                          // bit i: texel i's plane; bit 0 is 0 in a packed block
  int shape = 0;                                   // 0 .. 7
  std::array<int, kBaseCoordinateCount> base{};    // 0 .. 127
  std::array<std::uint8_t, kTexels> chroma_index{};   // 0 .. 3
  bool operator==(const TwoPlaneParams& o) const {
    return plane == o.plane && mask == o.mask && shape == o.shape && base == o.base && chroma_index == o.chroma_index;
  }
};

// Error names an out-of-range field, or a mask whose bit 0 is set (call canonicalize_mask_anchor first).
void pack_two_plane(const TwoPlaneParams& params, std::uint8_t* bytes);
TwoPlaneParams unpack_two_plane(const std::uint8_t* bytes);               // Error unless the selector is 1,1,1,0
// Mask anchor (file comment): when texel 0 takes plane 1, swaps the planes and inverts the mask; the decoded texels
// do not change. The encoder calls it before pack_two_plane.
void canonicalize_mask_anchor(TwoPlaneParams* params);

// Decoded log2 luminance of plane `p` at texel (x, y) before the black rule; clamped to [kLogLumMin, kLogLumMax].
inline double plane_log_luminance(const Plane& p, int x, int y) {
  const double ybar = kLogLumMin + (kLogLumRange * static_cast<double>(p.offset)) / static_cast<double>(kPlaneOffsetMax) +
                      static_cast<double>(p.dx * (2 * x - 3) + p.dy * (2 * y - 3)) / kPlaneDeltaDivisor;
  return std::min(kLogLumMax, std::max(kLogLumMin, ybar));   // slopes may overshoot the half range: clamp
}

// The templated decoder: x = (u0, v0, u1, v1) as T (the chroma base values; the luminance planes are integer-coded
// and decoded in double, then lifted to T).
template <typename T>
void decode_two_plane(const TwoPlaneParams& params, const ShapeSet& shapes, const T x[4], T rgb[kTexels][3]) {
  T landmark_u[kShapeLandmarkCount], landmark_v[kShapeLandmarkCount];
  decode_landmarks(shapes.shapes[static_cast<std::size_t>(params.shape)], x, landmark_u, landmark_v);
  for (int i = 0; i < kTexels; ++i) {
    const Plane& p = params.plane[static_cast<std::size_t>((params.mask >> i) & 1u)];
    // Offset code 0: true-black plane.
    const T luminance(p.offset == 0 ? 0.0 : std::exp2(plane_log_luminance(p, i % 4, i / 4)));
    const int k = params.chroma_index[static_cast<std::size_t>(i)];
    const T& u = landmark_u[k];
    const T& v = landmark_v[k];
    rgb[i][0] = (v * luminance) / T(kRec601WeightR);
    rgb[i][1] = (max(T(0.0), T(1.0) - u - v) * luminance) / T(kRec601WeightG);
    rgb[i][2] = (u * luminance) / T(kRec601WeightB);
  }
}

BlockTexels decode_two_plane_params(const TwoPlaneParams& params, const ShapeSet& shapes);
// The oracle (two_plane_reference_decode.cpp).
BlockTexels reference_decode_two_plane(const std::uint8_t* bytes, const ShapeSet& shapes);

}  // namespace blocklab::munkberg
