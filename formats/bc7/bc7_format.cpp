// The `bc7` Format: tiles the image, encodes blocks in parallel (each block writes only its own 16-byte slot, so
// the bytes do not depend on the thread count) and decodes with the fast decoder decode(unpack(bytes)).
#include "formats/bc7/bc7_format.h"

#include <cmath>
#include <string>

#include "core/blocks.h"
#include "core/error.h"
#include "core/parallel.h"
#include "formats/bc7/bc7_decode.h"
#include "formats/bc7/bc7_mode_search.h"
#include "formats/bc7/bc7_presets.h"

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
  std::vector<std::string> modes() const override {
    return {"mode0", "mode1", "mode2", "mode3", "mode4", "mode5", "mode6", "mode7"};
  }
  int block_bytes(const FormatOptions&) const override { return bc7::kBlockBytes; }

  EncodedTexture encode(const Image& image, const FormatOptions& options, const CodecContext& context) const override {
    validate_encoder_input(image, kName);
    reject_nan_texels(image);
    const FormatOptions expanded = bc7::expand_bc7_options(options);
    const bc7::EncoderSettings settings = bc7::encoder_settings(expanded);
    const BlockGrid grid(image.width, image.height);
    EncodedTexture texture;
    texture.format = kName;
    texture.options = expanded;   // the preset's knobs made explicit (bc7_presets.h)
    texture.width = image.width;
    texture.height = image.height;
    texture.channels = image.channels;
    texture.block_bytes = bc7::kBlockBytes;
    texture.blocks.resize(grid.block_count() * bc7::kBlockBytes);
    texture.block_modes.resize(grid.block_count());
    const bool has_alpha = image.channels == 4;
    parallel_for_index(grid.block_count(), context.threads, [&](std::size_t index) {
      const BlockTexels block = load_block(image, grid, index);
      std::uint8_t rgba[bc7::kTexels][4];
      for (int i = 0; i < bc7::kTexels; ++i) {
        for (int c = 0; c < 3; ++c) rgba[i][c] = to_code(block.rgba[i][c]);
        // Sources without alpha are opaque: encode alpha 255 exactly.
        rgba[i][3] = has_alpha ? to_code(block.rgba[i][3]) : 255;
      }
      const bc7::Params params = bc7::encode_block(rgba, settings);
      bc7::pack(params, texture.blocks.data() + index * bc7::kBlockBytes);
      texture.block_modes[index] = static_cast<std::uint8_t>(params.mode);
    });
    return texture;
  }

  Image decode(const EncodedTexture& texture, const CodecContext& context) const override {
    validate_encoded_texture(*this, texture, kName);
    const BlockGrid grid(texture.width, texture.height);
    Image image(texture.width, texture.height, texture.channels);
    const bool keep_alpha = texture.channels == 4;
    parallel_for_index(grid.block_count(), context.threads, [&](std::size_t index) {
      const bc7::Params params = bc7::unpack(texture.blocks.data() + index * bc7::kBlockBytes);
      float decoded[bc7::kTexels][4];
      bc7::decode(params, decoded);
      BlockTexels block;
      for (int i = 0; i < bc7::kTexels; ++i) {
        for (int c = 0; c < 4; ++c) block.rgba[i][c] = decoded[i][c] / 255.0f;
        // Image convention: sources without alpha carry alpha 1.
        if (!keep_alpha) block.rgba[i][3] = 1.0f;
      }
      store_block(image, grid, index, block);
    });
    return image;
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
