// The per-block encoder of the `munkberg` format (Munkberg et al. 2008, sections 5, 6 and 7): the texels go to
// logYuv (eq. 2), each enabled mode (shape II, shape I) is fitted (luminance: munkberg_luminance.h; chroma:
// munkberg_chroma.h), and the mode with the smaller log2[RGB] error of its DECODED texels wins (section 6: "the one
// with the smallest error in the chosen metric (we use log[RGB] error) is selected"; ties keep shape II).
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>

#include "formats/munkberg/munkberg_color_spaces.h"
#include "core/blocks.h"
#include "formats/munkberg/munkberg_block.h"
#include "formats/munkberg/ext_s3tc_encoder.h"
#include "formats/munkberg/munkberg_chroma.h"
#include "formats/munkberg/munkberg_luminance.h"
#include "metrics/zero_rule.h"

namespace blocklab::munkberg {

// The modes the encoder lets compete, indexed by BlockMode (munkberg_layout.h). EncoderSettings' default is the
// paper's format, shape II + shape I; the format option `modes` sets the mask (every preset but `paper`: all five,
// the rejected modes of section 6, ext_s3tc, two_plane and dct, included).
using ModeMask = std::array<bool, kBlockModeCount>;
constexpr ModeMask kPaperModes = {true, true, false, false, false};

// How the final chroma index of each texel / pair is chosen once the shape and base colours are fixed:
//   fit      the nearest landmark in the shape-fit error (linear or stretched), as in the fit itself;
//   log2rgb  the landmark whose DECODED texels (with the block's decoded luminance) have the smallest log2[RGB]
//            error (eq. 1), the metric the encoder selects modes by.
enum class IndexMetric { fit, log2rgb };

struct EncoderSettings {
  ChromaSettings chroma;
  int luma_radius = 2;          // endpoint neighbourhood (section 7.3); 0 = plain min/max
  ModeMask modes = kPaperModes;
  ExtS3tcSettings ext_s3tc;
  IndexMetric index_metric = IndexMetric::log2rgb;
  // The polish error's weights (option `error`, munkberg_log_error.h; log2_floor: the unweighted eq. 1).
  HdrBlockError error = HdrBlockError::log2_floor;
  // DCT mode (dct_encoder.h): coordinate-descent passes over its codes in the log2[RGB] error (0 = nearest codes).
  int dct_refine_passes = 2;
  // Skip rule (option skip_mode_bound): a shape mode is not encoded when shape_mode_lower_bound shows it cannot beat
  // the best mode encoded so far (the competition then tries modes in ascending order of their bound). Exact: the
  // same winner as without the rule.
  bool skip_mode_bound = true;
  // Skip rule (option good_enough; approximate, off at 0): once the best mode so far has a block error
  // (block_log2_error: squared log2[RGB] differences summed over 16 texels x 3 channels) of at most good_enough, the
  // remaining modes are not tried, as astcenc stops its search at a quality limit. 0.1 is an RMS log2 error of 0.046
  // per channel, about a third of a typical image's.
  double good_enough = 0.0;
  // Mode predictor (option mode_predictor; approximate, off at 0): before a section-6 mode is encoded in full, its
  // cheap estimate is compared with the best error so far and the mode is skipped when factor x estimate >= that
  // error. Estimates: ext_s3tc and dct, the error of their unrefined fit (0 descent passes: an upper bound of the
  // refined error); two_plane, its luminance lower bound plus shape I's chroma share (shape I's error minus its
  // luminance bound) when shape I was encoded. 1 skips every mode whose estimate is no better than the best; smaller
  // factors encode more (factor -> 0: the full competition).
  double mode_predictor = 0.0;
};

// Floor of the log2[RGB] metric (metrics/zero_rule.h): every channel value counts as max(value, 2^-24).
constexpr double kMetricValueFloor = kLogDomainDefaultFloor;
static_assert(kMetricValueFloor == 0x1p-24 && kBlackLog2 == -24.0, "the metric's floor and its log2");
// One channel value in the metric: log2 max(value, 2^-24).
inline double metric_log2(double value) { return std::log2(std::max(value, kMetricValueFloor)); }
// metric_log2 of every texel and channel (R, G, B) of a block: the source side of block_log2_error, computed once per
// block by the searches that measure many trial blocks against it.
using TexelLog2 = std::array<std::array<double, 3>, kTexels>;
TexelLog2 texel_log2(const BlockTexels& texels);

// Sum over texels and R, G, B of (log2 max(decoded, 2^-24) - log2 max(source, 2^-24))^2: the per-block part of the
// log2[RGB] metric (eq. 1, metrics/zero_rule.h floor). The second form takes the source side already computed
// (texel_log2); both give the same value bit for bit.
double block_log2_error(const BlockTexels& source, const BlockTexels& decoded);
double block_log2_error(const TexelLog2& source_log2, const BlockTexels& decoded);

// Splits a block into the luminance targets (log2, clamped to [kBlackLog2, kLogLumMax]; true black -> kBlackLog2)
// and the chroma points (u, v; weight 0 for true black).
void block_targets(const BlockTexels& texels, double log_luminance[kTexels], ChromaPoints* chroma);

// What both shape modes' bounds and encodes need from a block's source texels, computed once per block (they used to
// be recomputed by each of them: ~300 libm log2 calls per block, 2026-11-26).
struct BlockAnalysis {
  TexelLog2 source_log2{};                              // texel_log2
  std::array<double, kTexels> log_luminance{};          // block_targets' luminance targets
  ChromaPoints chroma;                                  // block_targets' chroma points
  std::array<double, kTexels> source_log_luminance{};   // rgb_to_logyuv(texel).log_luminance, not clamped
};
BlockAnalysis analyse_block(const BlockTexels& texels);

// Re-chooses params->chroma_index by the log2[RGB] error of the decoded texels (IndexMetric::log2rgb): per chroma
// group the landmark whose decoded texels have the smallest error (ties: the lower landmark). Returns the block's
// error with the chosen indices, block_log2_error(source_log2, decode_params(*params, shapes)) bit for bit (each texel
// is decoded on each landmark once, with decode_block's arithmetic).
double assign_chroma_indices_log2(const TexelLog2& source_log2, const ShapeSet& shapes, Params* params);
inline void assign_chroma_indices_log2(const BlockTexels& texels, const ShapeSet& shapes, Params* params) {
  assign_chroma_indices_log2(texel_log2(texels), shapes, params);
}

// What the chroma polish needs for the log2[RGB] error of `mode` with the luminance `luminance`: the decoded log2
// luminance per texel (true black per eq. 3) and the source channels' log2 (metric floor 2^-24).
ChromaLogTargets chroma_log_targets(const TexelLog2& source_log2, Mode mode, const LuminanceFit& luminance);
inline ChromaLogTargets chroma_log_targets(const BlockTexels& texels, Mode mode, const LuminanceFit& luminance) {
  return chroma_log_targets(texel_log2(texels), mode, luminance);
}

// The per-texel terms of the luminance lower bounds below, for any mode whose texels decode as
// RGB = (v, max(0, 1 - u - v), u) Y / w with Y = 2^decoded_log2[i] (or true black where black[i]): texel_bound[i]
// bounds texel i's part of block_log2_error whatever the chroma (the argument of shape_mode_lower_bound).
void luminance_texel_bounds(const BlockTexels& texels, const BlockAnalysis& analysis, const bool black[kTexels],
                            const double decoded_log2[kTexels], double texel_bound[kTexels]);

// A lower bound of block_log2_error for shape mode `mode` (shape_ii / shape_i) whatever its chroma, from the
// luminance encode_mode chooses (fit_luminance). Per texel: decoded true black (eq. 3) gives its exact error
// sum_c (-24 - s_c)^2; a texel whose source channels are all above the metric floor 2^-24 and whose decoded log2
// luminance differs from the source's by delta gives (|delta| - 1e-6)^2 when delta > 0 (sum_c w_c decoded_c =
// Y_dec max(1, u + v) >= Y_dec while sum_c w_c source_c = Y_src, so some channel's decoded / source ratio is
// >= 2^delta) and min(delta^2, min_c (24 + s_c)^2) when delta < 0 (with u + v <= 1 some channel's ratio is
// <= 2^delta unless that channel is floored; with u + v > 1 green decodes to 0); other texels give 0. Per chroma
// group of several non-black texels (shape II's pairs share one landmark): per channel the minimum over a shared
// log2 factor of the group's error, if the sum over channels is larger than the texels' terms. 1e-6 covers the
// float rounding of decoded channels and of exp2; the sum is scaled by (1 - 1e-9) so that rounding in the order of
// additions cannot lift it above the true error.
// `luminance` (optional) receives the luminance fit, which encode_mode can reuse.
double shape_mode_lower_bound(const BlockTexels& texels, const BlockAnalysis& analysis, Mode mode,
                              const EncoderSettings& settings, LuminanceFit* luminance = nullptr);
inline double shape_mode_lower_bound(const BlockTexels& texels, Mode mode, const EncoderSettings& settings,
                                     LuminanceFit* luminance = nullptr) {
  return shape_mode_lower_bound(texels, analyse_block(texels), mode, settings, luminance);
}

// Fits one mode (no choice between modes).
// `cache` (optional): fit_chroma's shared shape solves (munkberg_chroma.h). `luminance` (optional): the block's
// fit_luminance result for this mode and settings.luma_radius, already computed (shape_mode_lower_bound's).
// `block_error` (optional) receives block_log2_error of the decoded result. `workspace` (optional): the worker's
// chroma search buffers (munkberg_chroma.h).
Params encode_mode(const BlockTexels& texels, const BlockAnalysis& analysis, Mode mode, const ShapeSet& shapes,
                   const EncoderSettings& settings, std::uint64_t block_seed, ShapeSolveCache* cache = nullptr,
                   const LuminanceFit* luminance = nullptr, double* block_error = nullptr,
                   ChromaWorkspace* workspace = nullptr);
inline Params encode_mode(const BlockTexels& texels, Mode mode, const ShapeSet& shapes, const EncoderSettings& settings,
                          std::uint64_t block_seed, ShapeSolveCache* cache = nullptr,
                          const LuminanceFit* luminance = nullptr) {
  return encode_mode(texels, analyse_block(texels), mode, shapes, settings, block_seed, cache, luminance);
}

// Encodes one block in the shape modes only: every enabled shape mode (settings.modes[0], [1]; both when neither is
// enabled), the lower log2[RGB] error wins. `error` (optional) receives that error. The competition with the
// rejected modes is encode_best_block (munkberg_modes.h).
Params encode_block(const BlockTexels& texels, const ShapeSet& shapes, const EncoderSettings& settings,
                    std::uint64_t block_seed, double* error = nullptr);

}  // namespace blocklab::munkberg
