// The `bc3` Format (formats/bc3/bc3_format.h): colour and alpha encoded independently per block, in parallel over
// blocks (each block writes its own 16-byte slot, so the bytes do not depend on the thread count).
#include "formats/bc3/bc3_format.h"

#include <string>

#include "core/error.h"
#include "core/parallel.h"
#include "formats/bc3/bc3_block.h"
#include "formats/bc4/bc4_encoder.h"
#include "formats/common/s3tc_color_fit.h"

namespace blocklab {

namespace {

constexpr const char* kName = "bc3";

class Bc3Format final : public Format {
 public:
  std::string name() const override { return kName; }
  std::string description() const override {
    return "BC3/DXT5 RGBA, 8 bpp: 4-colour BC1 colour block + 8-bit interpolated alpha block (KDFS S3TC)";
  }
  std::vector<OptionSpec> option_specs() const override {
    return {
        {"search", OptionType::choice, "default", {"fast", "default", "exhaustive"},
         "endpoint search for colour and alpha: fast, default (cluster fit + polish), exhaustive"},
        {"weights", OptionType::text, "1,1,1", {}, "per-channel colour error weights 'r,g,b' (non-negative, not all 0)"},
        {"solver", OptionType::choice, "builtin", {"builtin"}, "endpoint solver (builtin search pipeline)"},
    };
  }
  // The colour half is always 4-colour; the modes are those of the alpha half.
  std::vector<std::string> modes() const override { return {"eight_alpha", "six_alpha"}; }
  int block_bytes(const FormatOptions&) const override { return kBc3BlockBytes; }

  EncodedTexture encode(const Image& image, const FormatOptions& options,
                        const CodecContext& context) const override {
    validate_encoder_input(image, kName);
    ColorFitSettings settings;
    settings.search = parse_s3tc_search(option_text(options, "search"), kName);
    settings.allow_three_color = false;   // BC3 colour is always decoded with 4 colours (SPECS.md 2.5 item 2)
    const std::array<float, 3> weights = parse_channel_weights(option_text(options, "weights"), kName);
    const BlockGrid grid(image.width, image.height);
    EncodedTexture texture;
    texture.format = kName;
    texture.options = options;
    texture.width = image.width;
    texture.height = image.height;
    texture.channels = image.channels;
    texture.block_bytes = kBc3BlockBytes;
    texture.blocks.resize(grid.block_count() * kBc3BlockBytes);
    texture.block_modes.resize(grid.block_count());
    std::uint8_t* blocks = texture.blocks.data();
    std::uint8_t* modes = texture.block_modes.data();
    parallel_for_index(grid.block_count(), context.threads, [&](std::size_t index) {
      const BlockTexels texels = load_block(image, grid, index);
      Bc3Params params;
      params.color = fit_color_block(make_color_block(texels, weights), settings);
      float alpha[16];
      for (int texel = 0; texel < 16; ++texel) {
        const float value = texels.rgba[texel][3];
        alpha[texel] = value >= 1.0f ? 255.0f : (value > 0.0f ? value * 255.0f : 0.0f);   // clamp to [0, 255]
      }
      params.alpha = fit_bc4_block(alpha, settings.search);
      pack_bc3_block(params, blocks + index * kBc3BlockBytes);
      modes[index] = static_cast<std::uint8_t>(params.alpha.mode);   // 0 eight_alpha, 1 six_alpha
    });
    return texture;
  }

  Image decode(const EncodedTexture& texture, const CodecContext& context) const override {
    validate_encoded_texture(*this, texture, kName);
    const BlockGrid grid(texture.width, texture.height);
    Image image(texture.width, texture.height, texture.channels);   // alpha kept only for 4-channel sources
    const bool keep_alpha = texture.channels == 4;
    const std::uint8_t* blocks = texture.blocks.data();
    parallel_for_index(grid.block_count(), context.threads, [&](std::size_t index) {
      BlockTexels texels = decode_bc3_params(unpack_bc3_block(blocks + index * kBc3BlockBytes));
      // A source without alpha stored alpha = 1 (255): report the image as it came, alpha 1.
      if (!keep_alpha)
        for (auto& texel : texels.rgba) texel[3] = 1.0f;
      store_block(image, grid, index, texels);
    });
    return image;
  }
};

}  // namespace

const Format& bc3_format() {
  static const Bc3Format format;
  return format;
}

}  // namespace blocklab
