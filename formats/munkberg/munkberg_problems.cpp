// The `munkberg` block problems: the 2D chroma shape fit of Munkberg et al. 2008 section 7.1 (formats/munkberg/shape_fit/shape_fit_problem.h)
// on an HDR block.
//   shape_i, shape_ii   exactly what the encoder hands the solver (munkberg_chroma.h chroma_fit_data with the
//                       default settings): the stretched error of section 7.2 (alpha = 0.455), the 7-bit base-colour
//                       lattice, one of the 8 template shapes of the built-in set (drawn from the block's seed),
//                       per-texel points (shape I) or the weighted means of the 2x1 pairs (shape II);
//   shape_ii_log2, shape_i_log2
//                       the log2[RGB] chroma error the encoder's polish searches (munkberg_log_error.h
//                       make_chroma_log_problem): the block's luminance fitted as the encoder does (fit_luminance with
//                       the default radius), the decoded texels' log2[RGB] error against the source over the 7-bit
//                       base-colour lattice, each chroma group on its best landmark; template drawn from the seed;
//   kite_linear, kite_stretched
//                       the section 7.1 fit in its plain form: points = the chroma (u, v) of eq. 2 (rgb_to_logyuv,
//                       clamped to [0, 1]) of every texel, weight 0 for black texels (no chroma) and 1 otherwise, an
//                       8-bit lattice per base coordinate, the "kite" template (0,0), (1,0), (0.6,0.5), (0.2,-0.4)
//                       (no symmetry, so no correspondence is free), with the linear error (eq. 11) or the
//                       stretched one (section 7.2).
#include "formats/munkberg/munkberg_problems.h"

#include <algorithm>
#include <memory>

#include "formats/munkberg/munkberg_color_spaces.h"
#include "formats/munkberg/shape_fit/shape_fit_problem.h"
#include "formats/munkberg/munkberg_chroma.h"
#include "formats/munkberg/munkberg_encoder.h"
#include "formats/munkberg/munkberg_log_error.h"
#include "formats/munkberg/munkberg_luminance.h"
#include "formats/munkberg/munkberg_shapes.h"
#include "solvers/seeding.h"

namespace blocklab {

namespace {

std::unique_ptr<Problem> make_encoder_shape_fit(munkberg::Mode mode, const BlockTexels& block, std::uint64_t seed) {
  double log_luminance[munkberg::kTexels];
  munkberg::ChromaPoints points;
  munkberg::block_targets(block, log_luminance, &points);
  const munkberg::ChromaSettings settings;   // the format's defaults: stretched error, alpha 0.455
  const auto shape_index = static_cast<std::size_t>(RandomStream(seed).uniform_index(munkberg::kShapeCount));
  const ShapeTemplate& shape = munkberg::default_shape_set().shapes[shape_index];
  return std::make_unique<ShapeFitProblem>(munkberg::chroma_fit_data(points, mode, shape, settings, nullptr));
}

std::unique_ptr<Problem> make_chroma_log2_fit(munkberg::Mode mode, const BlockTexels& block, std::uint64_t seed) {
  const munkberg::BlockAnalysis analysis = munkberg::analyse_block(block);
  const munkberg::EncoderSettings settings;   // the format's defaults
  const munkberg::LuminanceFit luminance =
      munkberg::fit_luminance(mode, analysis.log_luminance.data(), settings.luma_radius);
  const auto shape_index = static_cast<std::size_t>(RandomStream(seed).uniform_index(munkberg::kShapeCount));
  return std::make_unique<ErrorProblem<munkberg::ChromaLogError>>(munkberg::make_chroma_log_problem(
      mode, munkberg::default_shape_set().shapes[shape_index],
      munkberg::chroma_log_targets(analysis.source_log2, mode, luminance)));
}

std::unique_ptr<Problem> make_kite_shape_fit(ShapeErrorKind kind, const BlockTexels& block) {
  ShapeFitData data;
  data.shape = ShapeTemplate::from_landmarks({Point2{0, 0}, Point2{1, 0}, Point2{0.6, 0.5}, Point2{0.2, -0.4}});
  data.error_kind = kind;
  for (int t = 0; t < kBlockTexels; ++t) {
    const Rgb<double> rgb{block.rgba[t][0], block.rgba[t][1], block.rgba[t][2]};
    const LogYuv<double> yuv = rgb_to_logyuv(rgb);
    // u, v are in [0, 1] for non-negative RGB; the clamp removes rounding overshoot.
    data.points.push_back({std::clamp(yuv.u, 0.0, 1.0), std::clamp(yuv.v, 0.0, 1.0)});
    // A black texel has no chroma (eq. 2 would divide 0 by 0): weight 0, as the munkberg encoder does.
    data.weights.push_back(rgb.r == 0.0 && rgb.g == 0.0 && rgb.b == 0.0 ? 0.0 : 1.0);
  }
  return std::make_unique<ShapeFitProblem>(std::move(data));
}

}  // namespace

std::vector<BlockProblem> munkberg_block_problems() {
  return {
      {"shape_ii", "section 7: shape II chroma fit as the encoder poses it (4 base coordinates, 7-bit lattice, "
                   "stretched error, template drawn per block)",
       BlockImageKind::hdr,
       [](const BlockTexels& block, std::uint64_t seed) {
         return make_encoder_shape_fit(munkberg::Mode::shape_ii, block, seed);
       }},
      {"shape_i", "section 7: shape I chroma fit as the encoder poses it (4 base coordinates, 7-bit lattice, "
                  "stretched error, template drawn per block)",
       BlockImageKind::hdr,
       [](const BlockTexels& block, std::uint64_t seed) {
         return make_encoder_shape_fit(munkberg::Mode::shape_i, block, seed);
       }},
      {"shape_ii_log2", "section 7: shape II base colours (7-bit lattice) in the log2[RGB] error of the decoded block, "
                        "luminance fixed, template drawn per block",
       BlockImageKind::hdr,
       [](const BlockTexels& block, std::uint64_t seed) {
         return make_chroma_log2_fit(munkberg::Mode::shape_ii, block, seed);
       }},
      {"shape_i_log2", "section 7: shape I base colours (7-bit lattice) in the log2[RGB] error of the decoded block, "
                       "luminance fixed, template drawn per block",
       BlockImageKind::hdr,
       [](const BlockTexels& block, std::uint64_t seed) {
         return make_chroma_log2_fit(munkberg::Mode::shape_i, block, seed);
       }},
      {"kite_linear", "section 7.1 eq. 11: linear shape-fit error of the texels' chroma to the kite template, 8-bit "
                      "lattice",
       BlockImageKind::hdr,
       [](const BlockTexels& block, std::uint64_t) { return make_kite_shape_fit(ShapeErrorKind::linear, block); }},
      {"kite_stretched", "section 7.2: stretched shape-fit error of the texels' chroma to the kite template, 8-bit "
                         "lattice",
       BlockImageKind::hdr,
       [](const BlockTexels& block, std::uint64_t) { return make_kite_shape_fit(ShapeErrorKind::stretched, block); }},
  };
}

}  // namespace blocklab
