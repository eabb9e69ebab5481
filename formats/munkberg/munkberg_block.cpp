// Packing, unpacking and the double decoder of one `munkberg` block (formats/munkberg/munkberg_block.h; layout
// formats/munkberg/munkberg_layout.h; Munkberg et al. 2008, sections 3.1, 5, 7.1).
#include "formats/munkberg/munkberg_block.h"

#include <string>
#include <utility>

#include "core/bits.h"
#include "core/error.h"
#include "formats/munkberg/field_range.h"

namespace blocklab::munkberg {

bool Params::operator==(const Params& other) const {
  return mode == other.mode && shape == other.shape && base == other.base && lum == other.lum &&
         lum_index == other.lum_index && chroma_index == other.chroma_index;
}

void pack_block(const Params& params, std::uint8_t* bytes) {
  const Mode mode = params.mode;
  if (mode != Mode::shape_ii && mode != Mode::shape_i)
    fail("munkberg", "mode: " + std::to_string(static_cast<int>(mode)) + " is not shape_ii (0) or shape_i (1)");
  check_field_range(params.shape, 0, kShapeCount - 1, [] { return std::string("shape"); });
  for (int c = 0; c < kBaseCoordinateCount; ++c)
    check_field_range(params.base[static_cast<std::size_t>(c)], 0, kBaseCoordinateMax,
                      [c] { return "base[" + std::to_string(c) + "]"; });
  for (int e = 0; e < kLumEndpointCount; ++e)
    check_field_range(params.lum[static_cast<std::size_t>(e)], 0, kLumEndpointMax,
                      [e] { return "lum[" + std::to_string(e) + "]"; });
  const int n = lum_levels_minus_one(mode);
  for (int i = 0; i < kTexels; ++i)
    check_field_range(params.lum_index[static_cast<std::size_t>(i)], 0, n,
                      [i] { return "lum_index[" + std::to_string(i) + "]"; });
  // Shape I's anchor (munkberg_layout.h): texel 0's index is stored in 2 bits; canonicalize_anchor() fixes it.
  if (mode == Mode::shape_i && params.lum_index[0] > kShape1AnchorIndexMax)
    fail("munkberg", "lum_index[0]: " + std::to_string(params.lum_index[0]) +
                         " is above the shape I anchor maximum " + std::to_string(kShape1AnchorIndexMax) +
                         " (call canonicalize_anchor first)");
  const int groups = chroma_groups(mode);
  for (int g = 0; g < kTexels; ++g)
    // Unused groups (shape II has 8) must be 0 so that pack(unpack(b)) == b and equal blocks compare equal.
    check_field_range(params.chroma_index[static_cast<std::size_t>(g)], 0, g < groups ? (1 << kChromaIndexBits) - 1 : 0,
                      [g] { return "chroma_index[" + std::to_string(g) + "]"; });

  BitWriter128 writer;
  writer.write(selector_value(mode), selector_bits(mode));
  writer.write(static_cast<std::uint64_t>(params.shape), kShapeIndexBits);
  for (int c = 0; c < kBaseCoordinateCount; ++c)
    writer.write(static_cast<std::uint64_t>(params.base[static_cast<std::size_t>(c)]), kBaseCoordinateBits);
  for (int e = 0; e < kLumEndpointCount; ++e)
    writer.write(static_cast<std::uint64_t>(params.lum[static_cast<std::size_t>(e)]), kLumEndpointBits);
  for (int i = 0; i < kTexels; ++i)
    writer.write(params.lum_index[static_cast<std::size_t>(i)], lum_index_stored_bits(mode, i));
  for (int g = 0; g < groups; ++g) writer.write(params.chroma_index[static_cast<std::size_t>(g)], kChromaIndexBits);
  if (!writer.full()) fail("munkberg", "internal: block not full after packing (" + std::to_string(writer.position()) + " bits)");
  writer.to_bytes(bytes);
}

Params unpack_block(const std::uint8_t* bytes) {
  BitReader128 reader(bytes);
  Params params;
  const BlockMode block_mode = block_mode_of(bytes);
  if (block_mode != BlockMode::shape_ii && block_mode != BlockMode::shape_i)
    fail("munkberg", "unpack_block: the selector is not shape II (0) or shape I (1,0); decode with decode_any_block");
  params.mode = block_mode == BlockMode::shape_ii ? Mode::shape_ii : Mode::shape_i;
  reader.read(selector_bits(params.mode));
  params.shape = static_cast<int>(reader.read(kShapeIndexBits));
  for (int c = 0; c < kBaseCoordinateCount; ++c)
    params.base[static_cast<std::size_t>(c)] = static_cast<int>(reader.read(kBaseCoordinateBits));
  for (int e = 0; e < kLumEndpointCount; ++e)
    params.lum[static_cast<std::size_t>(e)] = static_cast<int>(reader.read(kLumEndpointBits));
  for (int i = 0; i < kTexels; ++i)
    params.lum_index[static_cast<std::size_t>(i)] =
        static_cast<std::uint8_t>(reader.read(lum_index_stored_bits(params.mode, i)));
  for (int g = 0; g < chroma_groups(params.mode); ++g)
    params.chroma_index[static_cast<std::size_t>(g)] = static_cast<std::uint8_t>(reader.read(kChromaIndexBits));
  return params;
}

void canonicalize_anchor(Params* params) {
  // Shape II stores every index in full; shape I's texel 0 must be <= 3: swap the endpoints and mirror the indices
  // (q = (n - l) e0 + l e1 is unchanged, so the decoded texels are bit-identical).
  if (params->mode != Mode::shape_i || params->lum_index[0] <= kShape1AnchorIndexMax) return;
  const int n = lum_levels_minus_one(params->mode);
  std::swap(params->lum[0], params->lum[1]);
  for (std::uint8_t& l : params->lum_index) l = static_cast<std::uint8_t>(n - l);
}

std::array<double, 6> decode_parameters(const Params& params) {
  return {static_cast<double>(params.lum[0]), static_cast<double>(params.lum[1]), base_value(params.base[0]),
          base_value(params.base[1]),         base_value(params.base[2]),         base_value(params.base[3])};
}

BlockTexels texels_from_rgb(const double (&rgb)[kTexels][3]) {
  BlockTexels texels;
  for (int i = 0; i < kTexels; ++i) {
    for (int c = 0; c < 3; ++c) texels.rgba[i][c] = static_cast<float>(rgb[i][c]);
    texels.rgba[i][3] = 1.0f;
  }
  return texels;
}

BlockTexels decode_params(const Params& params, const ShapeSet& shapes) {
  const std::array<double, 6> x = decode_parameters(params);
  double rgb[kTexels][3];
  decode_block(params, shapes, x.data(), rgb);
  return texels_from_rgb(rgb);
}

}  // namespace blocklab::munkberg
