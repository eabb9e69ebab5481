// The `fp16` Format: IEEE 754 binary16 RGB, 48 bpp (the FP16 baseline of Wang et al. 2007, Table 2).
// Blocks are packed and unpacked by fp16_block.cpp; this file tiles the image (core/blocks.h) and runs the blocks in
// parallel, each block writing only its own 96-byte slot, so the bytes do not depend on the thread count.
#include <cmath>
#include <string>

#include "core/error.h"
#include "formats/fp16/fp16_format.h"
#include "formats/common/block_codec.h"

namespace blocklab {

namespace {

constexpr const char* kName = "fp16";

class Fp16Format final : public Format {
 public:
  std::string name() const override { return kName; }
  std::string description() const override {
    return "IEEE 754 binary16 RGB per texel, 48 bpp, round to nearest even (FP16 baseline, Wang et al. 2007 "
           "Table 2)";
  }
  std::vector<OptionSpec> option_specs() const override { return {}; }   // only the common options
  std::vector<ModeSpec> mode_table() const override { return {{"rgb_half", "every texel as three IEEE halves"}}; }
  int block_bytes(const FormatOptions&) const override { return kFp16BlockBytes; }

  EncodedTexture encode(const Image& image, const FormatOptions& options,
                        const CodecContext& context) const override {
    validate_encoder_input(image, kName);
    reject_nan_texels(image);
    return encode_blocks(*this, image, options, context, kFp16BlockBytes,
                         [](const BlockTexels& texels, std::size_t, std::uint8_t* out) {
                           pack_fp16_block(texels, out);
                           return 0;   // the only mode, "rgb_half"
                         });
  }

  Image decode(const EncodedTexture& texture, const CodecContext& context) const override {
    validate_encoded_texture(*this, texture, kName);
    reject_non_finite_halves(texture, BlockGrid(texture.width, texture.height));
    // Equal floats give equal halves, so a luminance source still decodes with R = G = B.
    return decode_blocks(*this, texture, context, rgb_only_decoded_channels(texture.channels),
                         [](const std::uint8_t* bytes, std::size_t) { return unpack_fp16_block(bytes); });
  }

 private:
  // Checked before the parallel loop so that the error names the first offending texel in row-major order,
  // whatever the thread count.
  static void reject_nan_texels(const Image& image) {
    for (int y = 0; y < image.height; ++y)
      for (int x = 0; x < image.width; ++x)
        for (int channel = 0; channel < 3; ++channel)
          if (std::isnan(image.texel(x, y)[channel]))
            fail(kName, "pixel (" + std::to_string(x) + ", " + std::to_string(y) + ") channel " +
                            std::string(1, "RGB"[channel]) + " is NaN (apply the input policy before encoding)");
  }

  static void reject_non_finite_halves(const EncodedTexture& texture, const BlockGrid& grid) {
    for (std::size_t index = 0; index < grid.block_count(); ++index) {
      const std::uint8_t* block = texture.blocks.data() + index * kFp16BlockBytes;
      for (int half_index = 0; half_index < kBlockTexels * 3; ++half_index) {
        const unsigned bits = block[2 * half_index] | (static_cast<unsigned>(block[2 * half_index + 1]) << 8);
        // Inf/NaN bit patterns cannot come from the encoder: the data is corrupt.
        if (!fp16_bits_are_finite(bits))
          fail(kName, "block " + std::to_string(index) + " texel " + std::to_string(half_index / 3) + " channel " +
                          std::string(1, "RGB"[half_index % 3]) + " holds a non-finite half (bits " +
                          std::to_string(bits) + "); the encoder never writes Inf or NaN");
      }
    }
  }
};

}  // namespace

const Format& fp16_format() {
  static const Fp16Format format;
  return format;
}

}  // namespace blocklab
