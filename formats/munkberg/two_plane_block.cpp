// Packing, unpacking and the double decoder of a two-plane block (formats/munkberg/two_plane_block.h; Munkberg et al.
// 2008, section 6.3 with section 5's shape-I chroma).
#include "formats/munkberg/two_plane_block.h"

#include <string>
#include <utility>

#include "core/bits.h"
#include "core/error.h"

namespace blocklab::munkberg {

namespace {

void check_range(const std::string& field, long long value, long long lo, long long hi) {
  if (value < lo || value > hi)
    fail("munkberg", "two_plane " + field + ": " + std::to_string(value) + " is outside " + std::to_string(lo) + ".." +
                         std::to_string(hi));
}

}  // namespace

void pack_two_plane(const TwoPlaneParams& params, std::uint8_t* bytes) {
  for (int p = 0; p < kPlaneCount; ++p) {
    const Plane& plane = params.plane[static_cast<std::size_t>(p)];
    const std::string name = "plane[" + std::to_string(p) + "].";
    check_range(name + "offset", plane.offset, 0, kPlaneOffsetMax);
    check_range(name + "dx", plane.dx, kPlaneDeltaMin, kPlaneDeltaMax);
    check_range(name + "dy", plane.dy, kPlaneDeltaMin, kPlaneDeltaMax);
  }
  // Mask anchor: texel 0's bit is not stored, so it must be 0 (canonicalize_mask_anchor).
  check_range("mask bit 0 (anchor; call canonicalize_mask_anchor)", params.mask & 1u, 0, 0);
  check_range("shape", params.shape, 0, kShapeCount - 1);
  for (int c = 0; c < kBaseCoordinateCount; ++c)
    check_range("base[" + std::to_string(c) + "]", params.base[static_cast<std::size_t>(c)], 0, kBaseCoordinateMax);
  for (int i = 0; i < kTexels; ++i)
    check_range("chroma_index[" + std::to_string(i) + "]", params.chroma_index[static_cast<std::size_t>(i)], 0,
                (1 << kChromaIndexBits) - 1);
  BitWriter128 writer;
  writer.write(kTwoPlaneSelector, kTwoPlaneSelectorBits);
  for (const Plane& plane : params.plane) {
    writer.write(static_cast<std::uint64_t>(plane.offset), kPlaneOffsetBits);
    writer.write_signed(plane.dx, kPlaneDeltaBits);
    writer.write_signed(plane.dy, kPlaneDeltaBits);
  }
  writer.write(static_cast<std::uint64_t>(params.mask >> 1), kPlaneMaskBits);   // texels 1..15
  writer.write(static_cast<std::uint64_t>(params.shape), kShapeIndexBits);
  for (const int code : params.base) writer.write(static_cast<std::uint64_t>(code), kBaseCoordinateBits);
  for (const std::uint8_t k : params.chroma_index) writer.write(k, kChromaIndexBits);
  if (!writer.full()) fail("munkberg", "internal: two_plane block not full after packing");
  writer.to_bytes(bytes);
}

TwoPlaneParams unpack_two_plane(const std::uint8_t* bytes) {
  if (block_mode_of(bytes) != BlockMode::two_plane) fail("munkberg", "unpack_two_plane: the selector is not 1,1,1,0");
  BitReader128 reader(bytes);
  reader.read(kTwoPlaneSelectorBits);
  TwoPlaneParams params;
  for (Plane& plane : params.plane) {
    plane.offset = static_cast<int>(reader.read(kPlaneOffsetBits));
    plane.dx = static_cast<int>(reader.read_signed(kPlaneDeltaBits));
    plane.dy = static_cast<int>(reader.read_signed(kPlaneDeltaBits));
  }
  params.mask = static_cast<std::uint16_t>(reader.read(kPlaneMaskBits) << 1);   // texel 0: plane 0 (anchor)
  params.shape = static_cast<int>(reader.read(kShapeIndexBits));
  for (int& code : params.base) code = static_cast<int>(reader.read(kBaseCoordinateBits));
  for (std::uint8_t& k : params.chroma_index) k = static_cast<std::uint8_t>(reader.read(kChromaIndexBits));
  return params;
}

void canonicalize_mask_anchor(TwoPlaneParams* params) {
  if ((params->mask & 1u) == 0u) return;
  std::swap(params->plane[0], params->plane[1]);
  params->mask = static_cast<std::uint16_t>(~params->mask);   // 16-bit: every texel changes plane with the planes
}

BlockTexels decode_two_plane_params(const TwoPlaneParams& params, const ShapeSet& shapes) {
  double x[4];
  for (int c = 0; c < 4; ++c) x[c] = base_value(params.base[static_cast<std::size_t>(c)]);
  double rgb[kTexels][3];
  decode_two_plane(params, shapes, x, rgb);
  return texels_from_rgb(rgb);
}

}  // namespace blocklab::munkberg
