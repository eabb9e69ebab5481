// The `banterle` Format (formats/banterle/banterle_format.h): encode = estimate + fit (alpha, Lwhite), tone map,
// S3TC-encode (and at 8 bpp the residual pass); decode = S3TC decode + Listing 1 through the half-float LUT.
#include "formats/banterle/banterle_format.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "core/error.h"
#include "core/parallel.h"
#include "formats/banterle/banterle_problems.h"
#include "formats/banterle/banterle_side_data.h"
#include "formats/banterle/itmo_lut.h"
#include "formats/banterle/log_domain_refine.h"
#include "formats/banterle/luminance_residual.h"
#include "formats/banterle/reinhard_operator.h"
#include "formats/banterle/tmo_fit_problem.h"
#include "formats/bc1/bc1_block.h"
#include "formats/bc3/bc3_block.h"
#include "formats/common/block_codec.h"
#include "formats/common/s3tc_color_fit.h"

namespace blocklab {

namespace {

constexpr const char* kName = "banterle";
constexpr std::array<float, 3> kUnitWeights = {1.0f, 1.0f, 1.0f};

struct BanterleOptions {
  std::string bpp = "4";
  std::string mean = "geometric";
  std::string fit = "ceres_lm";
  std::string fit_options;
  S3tcSearch search = S3tcSearch::standard;
};

const OptionTable<BanterleOptions>& banterle_option_table() {
  using O = BanterleOptions;
  static const auto table = OptionTable<O>()
      .choice("bpp", &O::bpp, {"4", "8"}, "4: BC1 tone-mapped texture; 8: BC3 with the eq. 4 residual in alpha")
      .choice("mean", &O::mean, {"geometric", "harmonic"}, "L_H of eq. 1 (SPECS.md section 3)")
      .choice("fit", &O::fit, tmo_fit_method_names(),
              "eq. 3 parameter fit: none (Reinhard 2002 estimate), coeff_search, nlopt, ceres_lm (surrogate LM + "
              "polish), ceres_lm_raw (LM on the quantised objective)")
      .text("fit_options", &O::fit_options,
            "options of the fit's solver as 'key=value, key=value' (nlopt: algorithm, max_evaluations, ...; ceres_lm: "
            "its LM stage; see `blocklab list`), overriding the method's defaults")
      .choice("search", &O::search, s3tc_search_choices(), "S3TC endpoint search");
  return table;
}

bool residual_enabled(const FormatOptions& options) { return banterle_option_table().from_resolved(options).bpp == "8"; }

TmoFitSettings fit_settings(const FormatOptions& options) {
  const BanterleOptions typed = banterle_option_table().from_resolved(options);
  TmoFitSettings settings;
  settings.method = parse_tmo_fit_method(typed.fit, kName);
  settings.solver_options = parse_tmo_fit_options(typed.fit_options, kName);
  // Unknown keys or bad values fail here, before any work, naming the format, the solver and the key.
  resolve_tmo_fit_options(settings.method, settings.solver_options, kName);
  settings.seed = static_cast<std::uint64_t>(option_int(options, "seed"));
  return settings;
}

class BanterleFormat final : public Format {
 public:
  std::string name() const override { return kName; }
  // 2: 8 bpp residual with an exactly-zero zero code and the black-texel block candidate (luminance_residual.h);
  //    the 4 bpp bytes are unchanged, but the revision is per format. Options fit_algorithm / fit_evaluations
  //    became fit_options (same defaults, same bytes).
  int revision() const override { return 2; }
  std::string description() const override {
    return "Banterle et al. 2008 inverse tone mapping: Reinhard TMO (fitted alpha, Lwhite) + BC1 (4 bpp) or BC3 with "
           "luminance residual (8 bpp), half-float inverse LUT decode";
  }
  std::vector<ModeSpec> mode_table() const override {
    return {{"four_color", "BC1 colour half, four-colour palette (4 bpp)"},
            {"three_color", "BC1 colour half, three colours and black (4 bpp)"},
            {"eight_alpha", "8 bpp: BC3 block, luminance residual in eight-value alpha"},
            {"six_alpha", "8 bpp: BC3 block, luminance residual in six values plus 0 and 1"}};
  }
  std::vector<BlockProblem> block_problems() const override { return banterle_block_problems(); }
  std::vector<OptionSpec> option_specs() const override { return banterle_option_table().specs(); }
  // The endpoint search effort; every other option keeps its default.
  std::vector<FormatPreset> presets() const override {
    return one_option_presets("search", "fast", "default", "exhaustive");
  }
  int block_bytes(const FormatOptions& options) const override {
    return residual_enabled(options) ? kBc3BlockBytes : kBc1BlockBytes;
  }

  EncodedTexture encode(const Image& image, const FormatOptions& options, const CodecContext& context) const override {
    validate_encoder_input(image, kName);
    const bool residual = residual_enabled(options);
    const S3tcSearch search = banterle_option_table().from_resolved(options).search;

    // Section 3.1: Reinhard 2002 estimate, then the eq. 3 fit on the luminance histogram.
    const TmoFitResult fit = banterle_fit_tmo(image, options);
    BanterleSideData side;
    side.alpha = fit.fitted.alpha;
    side.l_white = fit.fitted.l_white;
    side.mean = fit.fitted.mean;
    side.has_residual = residual;
    const ItmoLut lut = build_itmo_lut(side.alpha, side.l_white, side.mean, kName);

    const Image ldr = banterle_tone_map(image, fit.fitted);
    ColorFitSettings color_settings;
    color_settings.search = search;
    color_settings.allow_three_color = !residual;   // BC3's colour half is always 4-colour (SPECS.md 2.5 item 2)

    const BlockGrid grid(image.width, image.height);
    if (!residual) {
      EncodedTexture texture = encode_blocks(*this, ldr, options, context, kBc1BlockBytes,
                                             [&](const BlockTexels& texels, std::size_t index, std::uint8_t* out) {
                                               Bc1Params params =
                                                   fit_color_block(make_color_block(texels, kUnitWeights), color_settings);
                                               refine_color_block_log_domain(load_block(image, grid, index), lut, false,
                                                                             params);
                                               pack_bc1_block(params, out);
                                               return static_cast<int>(params.mode);
                                             });
      texture.channels = image.channels;
      store_banterle_side_data(side, texture);
      return texture;
    }

    // 8 bpp, pass 1: colour halves, and per texel (block order) the original luminance and the decoder's
    // reconstruction without residual.
    std::vector<float> original(grid.block_count() * kBlockTexels), reconstructed(original.size());
    EncodedTexture texture = encode_blocks(
        *this, ldr, options, context, kBc3BlockBytes, [&](const BlockTexels& texels, std::size_t index, std::uint8_t* out) {
          const BlockTexels source = load_block(image, grid, index);
          Bc1Params color = fit_color_block(make_color_block(texels, kUnitWeights), color_settings);
          refine_color_block_log_domain(source, lut, true, color);
          pack_bc1_color_bits(color, out + kBc4BlockBytes);
          const BlockTexels decoded = decode_bc1_params(color);
          for (int texel = 0; texel < kBlockTexels; ++texel) {
            const std::size_t slot = index * kBlockTexels + static_cast<std::size_t>(texel);
            original[slot] = banterle_luminance(source.rgba[texel]);
            reconstructed[slot] = itmo_lookup(lut, banterle_luminance(decoded.rgba[texel]));
          }
          return 0;
        });
    texture.channels = image.channels;
    side.residual = fit_residual_range(original, reconstructed);
    // Pass 2: the alpha halves (each block writes its own 8 bytes and mode slot).
    std::uint8_t* blocks = texture.blocks.data();
    std::uint8_t* modes = texture.block_modes.data();
    parallel_for_index(grid.block_count(), context.threads, [&](std::size_t index) {
      const std::size_t first = index * kBlockTexels;
      const Bc4Params alpha =
          encode_residual_block(&original[first], &reconstructed[first], side.residual, search);
      pack_bc4_block(alpha, blocks + index * kBc3BlockBytes, kName);
      modes[index] = static_cast<std::uint8_t>(2 + static_cast<int>(alpha.mode));
    });
    store_banterle_side_data(side, texture);
    return texture;
  }

  Image decode(const EncodedTexture& texture, const CodecContext& context) const override {
    validate_encoded_texture(*this, texture, kName);
    const bool residual = residual_enabled(texture.options);
    const BanterleSideData side = read_banterle_side_data(texture, residual, kName);
    const ItmoLut lut = build_itmo_lut(side.alpha, side.l_white, side.mean, kName);
    return decode_blocks(*this, texture, context, rgb_only_decoded_channels(texture.channels),
                         [&](const std::uint8_t* bytes, std::size_t) {
                           BlockTexels texels = residual ? decode_bc3_params(unpack_bc3_block(bytes))
                                                         : decode_bc1_params(unpack_bc1_block(bytes));
                           for (auto& texel : texels.rgba) {
                             const float delta = residual ? dequantise_residual(side.residual, texel[3]) : 0.0f;
                             const float ldr[3] = {texel[0], texel[1], texel[2]};
                             itmo_decode_texel(lut, ldr, delta, texel);
                             texel[3] = 1.0f;
                           }
                           return texels;
                         });
  }
};

}  // namespace

Image banterle_tone_map(const Image& image, const ReinhardParameters& parameters) {
  Image ldr(image.width, image.height, 3);
  const double scale = parameters.alpha / parameters.mean;
  for (std::size_t i = 0; i < image.texel_count(); ++i) {
    const float* rgb = &image.pixels[i * 4];
    const double luminance = static_cast<double>(banterle_luminance(rgb));
    float* out = &ldr.pixels[i * 4];
    // L <= 0 (black, or negative channels summing to <= 0): the texel maps to black, as f(0) = 0.
    if (!(luminance > 0.0)) {
      out[0] = out[1] = out[2] = 0.0f;
      continue;
    }
    const double ratio = reinhard_forward_scaled(scale * luminance, parameters.l_white) / luminance;
    for (int channel = 0; channel < 3; ++channel) out[channel] = static_cast<float>(rgb[channel] * ratio);
  }
  return ldr;
}

TmoFitResult banterle_fit_tmo(const Image& image, const FormatOptions& options) {
  const TmoMean mean = parse_tmo_mean(banterle_option_table().from_resolved(options).mean, kName);
  const std::vector<double> luminances = banterle_luminances(image);
  const ReinhardParameters estimate = estimate_reinhard_parameters(luminances, mean);
  return fit_tmo_parameters(build_luminance_histogram(luminances), estimate, fit_settings(options));
}

const Format& banterle_format() {
  static const BanterleFormat format;
  return format;
}

}  // namespace blocklab
