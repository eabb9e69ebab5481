// The `bc7` Format: encodes blocks with the mode/partition search of bc7_mode_search.h and decodes with the fast
// decoder decode(unpack(bytes)), through the shared parallel block loop of formats/common/block_codec.h.
#include "formats/bc7/bc7_format.h"

#include <cmath>
#include <string>

#include "core/blocks.h"
#include "core/error.h"
#include "formats/common/block_codec.h"
#include "formats/bc7/bc7_decode.h"
#include "formats/bc7/bc7_mode_search.h"
#include "formats/bc7/bc7_presets.h"
#include "formats/bc7/bc7_problems.h"

namespace blocklab {

namespace {

constexpr const char* kName = "bc7";

// [0, 1] -> nearest 8-bit code. Values outside [0, 1] (HDR input given to an LDR format) clamp.
std::uint8_t to_code(float value) {
  const float clamped = value < 0.0f ? 0.0f : (value > 1.0f ? 1.0f : value);
  return static_cast<std::uint8_t>(std::lround(clamped * 255.0f));
}

class Bc7Format final : public Format {
 public:
  std::string name() const override { return kName; }
  std::string description() const override {
    return "BC7 / BPTC unorm, 8 bpp, all 8 modes, PCA + least-squares encoder with presets (Khronos Data Format "
           "Spec, BPTC)";
  }
  std::vector<OptionSpec> option_specs() const override { return bc7::option_specs(); }
  std::vector<ModeSpec> mode_table() const override {
    return {{"mode0", "3 subsets, RGB 4.4.4 + P-bits, 3-bit indices"},
            {"mode1", "2 subsets, RGB 6.6.6 + shared P-bits, 3-bit indices"},
            {"mode2", "3 subsets, RGB 5.5.5, 2-bit indices"},
            {"mode3", "2 subsets, RGB 7.7.7 + P-bits, 2-bit indices"},
            {"mode4", "1 subset, RGB 5.5.5 + alpha 6, rotation, 2/3-bit index sets"},
            {"mode5", "1 subset, RGB 7.7.7 + alpha 8, rotation, 2-bit index sets"},
            {"mode6", "1 subset, RGBA 7.7.7.7 + P-bits, 4-bit indices"},
            {"mode7", "2 subsets, RGBA 5.5.5.5 + P-bits, 2-bit indices"}};
  }
  std::vector<FormatPreset> presets() const override { return bc7::presets(); }
  std::vector<BlockProblem> block_problems() const override { return bc7_block_problems(); }
  int block_bytes(const FormatOptions&) const override { return bc7::kBlockBytes; }
  // Revision 2: encoder only (per-lane rounding of least-squares endpoints, winner lattice polish, one-subset modes
  // searched first); the decoder and the block layout are unchanged, so files of revision 1 stay readable.
  // Revision 3: encoder only, preset thorough (palette-estimate partition re-ranking, 3-subset threshold); fast and
  // medium give the same bytes as revision 2.
  int revision() const override { return 3; }
  int decoder_revision() const override { return 1; }

  EncodedTexture encode(const Image& image, const FormatOptions& options, const CodecContext& context) const override {
    validate_encoder_input(image, kName);
    reject_nan_texels(image);
    const FormatOptions expanded = bc7::expand_bc7_options(options);
    const bc7::EncoderSettings settings = bc7::encoder_settings(expanded);
    const bool has_alpha = image.channels == 4;
    // The preset's knobs are recorded explicitly (bc7_presets.h).
    return encode_blocks(*this, image, expanded, context, bc7::kBlockBytes,
                         [&](const BlockTexels& block, std::size_t, std::uint8_t* out) {
                           std::uint8_t rgba[bc7::kTexels][4];
                           for (int i = 0; i < bc7::kTexels; ++i) {
                             for (int c = 0; c < 3; ++c) rgba[i][c] = to_code(block.rgba[i][c]);
                             // Sources without alpha are opaque: encode alpha 255 exactly.
                             rgba[i][3] = has_alpha ? to_code(block.rgba[i][3]) : 255;
                           }
                           const bc7::Params params = bc7::encode_block(rgba, settings);
                           bc7::pack(params, out);
                           return static_cast<int>(params.mode);
                         });
  }

  // A standard texture: its own DDS file.
  bool has_gpu_textures() const override { return true; }
  std::vector<GpuTexture> gpu_textures(const EncodedTexture& texture) const override { return {{"", texture}}; }

  Image decode(const EncodedTexture& texture, const CodecContext& context) const override {
    const bool keep_alpha = texture.channels == 4;
    return decode_blocks(*this, texture, context, texture.channels, [keep_alpha](const std::uint8_t* bytes, std::size_t) {
      const bc7::Params params = bc7::unpack(bytes);
      float decoded[bc7::kTexels][4];
      bc7::decode(params, decoded);
      BlockTexels block;
      for (int i = 0; i < bc7::kTexels; ++i) {
        for (int c = 0; c < 4; ++c) block.rgba[i][c] = decoded[i][c] / 255.0f;
        // Image convention: sources without alpha carry alpha 1.
        if (!keep_alpha) block.rgba[i][3] = 1.0f;
      }
      return block;
    });
  }

 private:
  static void reject_nan_texels(const Image& image) {
    for (int y = 0; y < image.height; ++y)
      for (int x = 0; x < image.width; ++x)
        for (int channel = 0; channel < 4; ++channel)
          if (std::isnan(image.texel(x, y)[channel]))
            fail(kName, "pixel (" + std::to_string(x) + ", " + std::to_string(y) + ") channel " +
                            std::string(1, "RGBA"[channel]) + " is NaN (apply the input policy before encoding)");
  }
};

}  // namespace

const Format& bc7_format() {
  static const Bc7Format format;
  return format;
}

}  // namespace blocklab
