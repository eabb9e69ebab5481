// `munkberg` encoder search shortcuts (formats/munkberg): the fast log2[RGB] polishes (full neighbourhood and
// coordinate descent) give lattice_polish's answers bit for bit and eval_below equals the error below its bound; the skip rules are exact (skip_constant and
// skip_mode_bound on or off give the same bytes, on the samples and on blocks built to trigger them) and the mode
// lower bound never exceeds a mode's error; the global chroma search stays within a few percent of the per-shape
// search on the Desk sample; polish_margin only skips shapes far behind the first; the candidate evaluation's bound at
// the polish_candidates best shapes and the fused log2[RGB] index assignment change nothing.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <random>

#include "core/image_io.h"
#include "core/number_text.h"
#include "core/input_policy.h"
#include "formats/munkberg/munkberg_base_colour_sums.h"
#include "formats/munkberg/munkberg_encoder.h"
#include "formats/munkberg/munkberg_format.h"
#include "formats/munkberg/munkberg_log_error.h"
#include "formats/munkberg/munkberg_luminance.h"
#include "formats/registry.h"
#include "metrics/metric.h"
#include "solvers/lattice_polish/lattice_polish_solver.h"
#include "solvers/procrustes/procrustes_solver.h"

namespace blocklab::munkberg {
namespace {

const Format& format() { return find_format("munkberg"); }
FormatOptions options(const FormatOptions& given = {}) { return resolve_format_options(format(), given); }

Image sample(const std::string& name) {
  Image image = read_image(std::string(BLOCKLAB_TEST_SAMPLES) + "/hdr/" + name);
  apply_input_policy(image, InputPolicy::clamp, name);
  return image;
}

BlockTexels block_at(const Image& image, int bx, int by) {
  BlockTexels t;
  for (int i = 0; i < kTexels; ++i) {
    const float* texel = image.texel(std::min(image.width - 1, 4 * bx + i % 4), std::min(image.height - 1, 4 * by + i / 4));
    for (int c = 0; c < 4; ++c) t.rgba[i][c] = texel[c];
  }
  return t;
}

// The luminance targets of encode_mode for a block (decoded luminance + source log2 channels).
ChromaLogTargets log_targets_of(const BlockTexels& texels, Mode mode) {
  double log_luminance[kTexels];
  ChromaPoints chroma;
  block_targets(texels, log_luminance, &chroma);
  return chroma_log_targets(texels, mode, fit_luminance(mode, log_luminance, 2));
}

TEST(MunkbergSearch, FastLogPolishGivesLatticePolishsAnswerBitForBit) {
  const Image image = sample("Desk.exr");
  const ShapeSet shapes = default_shape_set();
  std::mt19937 random(7);
  std::uniform_int_distribution<int> code(0, kBaseCoordinateMax);
  const SolverOptions polish = resolve_solver_options(lattice_polish_solver(), {{"radius", "1"}});
  int moved = 0;
  for (int trial = 0; trial < 60; ++trial) {
    const BlockTexels texels = block_at(image, (trial * 7) % (image.width / 4), (trial * 5) % (image.height / 4));
    const Mode mode = trial % 2 == 0 ? Mode::shape_i : Mode::shape_ii;
    const ShapeTemplate& shape = shapes.shapes[static_cast<std::size_t>(trial % kShapeCount)];
    const ErrorProblem<ChromaLogError> problem = make_chroma_log_problem(mode, shape, log_targets_of(texels, mode));
    const std::array<int, kBaseCoordinateCount> start = {code(random), code(random), code(random), code(random)};
    const double start_x[4] = {problem.lattice(0).point(start[0]), problem.lattice(1).point(start[1]),
                               problem.lattice(2).point(start[2]), problem.lattice(3).point(start[3])};
    const SolveResult reference = lattice_polish_solver().solve(problem, polish, start_x, 0);
    std::array<int, kBaseCoordinateCount> codes = start;
    double error = problem.eval(start_x);
    const bool improved = polish_log_error_full(problem.error(), 16, &codes, &error);
    for (int p = 0; p < kBaseCoordinateCount; ++p)
      EXPECT_EQ(codes[static_cast<std::size_t>(p)], reference.lattice_indices[static_cast<std::size_t>(p)]) << trial;
    EXPECT_EQ(error, reference.summary.final_error) << trial;
    moved += improved ? 1 : 0;
  }
  EXPECT_GT(moved, 30);   // random starts are almost always improved: the comparison covers real searches
}

TEST(MunkbergSearch, FastCoordinatePolishGivesLatticePolishsCoordinateDescentBitForBit) {
  // polish_search=coordinate (full_neighbourhood_limit 1) and radii above 1 run lattice_polish's coordinate descent;
  // polish_log_error_coordinate must find its codes and error, with one pass or many.
  const Image image = sample("Desk.exr");
  const ShapeSet shapes = default_shape_set();
  std::mt19937 random(17);
  std::uniform_int_distribution<int> code(0, kBaseCoordinateMax);
  int moved = 0, edge = 0;
  for (int trial = 0; trial < 60; ++trial) {
    const int radius = 1 + trial % 3, passes = trial % 4 == 0 ? 1 : 16;
    const SolverOptions polish = resolve_solver_options(
        lattice_polish_solver(), {{"radius", std::to_string(radius)}, {"max_passes", std::to_string(passes)},
                                  {"full_neighbourhood_limit", "1"}});
    const BlockTexels texels = block_at(image, (trial * 11) % (image.width / 4), (trial * 3) % (image.height / 4));
    const Mode mode = trial % 2 == 0 ? Mode::shape_ii : Mode::shape_i;
    const ShapeTemplate& shape = shapes.shapes[static_cast<std::size_t>((trial / 2) % kShapeCount)];
    const ErrorProblem<ChromaLogError> problem = make_chroma_log_problem(mode, shape, log_targets_of(texels, mode));
    std::array<int, kBaseCoordinateCount> start = {code(random), code(random), code(random), code(random)};
    if (trial % 5 == 0) start[static_cast<std::size_t>(trial % 4)] = trial % 10 == 0 ? 0 : kBaseCoordinateMax;
    edge += trial % 5 == 0 ? 1 : 0;   // starts on a lattice end (clipped offsets)
    const double start_x[4] = {problem.lattice(0).point(start[0]), problem.lattice(1).point(start[1]),
                               problem.lattice(2).point(start[2]), problem.lattice(3).point(start[3])};
    const SolveResult reference = lattice_polish_solver().solve(problem, polish, start_x, 0);
    std::array<int, kBaseCoordinateCount> codes = start;
    double error = problem.eval(start_x);
    const bool improved = polish_log_error_coordinate(problem.error(), radius, passes, &codes, &error);
    for (int p = 0; p < kBaseCoordinateCount; ++p)
      EXPECT_EQ(codes[static_cast<std::size_t>(p)], reference.lattice_indices[static_cast<std::size_t>(p)]) << trial;
    EXPECT_EQ(error, reference.summary.final_error) << trial;
    moved += improved ? 1 : 0;
  }
  EXPECT_GT(moved, 30);   // random starts are almost always improved: the comparison covers real searches
  EXPECT_EQ(edge, 12);
}

TEST(MunkbergSearch, EvalBelowIsTheErrorBelowTheBoundAndAtLeastTheBoundAbove) {
  const Image image = sample("hdr-rgb-arboretum.hdr");
  const ShapeSet shapes = default_shape_set();
  std::mt19937 random(3);
  std::uniform_real_distribution<double> value(0.0, 1.0);
  for (int trial = 0; trial < 200; ++trial) {
    const BlockTexels texels = block_at(image, trial % 64, (trial / 64) * 9 % 64);
    const ChromaLogError error =
        ChromaLogError::make(Mode::shape_ii, shapes.shapes[static_cast<std::size_t>(trial % 8)],
                             log_targets_of(texels, Mode::shape_ii));
    const double x[4] = {value(random), value(random), value(random), value(random)};
    const double exact = error(x);
    EXPECT_EQ(error.eval_below(x, std::numeric_limits<double>::infinity()), exact);
    EXPECT_EQ(error.eval_below(x, exact * 1.5 + 1.0), exact);
    EXPECT_GE(error.eval_below(x, exact * 0.5), exact * 0.5);
  }
}

TEST(MunkbergSearch, EvalWithCachedBaseColourSumsEqualsEvalBelowBitForBit) {
  // The global search's and the polish's evaluation: landmarks 0 and 1's group sums from a cache shared by all shapes
  // of a block and mode, only landmarks 2 and 3 per call. Random lattice points (so landmark 1 is sometimes a rounded
  // B0 + (B1 - B0)), their radius-1 neighbours (cache hits), more code pairs than the table holds (its crowded
  // path), and bounds below, at and above the error. Every third block has four texels set to true black, which
  // decode black and are left out of the sums (masked lanes in the paired group sums). One cache serves every block,
  // emptied between them as the global search's per-thread table is.
  const Image image = sample("hdr-rgb-arboretum.hdr");
  const ShapeSet shapes = default_shape_set();
  std::mt19937 random(11);
  std::uniform_int_distribution<int> code(0, kBaseCoordinateMax), step(-1, 1), shape(0, kShapeCount - 1);
  int blocks_with_black_texels = 0;
  BaseColourSums cache;
  for (int trial = 0; trial < 18; ++trial) {
    BlockTexels texels = block_at(image, trial * 5 % 64, (trial / 4) * 9 % 64);
    if (trial % 3 == 2)
      for (const int i : {0, 5, 6, 15})
        for (int c = 0; c < 3; ++c) texels.rgba[i][c] = 0.0f;
    const Mode mode = trial % 2 == 0 ? Mode::shape_i : Mode::shape_ii;
    const ChromaLogTargets targets = log_targets_of(texels, mode);
    if (std::count(targets.black.begin(), targets.black.end(), true) > 0) ++blocks_with_black_texels;
    cache.clear();
    std::array<int, kBaseCoordinateCount> codes{};
    for (int point = 0; point < 600; ++point) {
      if (point % 4 == 0) {
        codes = {code(random), code(random), code(random), code(random)};
      } else {
        for (int& c : codes) c = std::min(kBaseCoordinateMax, std::max(0, c + step(random)));
      }
      const ChromaLogError error = ChromaLogError::make(mode, shapes.shapes[static_cast<std::size_t>(shape(random))], targets);
      const double exact = error(base_code_point(codes).data());
      for (const double bound : {std::numeric_limits<double>::infinity(), exact * 1.5 + 1.0, exact, exact * 0.5}) {
        const double cached = eval_below_cached(error, codes, bound, &cache);
        if (exact < bound) {
          EXPECT_EQ(cached, exact) << trial << " " << point;
        } else {
          EXPECT_GE(cached, bound) << trial << " " << point;
        }
      }
    }
  }
  EXPECT_EQ(blocks_with_black_texels, 6);
}

TEST(MunkbergSearch, ModeLowerBoundNeverExceedsTheModesErrorOnTheSamples) {
  EncoderSettings settings;
  settings.chroma.solver = &procrustes_solver();
  settings.chroma.polish_options = {{"radius", "1"}};
  const ShapeSet shapes = default_shape_set();
  int positive = 0, blocks = 0;
  for (const std::string name : {"Desk.exr", "blender_world_sunset.exr"}) {
    const Image image = sample(name);
    for (int by = 0; by < image.height / 4; by += 3)
      for (int bx = 0; bx < image.width / 4; bx += 3) {
        const BlockTexels texels = block_at(image, bx, by);
        for (const Mode mode : {Mode::shape_ii, Mode::shape_i}) {
          const double bound = shape_mode_lower_bound(texels, mode, settings);
          const double error = block_log2_error(texels, decode_params(encode_mode(texels, mode, shapes, settings, 1), shapes));
          EXPECT_LE(bound, error) << name << " block " << bx << "," << by;
          positive += bound > 0.0 ? 1 : 0;
          ++blocks;
        }
      }
  }
  EXPECT_GT(positive, blocks / 2);   // the bound is informative on most blocks, not a trivial 0
}

TEST(MunkbergSearch, ModeLowerBoundCountsDecodedBlackAndLuminanceRatiosExactly) {
  // Texel 0 true black, the others a grey ramp over 20 stops: shape I's 8 levels cannot follow it.
  BlockTexels texels;
  for (int i = 0; i < kTexels; ++i) {
    const float v = i == 0 ? 0.0f : std::exp2(-10.0f + 20.0f * static_cast<float>(i) / 15.0f);
    for (int c = 0; c < 3; ++c) texels.rgba[i][c] = v;
    texels.rgba[i][3] = 1.0f;
  }
  EncoderSettings settings;
  const double bound_i = shape_mode_lower_bound(texels, Mode::shape_i, settings);
  const double bound_ii = shape_mode_lower_bound(texels, Mode::shape_ii, settings);
  // Shape I's 3-bit levels are twice as coarse: its luminance bound is larger.
  EXPECT_GT(bound_i, bound_ii);
  EXPECT_GT(bound_ii, 0.0);
}

TEST(MunkbergSearch, TopShapeBoundGivesTheSameParamsForEveryPolishCandidateCount) {
  // The candidate evaluation stops at the error that could bring a shape into the polish_candidates best: the same
  // encoded parameters as with each shape's own bound only, on a sample with black, grey and saturated blocks, with
  // the fast option set's budgets (fewer candidates, so shapes are decided by fewer evaluations) and the default's.
  const Image image = sample("Desk.exr");
  const ShapeSet shapes = default_shape_set();
  int blocks = 0, differing_polish_counts = 0;
  for (const int search_candidates : {32, 64})
    for (const int polish_candidates : {1, 2, 3}) {
      EncoderSettings settings;
      settings.chroma.solver = &procrustes_solver();
      settings.chroma.polish_options = {{"radius", "1"}};
      settings.chroma.search_candidates = search_candidates;
      settings.chroma.polish_candidates = polish_candidates;
      EncoderSettings unbounded = settings;
      unbounded.chroma.top_shape_bound = false;
      for (int by = 0; by < image.height / 4; by += 3)
        for (int bx = 0; bx < image.width / 4; bx += 5) {
          const BlockTexels texels = block_at(image, bx, by);
          for (const Mode mode : {Mode::shape_ii, Mode::shape_i}) {
            const Params with = encode_mode(texels, mode, shapes, settings, 1);
            EXPECT_EQ(with, encode_mode(texels, mode, shapes, unbounded, 1))
                << "block (" << bx << ", " << by << ") mode " << static_cast<int>(mode) << " polish_candidates "
                << polish_candidates;
            if (polish_candidates == 1) {
              EncoderSettings two = settings;
              two.chroma.polish_candidates = 2;
              differing_polish_counts += !(with == encode_mode(texels, mode, shapes, two, 1));
            }
            ++blocks;
          }
        }
    }
  EXPECT_GT(blocks, 1000);
  // The polish count matters on these blocks (so the bound is tested where it decides something).
  EXPECT_GT(differing_polish_counts, 10);
}

TEST(MunkbergSearch, LogIndexAssignmentReturnsTheDecodedBlocksErrorAndTheBestLandmarkPerGroup) {
  // assign_chroma_indices_log2 decodes each texel on each landmark once: its indices must be those of decoding the
  // whole block on each landmark (the decoder's texels), and its error the decoded block's, bit for bit.
  const Image image = sample("Desk.exr");
  const ShapeSet shapes = default_shape_set();
  EncoderSettings settings;
  settings.chroma.solver = &procrustes_solver();
  settings.chroma.polish_options = {{"radius", "1"}};
  std::vector<BlockTexels> blocks_to_test;
  for (int by = 0; by < image.height / 4; by += 3)
    for (int bx = 0; bx < image.width / 4; bx += 3) blocks_to_test.push_back(block_at(image, bx, by));
  // A block whose first row is true black: every landmark ties on those texels, and the lower must win.
  BlockTexels with_black = blocks_to_test[blocks_to_test.size() / 2];
  for (int i = 0; i < 4; ++i) with_black.rgba[i][0] = with_black.rgba[i][1] = with_black.rgba[i][2] = 0.0f;
  blocks_to_test.push_back(with_black);
  int blocks = 0;
  for (const BlockTexels& texels : blocks_to_test)
    for (const Mode mode : {Mode::shape_ii, Mode::shape_i}) {
      Params params = encode_mode(texels, mode, shapes, settings, 1);
      params.chroma_index.fill(0);
      const double error = assign_chroma_indices_log2(texel_log2(texels), shapes, &params);
      EXPECT_EQ(error, block_log2_error(texels, decode_params(params, shapes)));
      std::array<BlockTexels, kShapeLandmarkCount> decoded;
      for (int k = 0; k < kShapeLandmarkCount; ++k) {
        Params trial = params;
        for (int g = 0; g < chroma_groups(mode); ++g)
          trial.chroma_index[static_cast<std::size_t>(g)] = static_cast<std::uint8_t>(k);
        decoded[static_cast<std::size_t>(k)] = decode_params(trial, shapes);
      }
      for (int g = 0; g < chroma_groups(mode); ++g) {
        std::array<double, kShapeLandmarkCount> group_error{};
        for (int k = 0; k < kShapeLandmarkCount; ++k)
          for (int i = 0; i < kTexels; ++i)
            if (chroma_group_of_texel(mode, i) == g)
              for (int c = 0; c < 3; ++c) {
                const double d =
                    metric_log2(decoded[static_cast<std::size_t>(k)].rgba[i][c]) - metric_log2(texels.rgba[i][c]);
                group_error[static_cast<std::size_t>(k)] += d * d;
              }
        const int chosen = params.chroma_index[static_cast<std::size_t>(g)];
        EXPECT_EQ(chosen, std::min_element(group_error.begin(), group_error.end()) - group_error.begin());
      }
      ++blocks;
    }
  EXPECT_GT(blocks, 200);
}

TEST(MunkbergSearch, SkipRulesLeaveTheBytesOfTheSamplesUnchanged) {
  // Both rules are exact for the thorough search without the mode predictor. With a quality limit (good_enough > 0:
  // the fast and medium presets) or the mode predictor (every preset but paper) the mode bound also sets the order in
  // which modes are tried and feeds the predictor's estimates, so it is part of those searches; the constant-chroma
  // rule stays exact there too.
  for (const std::string name : {"Desk.exr", "blender_world_sunset.exr", "hdr-rgb-arboretum.hdr"}) {
    const Image image = sample(name);
    const FormatOptions thorough = options({{"preset", "thorough"}, {"mode_predictor", "0"}});
    const EncodedTexture with = format().encode(image, thorough, CodecContext{2, 1});
    const EncodedTexture without = encode_with_speedups(image, thorough, CodecContext{2, 1}, ExactSpeedups{false, false});
    EXPECT_EQ(with.blocks, without.blocks) << name;
    EXPECT_EQ(with.block_modes, without.block_modes) << name;
    const EncodedTexture medium = format().encode(image, options(), CodecContext{2, 1});
    const EncodedTexture medium_without_constant_rule =
        encode_with_speedups(image, options(), CodecContext{2, 1}, ExactSpeedups{false, true});
    EXPECT_EQ(medium.blocks, medium_without_constant_rule.blocks) << name;
  }
}

TEST(MunkbergSearch, SkipRulesLeaveTheBytesOfConstantAndSteepBlocksUnchanged) {
  // 32x16: constant blocks (several colours, black), single-hue luminance ramps (constant chroma), and blocks whose
  // luminance spans 24 stops (shape I's bound can exceed shape II's error).
  Image image(32, 16, 4);
  for (int y = 0; y < 16; ++y)
    for (int x = 0; x < 32; ++x) {
      const int block = (y / 4) * 8 + x / 4;
      const int i = (y % 4) * 4 + x % 4;
      float r = 0.5f, g = 0.25f, b = 0.125f;
      if (block % 4 == 1) {   // constant chroma, luminance ramp
        const float s = std::exp2(static_cast<float>(i) / 3.0f - 2.0f);
        r *= s, g *= s, b *= s;
      } else if (block % 4 == 2) {   // 24-stop grey ramp with a black texel
        const float s = i == 0 ? 0.0f : std::exp2(-12.0f + 1.6f * static_cast<float>(i));
        r = g = b = s;
      } else if (block % 4 == 3) {   // constant, a different colour per block
        r = 0.01f * static_cast<float>(block + 1), g = 2.0f, b = 0.3f;
      }
      float* t = image.texel(x, y);
      t[0] = r, t[1] = g, t[2] = b, t[3] = 1.0f;
    }
  // The rules do fire here: the constant blocks' chroma is constant, and the steep block's shape I bound is above
  // shape II's error (shape I is skipped).
  EncoderSettings settings;
  settings.chroma.solver = &procrustes_solver();
  settings.chroma.polish_options = {{"radius", "1"}};
  const ShapeSet shapes = default_shape_set();
  const BlockTexels steep = block_at(image, 2, 0);
  const double shape_ii_error =
      block_log2_error(steep, decode_params(encode_mode(steep, Mode::shape_ii, shapes, settings, 1), shapes));
  EXPECT_GT(shape_mode_lower_bound(steep, Mode::shape_i, settings), shape_ii_error);
  double log_luminance[kTexels];
  ChromaPoints chroma;
  block_targets(block_at(image, 3, 0), log_luminance, &chroma);
  bool has_weight = false;
  Point2 point;
  EXPECT_TRUE(constant_chroma(chroma_fit_data(chroma, Mode::shape_i, shapes.shapes[0], settings.chroma, &has_weight),
                              0.0, &point));

  const FormatOptions thorough = options({{"preset", "thorough"}});   // the search both rules are exact for
  const EncodedTexture with = format().encode(image, thorough, CodecContext{1, 1});
  for (const ExactSpeedups& without_rule : {ExactSpeedups{false, true}, ExactSpeedups{true, false}}) {
    const EncodedTexture without = encode_with_speedups(image, thorough, CodecContext{1, 1}, without_rule);
    EXPECT_EQ(with.blocks, without.blocks) << without_rule.skip_constant;
  }
}

TEST(MunkbergSearch, GlobalChromaSearchStaysWithinThreePercentOfThePerShapeSearchOnDesk) {
  const Image image = sample("Desk.exr");
  const Metric& log2rgb = find_metric("log2rgb");
  const auto error_of = [&](const FormatOptions& given) {
    const EncodedTexture texture = format().encode(image, options(given), CodecContext{2, 1});
    return log2rgb.compute(image, format().decode(texture, CodecContext{2, 1}), {}).value;
  };
  const double global = error_of({{"preset", "thorough"}});
  const double per_shape = error_of({{"preset", "thorough"}, {"solver", "procrustes"}});
  EXPECT_LT(global, per_shape * 1.03);
  EXPECT_GT(global, 0.0);
}

TEST(MunkbergSearch, PolishMarginOnlySkipsShapesFarBehindTheFirst) {
  const Image image = sample("Desk.exr");
  const Metric& log2rgb = find_metric("log2rgb");
  // The thorough search polishes two shapes per mode, so the margin has a second shape to skip.
  const EncodedTexture plain = format().encode(image, options({{"preset", "thorough"}}), CodecContext{2, 1});
  // A margin no second shape exceeds on this sample: the same bytes as no margin.
  const EncodedTexture wide =
      format().encode(image, options({{"preset", "thorough"}, {"polish_margin", "1000"}}), CodecContext{2, 1});
  EXPECT_EQ(plain.blocks, wide.blocks);
  // A tight margin polishes fewer shapes: other bytes, a slightly higher error (measured +1.3 % on a Desk crop).
  const EncodedTexture tight =
      format().encode(image, options({{"preset", "thorough"}, {"polish_margin", "0.05"}}), CodecContext{2, 1});
  EXPECT_NE(plain.blocks, tight.blocks);
  const double plain_error = log2rgb.compute(image, format().decode(plain, CodecContext{2, 1}), {}).value;
  const double tight_error = log2rgb.compute(image, format().decode(tight, CodecContext{2, 1}), {}).value;
  EXPECT_GE(tight_error, plain_error * 0.99);
  EXPECT_LT(tight_error, plain_error * 1.05);
}

TEST(MunkbergSearch, GoodEnoughOnlyChangesBlocksThatAreAlreadyThatGood) {
  // good_enough stops the search of a block once it is at most that error: every block it changes must be that good
  // (up to the float rounding of decoded texels), some blocks must change, and the image error may rise only a little.
  const Image image = sample("Desk.exr");
  constexpr double kGoodEnough = 0.3;
  // On the thorough search (no limit of its own) with every other setting kept.
  const EncodedTexture plain = format().encode(image, options({{"preset", "thorough"}}), CodecContext{2, 1});
  const EncodedTexture quick = format().encode(
      image, options({{"preset", "thorough"}, {"good_enough", exact_number_text(kGoodEnough)}}), CodecContext{2, 1});
  const Image plain_image = format().decode(plain, CodecContext{2, 1});
  const Image quick_image = format().decode(quick, CodecContext{2, 1});
  int changed = 0;
  const int blocks_per_row = (image.width + 3) / 4;   // the last column of blocks is partial (254 pixels)
  for (int by = 0; by < image.height / 4; ++by)
    for (int bx = 0; bx < image.width / 4; ++bx) {   // whole blocks only (block_at reads 4x4 texels)
      const std::size_t b = static_cast<std::size_t>(by * blocks_per_row + bx) * kBlockBytes;
      if (std::equal(plain.blocks.begin() + static_cast<std::ptrdiff_t>(b),
                     plain.blocks.begin() + static_cast<std::ptrdiff_t>(b + kBlockBytes),
                     quick.blocks.begin() + static_cast<std::ptrdiff_t>(b)))
        continue;
      ++changed;
      const double error = block_log2_error(block_at(image, bx, by), block_at(quick_image, bx, by));
      EXPECT_LE(error, kGoodEnough * (1.0 + 1e-6) + 1e-9) << "block " << bx << "," << by;
    }
  EXPECT_GT(changed, 100);
  const Metric& log2rgb = find_metric("log2rgb");
  const double plain_error = log2rgb.compute(image, plain_image, {}).value;
  const double quick_error = log2rgb.compute(image, quick_image, {}).value;
  EXPECT_LT(quick_error, plain_error * 1.02);
}

}  // namespace
}  // namespace blocklab::munkberg
