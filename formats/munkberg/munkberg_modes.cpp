// The `munkberg` mode table (formats/munkberg/munkberg_modes.h): adapters from each mode's own block model
// (munkberg_block.h: shape II / shape I; ext_s3tc_block.h; two_plane_block.h) to the common plug-in interface.
#include "formats/munkberg/munkberg_modes.h"

#include <algorithm>

#include "core/error.h"
#include "formats/munkberg/dct_encoder.h"
#include "formats/munkberg/ext_s3tc_encoder.h"
#include "formats/munkberg/two_plane_encoder.h"

namespace blocklab::munkberg {

namespace {

// ---- shape II / shape I (munkberg_block.h) --------------------------------------------------------------------
std::vector<int> shape_widths(Mode mode) {
  std::vector<int> w = {selector_bits(mode), kShapeIndexBits};
  for (int c = 0; c < kBaseCoordinateCount; ++c) w.push_back(kBaseCoordinateBits);
  for (int e = 0; e < kLumEndpointCount; ++e) w.push_back(kLumEndpointBits);
  for (int i = 0; i < kTexels; ++i) w.push_back(lum_index_stored_bits(mode, i));
  for (int g = 0; g < chroma_groups(mode); ++g) w.push_back(kChromaIndexBits);
  return w;
}
BlockTexels shape_decode(const std::uint8_t* bytes, const ModeContext& context) {
  return decode_params(unpack_block(bytes), context.shapes);
}
BlockTexels shape_reference(const std::uint8_t* bytes, const ModeContext& context) {
  return reference_decode_block(bytes, context.shapes);
}
void shape_repack(const std::uint8_t* in, std::uint8_t* out) { pack_block(unpack_block(in), out); }
template <Mode kMode>
double shape_encode(const BlockTexels& texels, const ModeContext& context, std::uint64_t seed, BlockScratch* scratch,
                    std::uint8_t* out) {
  const std::optional<LuminanceFit>& luminance = scratch->luminance[static_cast<std::size_t>(kMode)];
  double error = 0.0;
  const Params params = encode_mode(texels, scratch->analysis_of(texels), kMode, context.shapes, context.settings, seed,
                                    kMode == Mode::shape_i ? &scratch->shape_i_solves : nullptr,
                                    luminance ? &*luminance : nullptr, &error, scratch->workspace);
  pack_block(params, out);
  return error;   // block_log2_error of the decoded block
}

// ---- extended S3TC (ext_s3tc_block.h) -------------------------------------------------------------------------
std::vector<int> ext_s3tc_widths() {
  std::vector<int> w = {kExtS3tcSelectorBits};
  for (int e = 0; e < 2; ++e)
    for (const int bits : kExtS3tcChannelBits) w.push_back(bits);
  w.push_back(kExtS3tcAnchorIndexBits);
  for (int i = 1; i < kTexels; ++i) w.push_back(kExtS3tcIndexBits);
  return w;
}
BlockTexels ext_s3tc_decode(const std::uint8_t* bytes, const ModeContext& context) {
  return decode_ext_s3tc_params(unpack_ext_s3tc(bytes), context.ext_s3tc_space);
}
BlockTexels ext_s3tc_reference(const std::uint8_t* bytes, const ModeContext& context) {
  return reference_decode_ext_s3tc(bytes, context.ext_s3tc_space);
}
void ext_s3tc_repack(const std::uint8_t* in, std::uint8_t* out) { pack_ext_s3tc(unpack_ext_s3tc(in), out); }
double ext_s3tc_encode(const BlockTexels& texels, const ModeContext& context, std::uint64_t, BlockScratch*,
                       std::uint8_t* out) {
  ExtS3tcSettings settings = context.settings.ext_s3tc;
  settings.space = context.ext_s3tc_space;   // the texture's space (side data) is the one decoders use
  const ExtS3tcParams params = encode_ext_s3tc(texels, settings);
  pack_ext_s3tc(params, out);
  // The competition compares every mode by the same sum (block_log2_error's order of additions).
  return block_log2_error(texels, decode_ext_s3tc_params(params, settings.space));
}

// ---- two-plane luminance (two_plane_block.h) ------------------------------------------------------------------
std::vector<int> two_plane_widths() {
  std::vector<int> w = {kTwoPlaneSelectorBits};
  for (int p = 0; p < kPlaneCount; ++p) {
    w.push_back(kPlaneOffsetBits);
    w.push_back(kPlaneDeltaBits);
    w.push_back(kPlaneDeltaBits);
  }
  w.push_back(kPlaneMaskBits);
  w.push_back(kShapeIndexBits);
  for (int c = 0; c < kBaseCoordinateCount; ++c) w.push_back(kBaseCoordinateBits);
  for (int i = 0; i < kTexels; ++i) w.push_back(kChromaIndexBits);
  return w;
}
BlockTexels two_plane_decode(const std::uint8_t* bytes, const ModeContext& context) {
  return decode_two_plane_params(unpack_two_plane(bytes), context.shapes);
}
BlockTexels two_plane_reference(const std::uint8_t* bytes, const ModeContext& context) {
  return reference_decode_two_plane(bytes, context.shapes);
}
void two_plane_repack(const std::uint8_t* in, std::uint8_t* out) { pack_two_plane(unpack_two_plane(in), out); }
double two_plane_encode(const BlockTexels& texels, const ModeContext& context, std::uint64_t seed,
                        BlockScratch* scratch, std::uint8_t* out) {
  double error = 0.0;
  pack_two_plane(encode_two_plane(texels, context.shapes, context.settings, seed, &error, &scratch->shape_i_solves,
                                 scratch->workspace,
                                 scratch->two_plane_luminance ? &*scratch->two_plane_luminance : nullptr),
                 out);
  return error;
}

// ---- fixed-rate DCT (dct_block.h) ------------------------------------------------------------------------------
std::vector<int> dct_widths() {
  std::vector<int> w = {kDctSelectorBits};
  for (const DctChannelTable& table : default_dct_tables().channel)
    for (const int bits : table.bits)
      if (bits > 0) w.push_back(bits);
  return w;
}
BlockTexels dct_decode(const std::uint8_t* bytes, const ModeContext& context) {
  return decode_dct_params(unpack_dct(bytes, context.dct()), context.dct());
}
BlockTexels dct_reference(const std::uint8_t* bytes, const ModeContext& context) {
  return reference_decode_dct(bytes, context.dct());
}
void dct_repack(const std::uint8_t* in, std::uint8_t* out) {
  pack_dct(unpack_dct(in, default_dct_tables()), default_dct_tables(), out);
}
double dct_encode(const BlockTexels& texels, const ModeContext& context, std::uint64_t, BlockScratch*,
                  std::uint8_t* out) {
  double error = 0.0;
  pack_dct(encode_dct(texels, context.dct(), context.settings.dct_refine_passes, &error), context.dct(), out);
  return error;
}

}  // namespace

const std::array<BlockModeModel, kBlockModeCount>& block_mode_models() {
  static const std::array<BlockModeModel, kBlockModeCount> models = {{
      {BlockMode::shape_ii, "shape_ii",
       "section 5: shape II, one chroma index per 2x1 texel pair, 4-bit luminance indices",
       kShape2SelectorBits, kShape2Selector, [] { return shape_widths(Mode::shape_ii); },
       shape_decode, shape_reference, shape_repack, shape_encode<Mode::shape_ii>},
      {BlockMode::shape_i, "shape_i", "section 5: shape I, one chroma index per texel, 3-bit luminance indices",
       kShape1SelectorBits, kShape1Selector, [] { return shape_widths(Mode::shape_i); },
       shape_decode, shape_reference, shape_repack, shape_encode<Mode::shape_i>},
      {BlockMode::ext_s3tc, "ext_s3tc", "section 6.1: extended S3TC, a 32-entry line palette in RGB or logYuv",
       kExtS3tcSelectorBits, kExtS3tcSelector, ext_s3tc_widths, ext_s3tc_decode,
       ext_s3tc_reference, ext_s3tc_repack, ext_s3tc_encode},
      {BlockMode::two_plane, "two_plane", "section 6.3: two luminance planes, a texel mask and shape I chroma",
       kTwoPlaneSelectorBits, kTwoPlaneSelector, two_plane_widths,
       two_plane_decode, two_plane_reference, two_plane_repack, two_plane_encode},
      {BlockMode::dct, "dct", "section 6.2: fixed-rate DCT of logYuv (64 bits luminance, 32 per chroma channel)",
       kDctSelectorBits, kDctSelector, dct_widths, dct_decode, dct_reference, dct_repack,
       dct_encode},
  }};
  return models;
}

std::vector<ModeSpec> mode_table() {
  std::vector<ModeSpec> table;
  for (const BlockModeModel& m : block_mode_models()) table.push_back({m.name, m.description});
  return table;
}

const BlockModeModel& block_mode_model(BlockMode mode) {
  return block_mode_models()[static_cast<std::size_t>(mode)];
}

ModeMask parse_mode_list(const std::string& text) {
  if (text == "both") return kPaperModes;
  ModeMask mask{};
  if (text == "all") {
    mask.fill(true);
    return mask;
  }
  std::string valid = "both, all";
  for (const BlockModeModel& m : block_mode_models()) valid += std::string(", ") + m.name;
  std::size_t start = 0;
  bool any = false;
  while (start <= text.size()) {
    const std::size_t comma = std::min(text.find(',', start), text.size());
    std::string token = text.substr(start, comma - start);
    // Blanks around a token are not part of it ("shape_i, ext_s3tc").
    token.erase(0, token.find_first_not_of(' '));
    token.erase(token.find_last_not_of(' ') + 1);
    bool found = false;
    for (const BlockModeModel& m : block_mode_models())
      if (token == m.name) {
        mask[static_cast<std::size_t>(m.mode)] = true;
        found = true;
      }
    if (!found) fail("munkberg: modes", "unknown mode '" + token + "' in '" + text + "'; valid: " + valid);
    any = true;
    start = comma + 1;
  }
  if (!any) fail("munkberg: modes", "empty mode list; valid: " + valid);
  return mask;
}

BlockTexels decode_any_block(const std::uint8_t* bytes, const ModeContext& context) {
  return block_mode_model(block_mode_of(bytes)).decode(bytes, context);
}

BlockTexels reference_decode_any_block(const std::uint8_t* bytes, const ModeContext& context) {
  return block_mode_model(block_mode_of(bytes)).reference_decode(bytes, context);
}

namespace {

// The mode predictor's estimate of a section-6 mode's error (EncoderSettings::mode_predictor), or a negative value
// when it has none: the unrefined fit's error for ext_s3tc and dct (an upper bound of the refined one), two_plane's
// luminance bound plus shape I's chroma share when shape I was encoded.
double predicted_error(BlockMode mode, const BlockTexels& texels, const ModeContext& context,
                       const std::array<double, kBlockModeCount>& bound,
                       const std::array<double, kBlockModeCount>& encoded_error,
                       const std::array<bool, kBlockModeCount>& encoded) {
  switch (mode) {
    case BlockMode::ext_s3tc: {
      ExtS3tcSettings probe = context.settings.ext_s3tc;
      probe.space = context.ext_s3tc_space;
      probe.refine_passes = 0;
      double error = 0.0;
      encode_ext_s3tc(texels, probe, &error);
      return error;
    }
    case BlockMode::dct: {
      double error = 0.0;
      encode_dct(texels, context.dct(), 0, &error);
      return error;
    }
    case BlockMode::two_plane: {
      const std::size_t shape_i = static_cast<std::size_t>(BlockMode::shape_i);
      if (!encoded[shape_i]) return -1.0;
      const std::size_t two_plane = static_cast<std::size_t>(BlockMode::two_plane);
      return bound[two_plane] + std::max(0.0, encoded_error[shape_i] - bound[shape_i]);
    }
    default:
      return -1.0;
  }
}

}  // namespace

BlockMode encode_best_block(const BlockTexels& texels, const ModeContext& context, std::uint64_t block_seed,
                            std::uint8_t* out, double* error, ChromaWorkspace* workspace) {
  // Skip rule (EncoderSettings::skip_mode_bound): shape modes and two_plane get a lower bound of their error from
  // their luminance and the modes run in ascending bound order (stable: table order among equal bounds; modes
  // without a bound have 0 and run first); a mode whose bound shows it cannot win is not encoded. The winner is the
  // same as in table order: the lowest error, ties to the mode listed first. With the mode predictor the modes
  // without a bound (ext_s3tc, dct) run last instead, after the modes that usually win.
  std::array<double, kBlockModeCount> bound{};
  std::array<std::size_t, kBlockModeCount> order{};
  for (std::size_t m = 0; m < kBlockModeCount; ++m) order[m] = m;
  const ModeMask& enabled = context.settings.modes;
  const double predictor = context.settings.mode_predictor;
  BlockScratch scratch;
  scratch.workspace = workspace;
  if (context.settings.skip_mode_bound) {
    for (const Mode mode : {Mode::shape_ii, Mode::shape_i})
      if (enabled[static_cast<std::size_t>(mode)]) {
        LuminanceFit luminance;
        bound[static_cast<std::size_t>(mode)] =
            shape_mode_lower_bound(texels, scratch.analysis_of(texels), mode, context.settings, &luminance);
        scratch.luminance[static_cast<std::size_t>(mode)] = luminance;   // the mode's encode reuses it
      }
    // With the predictor, the section-6 modes run after the shape modes (two_plane, then ext_s3tc, dct).
    const auto section6_last = [&](std::size_t m) {
      return predictor > 0.0 && m >= static_cast<std::size_t>(BlockMode::ext_s3tc);
    };
    const auto rank = [](std::size_t m) {
      return m == static_cast<std::size_t>(BlockMode::two_plane) ? 0 : 1;
    };
    std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
      if (section6_last(a) != section6_last(b)) return section6_last(b);
      if (section6_last(a)) return rank(a) < rank(b);
      return bound[a] < bound[b];
    });
  }
  // two_plane's bound needs its luminance fit (16 partitions of planes), so it is computed when the mode is reached.
  const auto lazy_bound = [&](std::size_t m) {
    if (!context.settings.skip_mode_bound || m != static_cast<std::size_t>(BlockMode::two_plane)) return;
    const BlockAnalysis& analysis = scratch.analysis_of(texels);
    TwoPlaneParams planes;
    fit_two_plane_luminance(analysis.log_luminance.data(), &planes);
    bound[m] = two_plane_lower_bound(texels, analysis, planes);
    scratch.two_plane_luminance = planes;   // encode_two_plane reuses it
  };
  std::size_t best = 0;
  double best_error = 0.0;
  bool have = false;
  std::array<double, kBlockModeCount> encoded_error{};
  std::array<bool, kBlockModeCount> encoded{};
  std::uint8_t trial[kBlockBytes];
  for (const std::size_t m : order) {
    if (!enabled[m]) continue;
    // good_enough (approximate, off at 0): the block is already encoded well enough to stop searching.
    if (have && context.settings.good_enough > 0.0 && best_error <= context.settings.good_enough) break;
    if (have) lazy_bound(m);
    // error >= bound: it cannot be strictly lower than the best, nor equal to it and listed earlier.
    if (have && (bound[m] > best_error || (bound[m] == best_error && m > best))) continue;
    const BlockModeModel& model = block_mode_models()[m];
    // mode_predictor (approximate, off at 0): a mode whose estimate says it will not win is not encoded.
    if (have && predictor > 0.0) {
      const double estimate = predicted_error(model.mode, texels, context, bound, encoded_error, encoded);
      if (estimate >= 0.0 && predictor * estimate >= best_error) continue;
    }
    const double e = model.encode(texels, context, block_seed, &scratch, trial);
    encoded_error[m] = e;
    encoded[m] = true;
    // Lower error wins; ties keep the mode listed first. A NaN error never wins (finite input cannot produce one).
    if (!have || e < best_error || (e == best_error && m < best)) {
      best = m;
      best_error = e;
      have = true;
      std::copy(trial, trial + kBlockBytes, out);
    }
  }
  if (!have) fail("munkberg", "no mode enabled (option modes)");
  if (error != nullptr) *error = best_error;
  return block_mode_models()[best].mode;
}

}  // namespace blocklab::munkberg
