// Multi-level decomposition of one `mavridis` plane (Mavridis & Papaioannou 2012, section 3.4): "the same encoding
// process can be applied recursively" to the scale coefficients LL; "the coefficients of the last level should be
// stored as a DXT5 or BC7 texture, as described before, while previous levels are stored in the DXT1 format".
//
// Level k (1 .. N-1) of a plane of size w_{k-1} x h_{k-1} (w_0 = width, w_k = ceil(w_{k-1} / 2)): its three wavelet
// bands (HL', LH', HH' for PI-Haar; HL, LH, HH for Haar) in the R, G, B of a half-resolution DXT1 texture (4-colour
// blocks, 8 bytes per 8x8 texels of the level = 1 bpp), each band mapped by section 3.2 (centre, half range shrunk
// by the clamp, gamma; clamp and gamma searched per level like the last level's, on the level's reconstruction
// error with its exact LL). LL (w_k x h_k, eq. 1's scale: twice the 2x2 mean) is the next level's plane. Level N
// is coded by mavridis_plane_codec.h (DXT5 or BC7, 2 bpp of its plane). Rate B_N = 1 + B_{N-1} / 4, B_1 = 2:
// 1.5 bpp at N = 2, 1.375 at N = 3.
//
// Bytes: level 1's DXT1 blocks (row-major, ceil(w_0 / 8) x ceil(h_0 / 8)), level 2's, ..., then level N's blocks.
// Decode, coarse to fine: level N's plane (eq. 3), then per finer level eq. 3 on (decoded LL, dequantised bands).
// LL of level k divided by 2^k is the box-filtered mip k of the plane.
#pragma once

#include <cstdint>
#include <vector>

#include "formats/mavridis/mavridis_plane_codec.h"

namespace blocklab {
namespace mavridis {

struct MultilevelPlane {
  std::vector<std::uint8_t> bytes;          // multilevel_plane_bytes(width, height, levels)
  std::vector<BandMapping> detail;          // levels 1 .. N-1 (their LL entries unused)
  std::vector<double> detail_clamp, detail_error;   // the search's choice and squared error per detail level
  WaveletPlane last;                        // level N (its bytes also copied at the end of `bytes`)
};

// Size of level k's plane (k = 0: the plane itself).
inline int level_size(int size, int level) {
  for (int k = 0; k < level; ++k) size = (size + 1) / 2;
  return size;
}
inline std::size_t detail_level_bytes(int width, int height) {
  return static_cast<std::size_t>(wavelet_blocks_x(width)) * static_cast<std::size_t>(wavelet_blocks_x(height)) * 8;
}
std::size_t multilevel_plane_bytes(int width, int height, int levels);

// levels >= 1 (1 = encode_wavelet_plane); Haar or PI-Haar (integer transforms are refused by the format).
MultilevelPlane encode_multilevel_plane(const Plane& plane, const WaveletSettings& settings, int levels);

// detail.size() = levels - 1.
Plane decode_multilevel_plane(const std::uint8_t* bytes, int width, int height, const std::vector<BandMapping>& detail,
                              const BandMapping& last, Transform transform, double w, int threads, Packing packing);

// The oracle (mavridis_reference_decode.cpp): DXT1 bits read by hand, eq. 2 inverted and eq. 1 per level.
Plane reference_decode_multilevel_plane(const std::uint8_t* bytes, int width, int height,
                                        const std::vector<BandMapping>& detail, const BandMapping& last,
                                        Transform transform, double w, Packing packing);

}  // namespace mavridis
}  // namespace blocklab
