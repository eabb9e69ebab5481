// The `rgbe` Format: Ward's RGBE shared-exponent texels, 32 bpp (Graphics Gems II "Real Pixels"; the baseline of
// Banterle et al. 2008 Table 1 and Wang et al. 2007 Table 2). Texels are encoded by rgbe_texel.cpp; this file
// tiles the image (core/blocks.h) and runs blocks in parallel, each block writing only its own 64-byte slot, so
// the bytes do not depend on the thread count.
#include <cmath>
#include <string>

#include "core/error.h"
#include "formats/rgbe/rgbe_format.h"
#include "formats/common/block_codec.h"

namespace blocklab {

namespace {

constexpr const char* kName = "rgbe";

struct RgbeOptions {
  RgbeDecodeOffset decode_offset = RgbeDecodeOffset::none;
};

const OptionTable<RgbeOptions>& rgbe_option_table() {
  static const auto table = OptionTable<RgbeOptions>().choice(
      "decode_offset", &RgbeOptions::decode_offset, {{"none", RgbeDecodeOffset::none}, {"half", RgbeDecodeOffset::half}},
      "value added to each mantissa byte when decoding: none = byte * 2^(E-136) (rgbe.c reader), half = (byte + 0.5) * "
      "2^(E-136) (Radiance's decoder; halves the mean truncation error). Encoded bytes are the same for both");
  return table;
}

class RgbeFormat final : public Format {
 public:
  std::string name() const override { return kName; }
  std::string description() const override {
    return "Ward's RGBE shared-exponent texels, 32 bpp (Graphics Gems II 'Real Pixels'; Radiance .hdr pixel)";
  }
  std::vector<OptionSpec> option_specs() const override { return rgbe_option_table().specs(); }
  std::vector<ModeSpec> mode_table() const override {
    return {{"rgbe", "every texel as RGB mantissas and a shared exponent"}};
  }
  int block_bytes(const FormatOptions&) const override { return kRgbeBlockBytes; }

  EncodedTexture encode(const Image& image, const FormatOptions& options,
                        const CodecContext& context) const override {
    validate_encoder_input(image, kName);
    reject_unstorable_texels(image);
    return encode_blocks(*this, image, options, context, kRgbeBlockBytes,
                         [](const BlockTexels& texels, std::size_t, std::uint8_t* out) {
                           pack_rgbe_block(texels, out);
                           return 0;   // the only mode, "rgbe"
                         });
  }

  Image decode(const EncodedTexture& texture, const CodecContext& context) const override {
    validate_encoded_texture(*this, texture, kName);
    const RgbeDecodeOffset offset = rgbe_option_table().from_resolved(texture.options).decode_offset;
    // A luminance source has R = G = B, which share one exponent and so get equal bytes.
    return decode_blocks(*this, texture, context, rgb_only_decoded_channels(texture.channels),
                         [offset](const std::uint8_t* bytes, std::size_t) { return unpack_rgbe_block(bytes, offset); });
  }

 private:
  // RGBE stores only finite non-negative values. The input policy guarantees them; a violation is a caller bug,
  // reported (first texel in row-major order, whatever the thread count) instead of silently mapped.
  static void reject_unstorable_texels(const Image& image) {
    for (int y = 0; y < image.height; ++y)
      for (int x = 0; x < image.width; ++x)
        for (int channel = 0; channel < 3; ++channel) {
          const float value = image.texel(x, y)[channel];
          if (!std::isfinite(value) || value < 0.0f)
            fail(kName, "pixel (" + std::to_string(x) + ", " + std::to_string(y) + ") channel " +
                            std::string(1, "RGB"[channel]) + " is " + std::to_string(value) +
                            "; RGBE stores finite non-negative values only (apply the input policy first)");
        }
  }
};

}  // namespace

const Format& rgbe_format() {
  static const RgbeFormat format;
  return format;
}

}  // namespace blocklab
