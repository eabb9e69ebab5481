// The `bc4` Format (formats/bc4/bc4_format.h): one channel per block, encoded in parallel over blocks (each block
// writes its own 8-byte slot, so the bytes do not depend on the thread count).
#include "formats/bc4/bc4_format.h"

#include <string>

#include "core/error.h"
#include "core/parallel.h"
#include "formats/bc4/bc4_block.h"
#include "formats/bc4/bc4_encoder.h"

namespace blocklab {

namespace {

constexpr const char* kName = "bc4";

int channel_index(const std::string& channel) {
  if (channel == "r") return 0;
  if (channel == "g") return 1;
  if (channel == "b") return 2;
  if (channel == "a") return 3;
  fail(kName, "option 'channel' must be one of r, g, b, a, got '" + channel + "'");
}

class Bc4Format final : public Format {
 public:
  std::string name() const override { return kName; }
  std::string description() const override {
    return "BC4/ATI1 unsigned single channel, 4 bpp, 8- and 6-value modes (KDFS RGTC)";
  }
  std::vector<OptionSpec> option_specs() const override {
    return {
        {"channel", OptionType::choice, "r", {"r", "g", "b", "a"}, "source channel stored in the block"},
        {"search", OptionType::choice, "default", {"fast", "default", "exhaustive"},
         "endpoint search: fast (min/max), default (least squares + +-2 box, both modes), exhaustive (all "
         "256x256 endpoint pairs)"},
        {"solver", OptionType::choice, "builtin", {"builtin"}, "endpoint solver (builtin search pipeline)"},
    };
  }
  std::vector<std::string> modes() const override { return {"eight_value", "six_value"}; }
  int block_bytes(const FormatOptions&) const override { return kBc4BlockBytes; }

  EncodedTexture encode(const Image& image, const FormatOptions& options,
                        const CodecContext& context) const override {
    validate_encoder_input(image, kName);
    const int channel = channel_index(option_text(options, "channel"));
    const S3tcSearch search = parse_s3tc_search(option_text(options, "search"), kName);
    const BlockGrid grid(image.width, image.height);
    EncodedTexture texture;
    texture.format = kName;
    texture.options = options;
    texture.width = image.width;
    texture.height = image.height;
    texture.channels = image.channels;
    texture.block_bytes = kBc4BlockBytes;
    texture.blocks.resize(grid.block_count() * kBc4BlockBytes);
    texture.block_modes.resize(grid.block_count());
    std::uint8_t* blocks = texture.blocks.data();
    std::uint8_t* modes = texture.block_modes.data();
    parallel_for_index(grid.block_count(), context.threads, [&](std::size_t index) {
      const BlockTexels texels = load_block(image, grid, index);
      float values[16];
      for (int texel = 0; texel < 16; ++texel) {
        const float value = texels.rgba[texel][channel];
        // Code values live in [0, 1]: above 1 clamps to 255, below 0 and NaN to 0.
        values[texel] = value >= 1.0f ? 255.0f : (value > 0.0f ? value * 255.0f : 0.0f);
      }
      const Bc4Params params = fit_bc4_block(values, search);
      pack_bc4_block(params, blocks + index * kBc4BlockBytes);
      modes[index] = static_cast<std::uint8_t>(params.mode);   // 0 eight_value, 1 six_value (modes() order)
    });
    return texture;
  }

  Image decode(const EncodedTexture& texture, const CodecContext& context) const override {
    validate_encoded_texture(*this, texture, kName);
    const BlockGrid grid(texture.width, texture.height);
    Image image(texture.width, texture.height, 1);   // one stored channel: grey, R = G = B
    const std::uint8_t* blocks = texture.blocks.data();
    parallel_for_index(grid.block_count(), context.threads, [&](std::size_t index) {
      const std::array<float, 16> values = decode_bc4_params(unpack_bc4_block(blocks + index * kBc4BlockBytes));
      BlockTexels texels;
      for (int texel = 0; texel < 16; ++texel) {
        texels.rgba[texel][0] = texels.rgba[texel][1] = texels.rgba[texel][2] = values[texel];
        texels.rgba[texel][3] = 1.0f;
      }
      store_block(image, grid, index, texels);
    });
    return image;
  }
};

}  // namespace

const Format& bc4_format() {
  static const Bc4Format format;
  return format;
}

}  // namespace blocklab
