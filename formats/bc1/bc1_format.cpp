// The `bc1` Format (formats/bc1/bc1_format.h): tiles the image (core/blocks.h), encodes each block with the S3TC
// colour encoder and decodes with the reference decoding, in parallel over blocks; every block writes only its own
// 8-byte slot, so the bytes do not depend on the thread count.
#include "formats/bc1/bc1_format.h"

#include <string>

#include "core/error.h"
#include "core/parallel.h"
#include "formats/bc1/bc1_block.h"
#include "formats/common/s3tc_color_fit.h"

namespace blocklab {

namespace {

constexpr const char* kName = "bc1";

class Bc1Format final : public Format {
 public:
  std::string name() const override { return kName; }
  std::string description() const override {
    return "BC1/DXT1 opaque RGB, 4 bpp, RGB565 endpoints, 4- and 3-colour modes (KDFS S3TC); cluster-fit encoder";
  }
  std::vector<OptionSpec> option_specs() const override {
    return {
        {"search", OptionType::choice, "default", {"fast", "default", "exhaustive"},
         "endpoint search: fast (axis bounding box + least squares), default (cluster fit + polish), exhaustive "
         "(default + every point of the +-1 endpoint neighbourhood)"},
        {"weights", OptionType::text, "1,1,1", {}, "per-channel error weights 'r,g,b' (non-negative, not all 0)"},
        {"solver", OptionType::choice, "builtin", {"builtin"}, "endpoint solver (builtin search pipeline)"},
    };
  }
  std::vector<std::string> modes() const override { return {"four_color", "three_color"}; }
  int block_bytes(const FormatOptions&) const override { return kBc1BlockBytes; }

  EncodedTexture encode(const Image& image, const FormatOptions& options,
                        const CodecContext& context) const override {
    validate_encoder_input(image, kName);
    ColorFitSettings settings;
    settings.search = parse_s3tc_search(option_text(options, "search"), kName);
    settings.allow_three_color = true;
    const std::array<float, 3> weights = parse_channel_weights(option_text(options, "weights"), kName);
    const BlockGrid grid(image.width, image.height);
    EncodedTexture texture;
    texture.format = kName;
    texture.options = options;
    texture.width = image.width;
    texture.height = image.height;
    texture.channels = image.channels;
    texture.block_bytes = kBc1BlockBytes;
    texture.blocks.resize(grid.block_count() * kBc1BlockBytes);
    texture.block_modes.resize(grid.block_count());
    std::uint8_t* blocks = texture.blocks.data();
    std::uint8_t* modes = texture.block_modes.data();
    parallel_for_index(grid.block_count(), context.threads, [&](std::size_t index) {
      const Bc1Params params = fit_color_block(make_color_block(load_block(image, grid, index), weights), settings);
      pack_bc1_block(params, blocks + index * kBc1BlockBytes);
      modes[index] = static_cast<std::uint8_t>(params.mode);   // 0 four_color, 1 three_color (modes() order)
    });
    return texture;
  }

  Image decode(const EncodedTexture& texture, const CodecContext& context) const override {
    validate_encoded_texture(*this, texture, kName);
    const BlockGrid grid(texture.width, texture.height);
    // Alpha is not stored: a 4-channel source decodes as RGB; 1- and 3-channel sources keep their count.
    Image image(texture.width, texture.height, texture.channels == 4 ? 3 : texture.channels);
    const std::uint8_t* blocks = texture.blocks.data();
    parallel_for_index(grid.block_count(), context.threads, [&](std::size_t index) {
      store_block(image, grid, index, decode_bc1_params(unpack_bc1_block(blocks + index * kBc1BlockBytes)));
    });
    return image;
  }
};

}  // namespace

const Format& bc1_format() {
  static const Bc1Format format;
  return format;
}

}  // namespace blocklab
