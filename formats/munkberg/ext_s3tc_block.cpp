// Packing, unpacking and the double decoder of an extended-S3TC block (formats/munkberg/ext_s3tc_block.h; Munkberg et
// al. 2008, section 6.1).
#include "formats/munkberg/ext_s3tc_block.h"

#include <cmath>
#include <string>
#include <utility>

#include "core/bits.h"
#include "core/error.h"
#include "formats/munkberg/field_range.h"
#include "formats/munkberg/munkberg_block.h"   // texels_from_rgb

namespace blocklab::munkberg {

namespace {

int index_stored_bits(int texel) { return texel == 0 ? kExtS3tcAnchorIndexBits : kExtS3tcIndexBits; }

}  // namespace

ExtS3tcSpace ext_s3tc_space_of(const std::map<std::string, std::vector<double>>& side_data) {
  const auto it = side_data.find(kExtS3tcSpaceKey);
  if (it == side_data.end()) return ExtS3tcSpace::rgb;   // absent: the paper's RGB line
  if (it->second.size() != 1 || !(it->second[0] == 0.0 || it->second[0] == 1.0))
    fail("munkberg", std::string("side data '") + kExtS3tcSpaceKey + "': expected one value 0 (rgb) or 1 (logyuv)");
  return it->second[0] == 0.0 ? ExtS3tcSpace::rgb : ExtS3tcSpace::logyuv;
}

void pack_ext_s3tc(const ExtS3tcParams& params, std::uint8_t* bytes) {
  for (int e = 0; e < 2; ++e)
    for (int c = 0; c < kExtS3tcChannels; ++c)
      check_field_range(params.endpoint[static_cast<std::size_t>(e)][static_cast<std::size_t>(c)], 0,
                        (1 << kExtS3tcChannelBits[static_cast<std::size_t>(c)]) - 1, [e, c] {
                          return "ext_s3tc endpoint[" + std::to_string(e) + "][" + std::to_string(c) + "]";
                        });
  for (int i = 0; i < kTexels; ++i)
    // Texel 0 is the anchor: its index MSB is implied 0 (canonicalize_ext_s3tc).
    check_field_range(params.index[static_cast<std::size_t>(i)], 0, i == 0 ? kExtS3tcAnchorIndexMax : kExtS3tcLevelsMinusOne,
                      [i] { return "ext_s3tc index[" + std::to_string(i) + "]"; });
  BitWriter128 writer;
  writer.write(kExtS3tcSelector, kExtS3tcSelectorBits);
  for (int e = 0; e < 2; ++e)
    for (int c = 0; c < kExtS3tcChannels; ++c)
      writer.write(static_cast<std::uint64_t>(params.endpoint[static_cast<std::size_t>(e)][static_cast<std::size_t>(c)]),
                   kExtS3tcChannelBits[static_cast<std::size_t>(c)]);
  for (int i = 0; i < kTexels; ++i) writer.write(params.index[static_cast<std::size_t>(i)], index_stored_bits(i));
  if (!writer.full()) fail("munkberg", "internal: ext_s3tc block not full after packing");
  writer.to_bytes(bytes);
}

ExtS3tcParams unpack_ext_s3tc(const std::uint8_t* bytes) {
  if (block_mode_of(bytes) != BlockMode::ext_s3tc) fail("munkberg", "unpack_ext_s3tc: the selector is not 1,1,0");
  BitReader128 reader(bytes);
  reader.read(kExtS3tcSelectorBits);
  ExtS3tcParams params;
  for (int e = 0; e < 2; ++e)
    for (int c = 0; c < kExtS3tcChannels; ++c)
      params.endpoint[static_cast<std::size_t>(e)][static_cast<std::size_t>(c)] =
          static_cast<int>(reader.read(kExtS3tcChannelBits[static_cast<std::size_t>(c)]));
  for (int i = 0; i < kTexels; ++i)
    params.index[static_cast<std::size_t>(i)] = static_cast<std::uint8_t>(reader.read(index_stored_bits(i)));
  return params;
}

void canonicalize_ext_s3tc(ExtS3tcParams* params) {
  if (params->index[0] <= kExtS3tcAnchorIndexMax) return;
  std::swap(params->endpoint[0], params->endpoint[1]);
  for (std::uint8_t& l : params->index) l = static_cast<std::uint8_t>(kExtS3tcLevelsMinusOne - l);
}

std::array<double, 6> ext_s3tc_parameters(const ExtS3tcParams& params, ExtS3tcSpace space) {
  std::array<double, 6> x{};
  for (int e = 0; e < 2; ++e) {
    const auto& code = params.endpoint[static_cast<std::size_t>(e)];
    double* out = x.data() + 3 * e;
    if (space == ExtS3tcSpace::rgb) {
      for (int c = 0; c < 3; ++c)
        out[c] = ext_s3tc_rgb_value(code[static_cast<std::size_t>(c)], kExtS3tcChannelBits[static_cast<std::size_t>(c)]);
    } else {
      out[0] = static_cast<double>(code[0]);   // log-luminance in code units (the decoder scales it)
      out[1] = static_cast<double>(code[1]) / static_cast<double>((1 << kExtS3tcChannelBits[1]) - 1);
      out[2] = static_cast<double>(code[2]) / static_cast<double>((1 << kExtS3tcChannelBits[2]) - 1);
    }
  }
  return x;
}

BlockTexels decode_ext_s3tc_params(const ExtS3tcParams& params, ExtS3tcSpace space) {
  const std::array<double, 6> x = ext_s3tc_parameters(params, space);
  double rgb[kTexels][3];
  decode_ext_s3tc(params, space, x.data(), rgb);
  return texels_from_rgb(rgb);
}

}  // namespace blocklab::munkberg
