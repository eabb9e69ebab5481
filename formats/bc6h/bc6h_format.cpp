// The `bc6h` and `bc6h_sf` Formats: encode with bc6h_mode_search.h, decode with decode<kSigned>(unpack(bytes)), both
// through the shared parallel block loop of formats/common/block_codec.h (bytes identical at any thread count).
#include "formats/bc6h/bc6h_format.h"

#include <cmath>
#include <string>

#include "core/blocks.h"
#include "core/error.h"
#include "formats/bc6h/bc6h_decode.h"
#include "formats/bc6h/bc6h_half.h"
#include "formats/bc6h/bc6h_mode_search.h"
#include "formats/bc6h/bc6h_presets.h"
#include "formats/bc6h/bc6h_problems.h"
#include "formats/common/block_codec.h"

namespace blocklab {

namespace {

class Bc6hFormat final : public Format {
 public:
  explicit Bc6hFormat(bool is_signed) : is_signed_(is_signed) {}
  std::string name() const override { return is_signed_ ? "bc6h_sf" : "bc6h"; }
  std::string description() const override {
    return std::string("BC6H ") + (is_signed_ ? "SF16 (signed" : "UF16 (unsigned") +
           " half floats), 8 bpp HDR RGB, all 14 modes; line fit + least squares in the half-bit domain (Khronos Data "
           "Format Spec, BC6H)";
  }
  std::vector<OptionSpec> option_specs() const override { return bc6h::option_specs(); }
  std::vector<ModeSpec> mode_table() const override {
    std::vector<ModeSpec> table;
    for (int index = 0; index < bc6h::kModeCount; ++index) {
      const bc6h::ModeInfo& mode = bc6h::mode_info(index);
      std::string description = std::to_string(mode.subset_count) + (mode.subset_count == 1 ? " subset" : " subsets") +
                                ", " + std::to_string(mode.endpoint_bits) + "-bit endpoints";
      if (mode.transformed)
        description += ", deltas " + std::to_string(mode.delta_bits[0]) + "." + std::to_string(mode.delta_bits[1]) +
                       "." + std::to_string(mode.delta_bits[2]);
      description += mode.subset_count == 1 ? ", 4-bit indices" : ", 3-bit indices";
      table.push_back({"mode" + std::to_string(mode.mode_number), description});
    }
    return table;
  }
  std::vector<FormatPreset> presets() const override { return bc6h::presets(); }
  // Revision 2: the presets search with error=mpsnr_weighted (medium also with two refinement rounds); the decoder
  // and the block layout are unchanged, so files of revision 1 stay readable.
  int revision() const override { return 2; }
  int decoder_revision() const override { return 1; }
  std::vector<BlockProblem> block_problems() const override { return bc6h_block_problems(is_signed_); }
  int block_bytes(const FormatOptions&) const override { return bc6h::kBlockBytes; }

  EncodedTexture encode(const Image& image, const FormatOptions& options, const CodecContext& context) const override {
    validate_encoder_input(image, name());
    reject_nan_texels(image);
    const FormatOptions expanded = bc6h::expand_bc6h_options(options, name());
    const bc6h::EncoderSettings settings = bc6h::encoder_settings(expanded, name());
    const bool is_signed = is_signed_;
    return encode_blocks(*this, image, expanded, context, bc6h::kBlockBytes,
                         [&settings, is_signed](const BlockTexels& block, std::size_t, std::uint8_t* out) {
                           const bc6h::BlockTarget target = bc6h::make_block_target(block.rgba, is_signed, settings.error);
                           const bc6h::EncodedBlock encoded = bc6h::encode_block(target, settings);
                           bc6h::pack(encoded.params, out);
                           return encoded.params.mode_index;
                         });
  }

  // A standard texture: its own DDS file (dxgiFormat 95 or 96).
  bool has_gpu_textures() const override { return true; }
  std::vector<GpuTexture> gpu_textures(const EncodedTexture& texture) const override { return {{"", texture}}; }

  Image decode(const EncodedTexture& texture, const CodecContext& context) const override {
    const bool is_signed = is_signed_;
    return decode_blocks(*this, texture, context, rgb_only_decoded_channels(texture.channels),
                         [is_signed](const std::uint8_t* bytes, std::size_t) {
                           std::uint16_t halves[bc6h::kTexels][3];
                           bc6h::decode(bc6h::unpack(bytes), is_signed, halves);
                           BlockTexels block;
                           for (int i = 0; i < bc6h::kTexels; ++i) {
                             for (int c = 0; c < 3; ++c) block.rgba[i][c] = bc6h::half_bits_to_float(halves[i][c]);
                             block.rgba[i][3] = 1.0f;
                           }
                           return block;
                         });
  }

 private:
  void reject_nan_texels(const Image& image) const {
    for (int y = 0; y < image.height; ++y)
      for (int x = 0; x < image.width; ++x)
        for (int channel = 0; channel < 3; ++channel)
          if (std::isnan(image.texel(x, y)[channel]))
            fail(name(), "pixel (" + std::to_string(x) + ", " + std::to_string(y) + ") channel " +
                             std::string(1, "RGB"[channel]) + " is NaN (apply the input policy before encoding)");
  }

  bool is_signed_;
};

}  // namespace

const Format& bc6h_format() {
  static const Bc6hFormat format(false);
  return format;
}

const Format& bc6h_sf_format() {
  static const Bc6hFormat format(true);
  return format;
}

}  // namespace blocklab
