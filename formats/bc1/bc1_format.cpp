// The `bc1` Format (formats/bc1/bc1_format.h): each block is encoded by the S3TC colour encoder (or a solver of the
// library, option `solver`) and decoded with the reference decoding, through the shared parallel block loop of
// formats/common/block_codec.h.
#include "formats/bc1/bc1_format.h"

#include <string>

#include "core/error.h"
#include "formats/common/block_codec.h"
#include "formats/common/s3tc_solver_fit.h"
#include "formats/bc1/bc1_block.h"
#include "formats/bc1/bc1_problems.h"
#include "formats/common/s3tc_color_fit.h"

namespace blocklab {

namespace {

constexpr const char* kName = "bc1";

struct Bc1Options {
  S3tcSearch search = S3tcSearch::standard;
  std::string weights = "1,1,1";
};

const OptionTable<Bc1Options>& bc1_option_table() {
  static const auto table = OptionTable<Bc1Options>()
      .choice("search", &Bc1Options::search, s3tc_search_choices(),
              "endpoint search: fast (axis bounding box + least squares), default (cluster fit + polish), exhaustive "
              "(default + every point of the +-1 endpoint neighbourhood)")
      .text("weights", &Bc1Options::weights, "per-channel error weights 'r,g,b' (non-negative, not all 0)");
  return table;
}

class Bc1Format final : public Format {
 public:
  std::string name() const override { return kName; }
  std::string description() const override {
    return "BC1/DXT1 opaque RGB, 4 bpp, RGB565 endpoints, 4- and 3-colour modes (KDFS S3TC); cluster-fit encoder";
  }
  std::vector<OptionSpec> option_specs() const override {
    std::vector<OptionSpec> specs = bc1_option_table().specs();
    for (OptionSpec& spec : block_solver_option_specs("two RGB565 endpoints")) specs.push_back(std::move(spec));
    return specs;
  }
  std::vector<ModeSpec> mode_table() const override {
    return {{"four_color", "color0 > color1: four-colour palette"},
            {"three_color", "color0 <= color1: three colours and transparent black"}};
  }
  std::vector<BlockProblem> block_problems() const override { return bc1_block_problems(); }
  // The endpoint search effort; every other option keeps its default.
  std::vector<FormatPreset> presets() const override {
    return one_option_presets("search", "fast", "default", "exhaustive");
  }
  int block_bytes(const FormatOptions&) const override { return kBc1BlockBytes; }

  EncodedTexture encode(const Image& image, const FormatOptions& options,
                        const CodecContext& context) const override {
    validate_encoder_input(image, kName);
    const Bc1Options typed = bc1_option_table().from_resolved(options);
    ColorFitSettings settings;
    settings.search = typed.search;
    settings.allow_three_color = true;
    const std::array<float, 3> weights = parse_channel_weights(typed.weights, kName);
    const BlockSolverSetup solver = parse_block_solver(options, kName);
    return encode_blocks(*this, image, options, context, kBc1BlockBytes,
                         [&](const BlockTexels& texels, std::size_t index, std::uint8_t* out) {
                           const ColorBlock block = make_color_block(texels, weights);
                           const Bc1Params params = solver.builtin()
                                                        ? fit_color_block(block, settings)
                                                        : fit_color_block_with_solver(block, settings, solver, index);
                           pack_bc1_block(params, out);
                           return static_cast<int>(params.mode);   // 0 four_color, 1 three_color (modes() order)
                         });
  }

  // A standard texture: its own DDS file.
  bool has_gpu_textures() const override { return true; }
  std::vector<GpuTexture> gpu_textures(const EncodedTexture& texture) const override { return {{"", texture}}; }

  Image decode(const EncodedTexture& texture, const CodecContext& context) const override {
    // Alpha is not stored: a 4-channel source decodes as RGB; 1- and 3-channel sources keep their count.
    return decode_blocks(*this, texture, context, rgb_only_decoded_channels(texture.channels),
                         [](const std::uint8_t* bytes, std::size_t) { return decode_bc1_params(unpack_bc1_block(bytes)); });
  }
};

}  // namespace

const Format& bc1_format() {
  static const Bc1Format format;
  return format;
}

}  // namespace blocklab
