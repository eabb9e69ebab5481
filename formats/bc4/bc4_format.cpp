// The `bc4` Format (formats/bc4/bc4_format.h): one channel per block, encoded in parallel over blocks (each block
// writes its own 8-byte slot, so the bytes do not depend on the thread count).
#include "formats/bc4/bc4_format.h"

#include <string>

#include "core/error.h"
#include "formats/common/block_codec.h"
#include "formats/common/s3tc_solver_fit.h"
#include "formats/bc4/bc4_block.h"
#include "formats/bc4/bc4_encoder.h"
#include "formats/bc4/bc4_problems.h"

namespace blocklab {

namespace {

constexpr const char* kName = "bc4";

struct Bc4Options {
  int channel = 0;   // r, g, b, a
  S3tcSearch search = S3tcSearch::standard;
};

const OptionTable<Bc4Options>& bc4_option_table() {
  static const auto table = OptionTable<Bc4Options>()
      .choice("channel", &Bc4Options::channel, {{"r", 0}, {"g", 1}, {"b", 2}, {"a", 3}},
              "source channel stored in the block")
      .choice("search", &Bc4Options::search, s3tc_search_choices(),
              "endpoint search: fast (min/max), default (least squares + +-2 box, both modes), exhaustive (all "
              "256x256 endpoint pairs)");
  return table;
}

class Bc4Format final : public Format {
 public:
  std::string name() const override { return kName; }
  std::string description() const override {
    return "BC4/ATI1 unsigned single channel, 4 bpp, 8- and 6-value modes (KDFS RGTC)";
  }
  std::vector<OptionSpec> option_specs() const override {
    std::vector<OptionSpec> specs = bc4_option_table().specs();
    for (OptionSpec& spec : block_solver_option_specs("two 8-bit endpoints")) specs.push_back(std::move(spec));
    return specs;
  }
  std::vector<ModeSpec> mode_table() const override {
    return {{"eight_value", "red0 > red1: eight interpolated values"},
            {"six_value", "red0 <= red1: six interpolated values plus 0 and 1"}};
  }
  std::vector<BlockProblem> block_problems() const override { return bc4_block_problems(); }
  // The endpoint search effort; every other option keeps its default.
  std::vector<FormatPreset> presets() const override {
    return one_option_presets("search", "fast", "default", "exhaustive");
  }
  int block_bytes(const FormatOptions&) const override { return kBc4BlockBytes; }

  EncodedTexture encode(const Image& image, const FormatOptions& options,
                        const CodecContext& context) const override {
    validate_encoder_input(image, kName);
    const Bc4Options typed = bc4_option_table().from_resolved(options);
    const int channel = typed.channel;
    const S3tcSearch search = typed.search;
    const BlockSolverSetup solver = parse_block_solver(options, kName);
    return encode_blocks(*this, image, options, context, kBc4BlockBytes,
                         [&](const BlockTexels& texels, std::size_t index, std::uint8_t* out) {
                           float values[16];
                           for (int texel = 0; texel < 16; ++texel) {
                             const float value = texels.rgba[texel][channel];
                             // Code values live in [0, 1]: above 1 clamps to 255, below 0 and NaN to 0.
                             values[texel] = value >= 1.0f ? 255.0f : (value > 0.0f ? value * 255.0f : 0.0f);
                           }
                           const Bc4Params params = solver.builtin() ? fit_bc4_block(values, search)
                                                                     : fit_bc4_block_with_solver(values, solver, index);
                           pack_bc4_block(params, out);
                           return static_cast<int>(params.mode);   // 0 eight_value, 1 six_value (modes() order)
                         });
  }

  // A standard texture: its own DDS file.
  bool has_gpu_textures() const override { return true; }
  std::vector<GpuTexture> gpu_textures(const EncodedTexture& texture) const override { return {{"", texture}}; }

  Image decode(const EncodedTexture& texture, const CodecContext& context) const override {
    // One stored channel: grey, R = G = B.
    return decode_blocks(*this, texture, context, 1, [](const std::uint8_t* bytes, std::size_t) {
      const std::array<float, 16> values = decode_bc4_params(unpack_bc4_block(bytes));
      BlockTexels texels;
      for (int texel = 0; texel < 16; ++texel) {
        texels.rgba[texel][0] = texels.rgba[texel][1] = texels.rgba[texel][2] = values[texel];
        texels.rgba[texel][3] = 1.0f;
      }
      return texels;
    });
  }
};

}  // namespace

const Format& bc4_format() {
  static const Bc4Format format;
  return format;
}

}  // namespace blocklab
