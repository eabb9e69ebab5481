// The `bc3` Format (formats/bc3/bc3_format.h): colour and alpha encoded independently per block, in parallel over
// blocks (each block writes its own 16-byte slot, so the bytes do not depend on the thread count).
#include "formats/bc3/bc3_format.h"

#include <string>

#include "core/error.h"
#include "formats/common/block_codec.h"
#include "formats/common/s3tc_solver_fit.h"
#include "formats/bc3/bc3_block.h"
#include "formats/bc3/bc3_problems.h"
#include "formats/bc4/bc4_encoder.h"
#include "formats/common/s3tc_color_fit.h"

namespace blocklab {

namespace {

constexpr const char* kName = "bc3";

struct Bc3Options {
  S3tcSearch search = S3tcSearch::standard;
  std::string weights = "1,1,1";
};

const OptionTable<Bc3Options>& bc3_option_table() {
  static const auto table = OptionTable<Bc3Options>()
      .choice("search", &Bc3Options::search, s3tc_search_choices(),
              "endpoint search for colour and alpha: fast, default (cluster fit + polish), exhaustive")
      .text("weights", &Bc3Options::weights, "per-channel colour error weights 'r,g,b' (non-negative, not all 0)");
  return table;
}

class Bc3Format final : public Format {
 public:
  std::string name() const override { return kName; }
  std::string description() const override {
    return "BC3/DXT5 RGBA, 8 bpp: 4-colour BC1 colour block + 8-bit interpolated alpha block (KDFS S3TC)";
  }
  std::vector<OptionSpec> option_specs() const override {
    std::vector<OptionSpec> specs = bc3_option_table().specs();
    for (OptionSpec& spec : block_solver_option_specs("colour and alpha endpoints")) specs.push_back(std::move(spec));
    return specs;
  }
  // The colour half is always 4-colour; the modes are those of the alpha half.
  std::vector<ModeSpec> mode_table() const override {
    return {{"eight_alpha", "alpha0 > alpha1: eight interpolated alpha values"},
            {"six_alpha", "alpha0 <= alpha1: six interpolated alpha values plus 0 and 1"}};
  }
  std::vector<BlockProblem> block_problems() const override { return bc3_block_problems(); }
  // The endpoint search effort; every other option keeps its default.
  std::vector<FormatPreset> presets() const override {
    return one_option_presets("search", "fast", "default", "exhaustive");
  }
  int block_bytes(const FormatOptions&) const override { return kBc3BlockBytes; }

  EncodedTexture encode(const Image& image, const FormatOptions& options,
                        const CodecContext& context) const override {
    validate_encoder_input(image, kName);
    const Bc3Options typed = bc3_option_table().from_resolved(options);
    ColorFitSettings settings;
    settings.search = typed.search;
    settings.allow_three_color = false;   // BC3 colour is always decoded with 4 colours (SPECS.md 2.5 item 2)
    const std::array<float, 3> weights = parse_channel_weights(typed.weights, kName);
    const BlockSolverSetup solver = parse_block_solver(options, kName);
    return encode_blocks(*this, image, options, context, kBc3BlockBytes,
                         [&](const BlockTexels& texels, std::size_t index, std::uint8_t* out) {
                           const ColorBlock block = make_color_block(texels, weights);
                           float alpha[16];
                           for (int texel = 0; texel < 16; ++texel) alpha[texel] = to_alpha_code(texels.rgba[texel][3]);
                           Bc3Params params;
                           if (solver.builtin()) {
                             params.color = fit_color_block(block, settings);
                             params.alpha = fit_bc4_block(alpha, settings.search);
                           } else {
                             params.color = fit_color_block_with_solver(block, settings, solver, index);
                             params.alpha = fit_bc4_block_with_solver(alpha, solver, index);
                           }
                           pack_bc3_block(params, out);
                           return static_cast<int>(params.alpha.mode);   // 0 eight_alpha, 1 six_alpha
                         });
  }

  // A standard texture: its own DDS file.
  bool has_gpu_textures() const override { return true; }
  std::vector<GpuTexture> gpu_textures(const EncodedTexture& texture) const override { return {{"", texture}}; }

  Image decode(const EncodedTexture& texture, const CodecContext& context) const override {
    const bool keep_alpha = texture.channels == 4;   // alpha kept only for 4-channel sources
    return decode_blocks(*this, texture, context, texture.channels,
                         [keep_alpha](const std::uint8_t* bytes, std::size_t) {
                           BlockTexels texels = decode_bc3_params(unpack_bc3_block(bytes));
                           // A source without alpha stored alpha = 1 (255): report the image as it came, alpha 1.
                           if (!keep_alpha)
                             for (auto& texel : texels.rgba) texel[3] = 1.0f;
                           return texels;
                         });
  }

 private:
  // [0, 1] alpha -> 8-bit code units: above 1 clamps to 255, below 0 and NaN to 0.
  static float to_alpha_code(float value) { return value >= 1.0f ? 255.0f : (value > 0.0f ? value * 255.0f : 0.0f); }
};

}  // namespace

const Format& bc3_format() {
  static const Bc3Format format;
  return format;
}

}  // namespace blocklab
