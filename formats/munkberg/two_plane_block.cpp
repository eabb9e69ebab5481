// Packing, unpacking and the double decoder of a two-plane block (formats/munkberg/two_plane_block.h; Munkberg et al.
// 2008, section 6.3 with section 5's shape-I chroma).
#include "formats/munkberg/two_plane_block.h"

#include <string>
#include <utility>

#include "core/bits.h"
#include "core/error.h"
#include "formats/munkberg/field_range.h"

namespace blocklab::munkberg {

void pack_two_plane(const TwoPlaneParams& params, std::uint8_t* bytes) {
  for (int p = 0; p < kPlaneCount; ++p) {
    const Plane& plane = params.plane[static_cast<std::size_t>(p)];
    const auto name = [p](const char* field) { return "two_plane plane[" + std::to_string(p) + "]." + field; };
    check_field_range(plane.offset, 0, kPlaneOffsetMax, [&] { return name("offset"); });
    check_field_range(plane.dx, kPlaneDeltaMin, kPlaneDeltaMax, [&] { return name("dx"); });
    check_field_range(plane.dy, kPlaneDeltaMin, kPlaneDeltaMax, [&] { return name("dy"); });
  }
  // Mask anchor: texel 0's bit is not stored, so it must be 0 (canonicalize_mask_anchor).
  check_field_range(params.mask & 1u, 0, 0,
                    [] { return std::string("two_plane mask bit 0 (anchor; call canonicalize_mask_anchor)"); });
  check_field_range(params.shape, 0, kShapeCount - 1, [] { return std::string("two_plane shape"); });
  for (int c = 0; c < kBaseCoordinateCount; ++c)
    check_field_range(params.base[static_cast<std::size_t>(c)], 0, kBaseCoordinateMax,
                      [c] { return "two_plane base[" + std::to_string(c) + "]"; });
  for (int i = 0; i < kTexels; ++i)
    check_field_range(params.chroma_index[static_cast<std::size_t>(i)], 0, (1 << kChromaIndexBits) - 1,
                      [i] { return "two_plane chroma_index[" + std::to_string(i) + "]"; });
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
