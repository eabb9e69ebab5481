// The `wang` Format (formats/wang/wang_format.h): per texture the zone splits, per block (in parallel, each block
// writing its own 32 bytes) the chroma and luminance blocks, then the residual zones from every texel's decoded
// luminance and the residual blocks.
#include "formats/wang/wang_format.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <string>
#include <vector>

#include "core/error.h"
#include "core/parallel.h"
#include "formats/common/block_codec.h"
#include "formats/common/s3tc_color_fit.h"
#include "formats/wang/wang_block.h"
#include "formats/wang/wang_dds.h"
#include "formats/wang/wang_joint_codes.h"
#include "formats/wang/wang_luminance_codec.h"
#include "formats/wang/wang_problems.h"
#include "formats/wang/wang_residual_codec.h"
#include "formats/wang/wang_side_data.h"
#include "formats/wang/wang_zone_split.h"

namespace blocklab {

namespace {

constexpr const char* kName = "wang";
constexpr std::array<float, 3> kUnitWeights = {1.0f, 1.0f, 1.0f};

// The format's own options (the common preset / seed and the block solver options are appended by the registry and
// block_solver_option_specs).
struct WangOptions {
  wang::ColorSpace space = wang::ColorSpace::luvw;
  wang::Residual residual = wang::Residual::s;
  wang::LuminanceSplit l_bits = wang::LuminanceSplit::two_zones;
  wang::Codec codec = wang::Codec::one_d;
  std::string effort = "medium";
  std::string t1_solver = "linear";
  std::string s_solver = "linear";
  std::string zone_solver_options;
  bool joint_codes = true;
  double error_c = 1.0 / 16384.0;
};

const OptionTable<WangOptions>& wang_option_table() {
  using O = WangOptions;
  static const auto table =
      OptionTable<O>()
          .choice("space", &O::space, {{"luvw", wang::ColorSpace::luvw}, {"luv", wang::ColorSpace::luv}},
                  "colour space: luvw (eq. 1) or luv (eq. 10)")
          .choice("residual", &O::residual,
                  {{"s", wang::Residual::s}, {"ratio", wang::Residual::ratio}, {"none", wang::Residual::none}},
                  "luminance residual in tex1.rgb: s (eq. 5), ratio (T = S / L', eq. 11) or none")
          .choice("l_bits", &O::l_bits,
                  {{"2x6", wang::LuminanceSplit::two_zones}, {"1x12", wang::LuminanceSplit::one_range}},
                  "luminance quantisation: two uniform zones (eq. 3) or one 12-bit range split over the alphas")
          .choice("codec", &O::codec, {{"1d", wang::Codec::one_d}, {"bc3", wang::Codec::bc3}},
                  "1d: section 3.5 codec in the log domain; bc3: the plain BC3 encoder on the eq. 3 / 6 targets")
          .choice("effort", &O::effort, wang::preset_names(),
                  "search effort of the 1D codec and colour fits (set by the presets; formats/wang/wang_presets.h)")
          .text("t1_solver", &O::t1_solver,
                "t1 of eq. 3: linear (eq. 2 linear search) or a solver on the zone quantisation error")
          .text("s_solver", &O::s_solver, "(s1, s2) of eq. 6: linear (eq. 2 analogue) or a solver of the library")
          .text("zone_solver_options", &O::zone_solver_options,
                "options of the zone solvers as 'key=value, key=value'")
          .boolean("joint_codes", &O::joint_codes,
                   "1d codec with a residual: each texel re-picks its three codes together once every endpoint is "
                   "fixed")
          .real("error_c", &O::error_c, 1e-30, 1e30, "c of the log-domain error |L - L'| / (L + c) (eq. 9)");
  return table;
}

// The typed options of a resolved map; a texture whose options were not resolved (e.g. built in memory) is an
// Error naming the format and the option, never a silent default.
WangOptions typed_options(const FormatOptions& options) {
  try {
    return wang_option_table().from_resolved(options);
  } catch (const Error& e) {
    fail(kName, e.what());
  }
}

wang::SplitSearch split_search(const FormatOptions& options, const WangOptions& typed, const std::string& key) {
  wang::SplitSearch search;
  search.solver = key == "t1_solver" ? typed.t1_solver : typed.s_solver;
  wang::check_split_solver_name(search.solver, key, kName);
  search.options = parse_solver_option_list(typed.zone_solver_options, "zone_solver_options", kName);
  search.seed = static_cast<std::uint64_t>(option_int(options, "seed"));
  return search;
}

// Block modes: which eq. 3 zones a block's luminances occupy (1x12 blocks count as both).
enum class ZoneUse : std::uint8_t { low_zone = 0, high_zone = 1, both_zones = 2 };

class WangFormat final : public Format {
 public:
  std::string name() const override { return kName; }
  std::string description() const override {
    return "Wang et al. 2007 LUVW in two DXT5 textures, 16 bpp: luminance in two alpha zones (eq. 3), residual in "
           "three colour zones (eq. 6), 1D log-domain codec (section 3.5), section 3.4 shader decode";
  }
  std::vector<OptionSpec> option_specs() const override {
    std::vector<OptionSpec> specs = wang_option_table().specs();
    for (OptionSpec& spec : block_solver_option_specs("1D codec's alpha and residual endpoints"))
      specs.push_back(std::move(spec));
    return specs;
  }
  std::vector<ModeSpec> mode_table() const override {
    return {{"low_zone", "every texel's luminance in the low zone [tmin, t1] (eq. 3)"},
            {"high_zone", "every texel's luminance in the high zone [t1, tmax]"},
            {"both_zones", "texels in both zones, or the one-range 1x12 split"}};
  }
  std::vector<BlockProblem> block_problems() const override { return wang_block_problems(); }
  // The presets set the search effort of the 1D codec and the colour fits; the zone splits are the same at each.
  std::vector<FormatPreset> presets() const override {
    return one_option_presets("effort", "fast", "medium", "thorough");
  }
  int block_bytes(const FormatOptions&) const override { return wang::kBlockBytes; }
  // Revision 3: the 1D codec's start is the 8-value BC4 fit alone. Revision 2: the residual and joint code searches
  // measure the clamped decode (ResidualBlockError::texel_error); preset medium makes 2 coordinate-descent passes.
  // The decoder and the bit layout are revision 1's (CHANGELOG.md).
  int revision() const override { return 3; }
  int decoder_revision() const override { return 1; }

  EncodedTexture encode(const Image& image, const FormatOptions& options, const CodecContext& context) const override {
    validate_encoder_input(image, kName);
    const WangOptions settings = typed_options(options);
    const wang::SearchEffort effort = wang::preset_effort(settings.effort, kName);
    const wang::Codec codec = settings.codec;
    const double c = settings.error_c;
    const wang::SplitSearch t1_search = split_search(options, settings, "t1_solver");
    const wang::SplitSearch s_search = split_search(options, settings, "s_solver");
    const BlockSolverSetup solver = parse_block_solver(options, kName);
    const bool joint_codes = codec == wang::Codec::one_d && settings.joint_codes;

    // Section 3.1: L of every texel; section 3.2: the zones.
    const std::size_t texel_count = image.texel_count();
    std::vector<double> luminances(texel_count), weights(texel_count);
    for (std::size_t i = 0; i < texel_count; ++i) {
      luminances[i] = wang::to_luminance_chroma(settings.space, &image.pixels[i * 4]).luminance;
      weights[i] = 1.0 / (luminances[i] + c);
    }
    wang::SideData side;
    side.has_split_records = true;
    wang::Zones& zones = side.zones;
    zones.tmin = *std::min_element(luminances.begin(), luminances.end());
    zones.tmax = *std::max_element(luminances.begin(), luminances.end());
    zones.t1 = zones.tmin;
    // The side data holds at most 1e30 (wang_side_data.h), so the float shader constants and their sums stay finite.
    if (!(zones.tmax <= 1e30))
      fail(kName, "the largest luminance " + std::to_string(zones.tmax) + " exceeds the format's range (1e30)");
    if (settings.l_bits == wang::LuminanceSplit::two_zones) {
      const wang::SplitResult split = wang::fit_luminance_split(luminances, weights, t1_search);
      zones.t1 = std::clamp(split.split[0], zones.tmin, zones.tmax);
      side.luminance_split_eq2 = split.eq2;
      side.luminance_split_quantisation = split.quantisation;
    }
    const wang::ShaderConstants luminance_constants =
        wang::shader_constants(zones, settings.l_bits, wang::Residual::none);
    wang::LuminanceBlockError luminance_template;
    luminance_template.high = luminance_constants.l_high;
    luminance_template.low = luminance_constants.l_low;
    luminance_template.tmin = luminance_constants.tmin;

    // Pass 1: tex0 (chroma + tex0.a) and tex1.a; every texel's L, weight and decoded eq. 4 luminance L_a.
    const BlockGrid grid(image.width, image.height);
    std::vector<double> block_l(grid.block_count() * kBlockTexels), block_w(block_l.size()), block_la(block_l.size());
    std::vector<std::uint8_t> inside(block_l.size());
    ColorFitSettings color_settings;
    color_settings.search = effort.s3tc;
    color_settings.allow_three_color = false;
    EncodedTexture texture = encode_blocks(
        *this, image, options, context, wang::kBlockBytes,
        [&](const BlockTexels& texels, std::size_t index, std::uint8_t* out) {
          BlockTexels chroma{};
          wang::LuminanceBlockError error = luminance_template;
          for (int texel = 0; texel < kBlockTexels; ++texel) {
            const wang::LuminanceChroma lc = wang::to_luminance_chroma(settings.space, texels.rgba[texel]);
            for (int channel = 0; channel < 3; ++channel)
              chroma.rgba[texel][channel] = static_cast<float>(lc.chroma[channel]);
            error.luminance[texel] = lc.luminance;
            error.weight[texel] = 1.0 / (lc.luminance + c);
          }
          wang::BlockParams params;
          params.tex0.color = fit_color_block(make_color_block(chroma, kUnitWeights), color_settings);
          const wang::LuminanceFit fit =
              wang::fit_luminance_block(error, zones, settings.l_bits, effort, codec, solver, index);
          params.tex0.alpha = fit.tex0;
          params.tex1.alpha = fit.tex1;
          params.tex1.color = Bc1Params{};   // the residual pass overwrites it
          wang::pack_block(params, out);
          double decoded[16];
          wang::decoded_luminance(error, fit.tex0, fit.tex1, decoded);
          const std::size_t bx = index % static_cast<std::size_t>(grid.blocks_x);
          const std::size_t by = index / static_cast<std::size_t>(grid.blocks_x);
          bool low = false, high = false;
          for (int texel = 0; texel < kBlockTexels; ++texel) {
            const std::size_t slot = index * kBlockTexels + static_cast<std::size_t>(texel);
            block_l[slot] = error.luminance[texel];
            block_w[slot] = error.weight[texel];
            block_la[slot] = decoded[texel];
            const std::size_t x = bx * 4 + static_cast<std::size_t>(texel % 4);
            const std::size_t y = by * 4 + static_cast<std::size_t>(texel / 4);
            inside[slot] = x < static_cast<std::size_t>(image.width) && y < static_cast<std::size_t>(image.height);
            (error.luminance[texel] <= zones.t1 ? low : high) = true;
          }
          if (settings.l_bits == wang::LuminanceSplit::one_range || (low && high))
            return static_cast<int>(ZoneUse::both_zones);
          return static_cast<int>(low ? ZoneUse::low_zone : ZoneUse::high_zone);
        });
    texture.channels = image.channels;

    if (settings.residual != wang::Residual::none) {
      // Section 3.3: S = L - L' (or T = S / L') of every texel inside the image, its zones, then the tex1.rgb blocks.
      const bool ratio = settings.residual == wang::Residual::ratio;
      std::vector<double> residuals, residual_weights;
      for (std::size_t slot = 0; slot < block_l.size(); ++slot) {
        if (!inside[slot]) continue;
        const double s = block_l[slot] - block_la[slot];
        // T = S / L' is unbounded where L' is tiny; the side data's range bound (1e30) caps it.
        residuals.push_back(std::clamp(ratio ? (block_la[slot] > 0.0 ? s / block_la[slot] : 0.0) : s, -1e30, 1e30));
        residual_weights.push_back(ratio ? block_w[slot] * std::max(block_la[slot], 0.0) : block_w[slot]);
      }
      const wang::SplitResult split = wang::fit_residual_split(residuals, residual_weights, s_search);
      zones.smin = split.low;
      zones.smax = split.high;
      zones.s1 = std::clamp(split.split[0], zones.smin, zones.smax);
      zones.s2 = std::clamp(split.split[1], zones.s1, zones.smax);
      side.residual_split_eq2 = split.eq2;
      side.residual_split_quantisation = split.quantisation;
      const wang::ShaderConstants constants = wang::shader_constants(zones, settings.l_bits, settings.residual);
      wang::ResidualBlockError residual_template;
      for (int channel = 0; channel < 3; ++channel) residual_template.ranges[channel] = constants.r_ranges[channel];
      residual_template.rmin = constants.rmin;
      residual_template.ratio = ratio;
      residual_template.c = c;
      const wang::ResidualTable table = wang::build_residual_table(residual_template);
      std::uint8_t* blocks = texture.blocks.data();
      parallel_for_index(grid.block_count(), context.threads, [&](std::size_t index) {
        wang::ResidualBlockError error = residual_template;
        for (int texel = 0; texel < kBlockTexels; ++texel) {
          const std::size_t slot = index * kBlockTexels + static_cast<std::size_t>(texel);
          error.luminance[texel] = block_l[slot];
          error.decoded[texel] = block_la[slot];
          error.weight[texel] = block_w[slot];
        }
        const wang::ResidualFit fit = wang::fit_residual_block(error, table, zones, effort, codec, solver, index);
        std::uint8_t* out = blocks + index * wang::kBlockBytes;
        if (!joint_codes) {
          pack_bc1_color_bits(fit.color, out + kBc3BlockBytes + kBc4BlockBytes);
          return;
        }
        wang::BlockParams params = wang::unpack_block(out);
        params.tex1.color = fit.color;
        wang::LuminanceBlockError luminance = luminance_template;
        luminance.luminance = error.luminance;
        luminance.weight = error.weight;
        wang::choose_codes_jointly(luminance, error, params);
        wang::pack_block(params, out);
      });
    }
    wang::store_side_data(side, settings.l_bits, settings.residual, texture);
    return texture;
  }

  // Section 3.3: tex0 (UVW + the first luminance zone) and tex1 (residual + the second zone), two DXT5 textures.
  bool has_gpu_textures() const override { return true; }
  std::vector<GpuTexture> gpu_textures(const EncodedTexture& texture) const override {
    validate_encoded_texture(*this, texture, kName);
    std::array<EncodedTexture, 2> pair = wang::split_into_dxt5_textures(texture);
    return {{"tex0", std::move(pair[0])}, {"tex1", std::move(pair[1])}};
  }

  Image decode(const EncodedTexture& texture, const CodecContext& context) const override {
    validate_encoded_texture(*this, texture, kName);
    const wang::DecodeSetup setup = wang::decode_setup(texture);
    return decode_blocks(*this, texture, context, rgb_only_decoded_channels(texture.channels),
                         [&](const std::uint8_t* bytes, std::size_t) {
                           return wang::decode_block_bytes(setup, bytes);
                         });
  }
};

}  // namespace

const Format& wang_format() {
  static const WangFormat format;
  return format;
}

namespace wang {

DecodeSetup decode_setup(const EncodedTexture& texture) {
  const WangOptions settings = typed_options(texture.options);
  const SideData side = read_side_data(texture, settings.l_bits, settings.residual, kName);
  DecodeSetup setup;
  setup.constants = shader_constants(side.zones, settings.l_bits, settings.residual);
  setup.space = settings.space;
  setup.residual = settings.residual;
  return setup;
}

}  // namespace wang

}  // namespace blocklab
