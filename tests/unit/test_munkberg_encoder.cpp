// `munkberg` encoder (formats/munkberg): constant and two-colour blocks are near-exact; true-black texels decode to
// black; the luminance endpoint neighbourhood search (section 7.3, Fig. 9) never loses to plain min/max and wins on
// a Fig. 9-like block; bytes are identical at 1 and 2 threads (also with the annealer and a stochastic NLopt
// algorithm) and the seed option drives the stochastic solvers; every solver option writes a valid .blk file;
// interval_bb's certified fit error is never above Procrustes'; a YAML shape set travels in side data; bad options
// are rejected naming the key, and NaN / infinite / negative texels naming the pixel.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <random>

#include "core/error.h"
#include "core/image_io.h"
#include "core/input_policy.h"
#include "formats/common/container.h"
#include "formats/munkberg/munkberg_encoder.h"
#include "formats/munkberg/munkberg_format.h"
#include "formats/munkberg/munkberg_luminance.h"
#include "formats/registry.h"
#include "solvers/interval_bb/interval_bb_solver.h"
#include "solvers/procrustes/procrustes_solver.h"

namespace blocklab::munkberg {
namespace {

const Format& format() { return find_format("munkberg"); }
FormatOptions options(const FormatOptions& given = {}) { return resolve_format_options(format(), given); }

EncoderSettings default_settings() {
  EncoderSettings settings;
  settings.chroma.solver = &procrustes_solver();
  settings.chroma.polish_options = {{"radius", "1"}};
  return settings;
}

Image sample(const std::string& name) {
  Image image = read_image(std::string(BLOCKLAB_TEST_SAMPLES) + "/hdr/" + name);
  apply_input_policy(image, InputPolicy::clamp, name);
  return image;
}

Image crop(const Image& image, int x0, int y0, int width, int height) {
  Image out(width, height, image.channels);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) std::memcpy(out.texel(x, y), image.texel(x0 + x, y0 + y), 4 * sizeof(float));
  return out;
}

BlockTexels uniform_block(float r, float g, float b) {
  BlockTexels t;
  for (int i = 0; i < kTexels; ++i) {
    t.rgba[i][0] = r;
    t.rgba[i][1] = g;
    t.rgba[i][2] = b;
    t.rgba[i][3] = 1.0f;
  }
  return t;
}

// Root mean square log2 error per channel sample of a block.
double rms_log2(const BlockTexels& source, const BlockTexels& decoded) {
  return std::sqrt(block_log2_error(source, decoded) / (3.0 * kTexels));
}

TEST(MunkbergEncoder, ConstantBlocksAreNearlyExact) {
  // Luminance: a constant value sits between two adjacent 8-bit codes and is reached within half of 1/15 code
  // (0.0042 log2); chroma: 7-bit base colours, so a chroma ratio is off by at most half a step (1/254) absolute.
  for (const auto& rgb : std::vector<std::array<float, 3>>{{0.7f, 2.3f, 0.4f}, {1000.0f, 800.0f, 900.0f},
                                                          {0.001f, 0.002f, 0.0005f}, {5.0f, 5.0f, 5.0f}}) {
    const BlockTexels source = uniform_block(rgb[0], rgb[1], rgb[2]);
    const Params params = encode_block(source, default_shape_set(), default_settings(), 7);
    const BlockTexels decoded = decode_params(params, default_shape_set());
    EXPECT_LT(rms_log2(source, decoded), 0.02) << rgb[0] << " " << rgb[1] << " -> " << decoded.rgba[0][0] << " "
                                               << decoded.rgba[0][1] << " " << decoded.rgba[0][2] << " mode "
                                               << static_cast<int>(params.mode) << " shape " << params.shape << " base "
                                               << params.base[0] << "," << params.base[1] << "," << params.base[2] << ","
                                               << params.base[3] << " ci " << int(params.chroma_index[0]);
  }
}

TEST(MunkbergEncoder, TwoColourBlocksAreNearlyExact) {
  BlockTexels source = uniform_block(0.2f, 0.9f, 0.1f);
  for (int i = 0; i < kTexels; ++i)
    if ((i % 4) >= 2) {   // right half another colour, ten times brighter
      source.rgba[i][0] = 6.0f;
      source.rgba[i][1] = 2.0f;
      source.rgba[i][2] = 3.0f;
    }
  const Params params = encode_block(source, default_shape_set(), default_settings(), 7);
  EXPECT_LT(rms_log2(source, decode_params(params, default_shape_set())), 0.03);
}

TEST(MunkbergEncoder, TrueBlackTexelsDecodeToBlack) {
  BlockTexels source = uniform_block(0.5f, 0.25f, 0.125f);
  source.rgba[3][0] = source.rgba[3][1] = source.rgba[3][2] = 0.0f;
  source.rgba[9][0] = source.rgba[9][1] = source.rgba[9][2] = 0.0f;
  const Params params = encode_block(source, default_shape_set(), default_settings(), 7);
  const BlockTexels decoded = decode_params(params, default_shape_set());
  for (int c = 0; c < 3; ++c) {
    EXPECT_EQ(decoded.rgba[3][c], 0.0f);
    EXPECT_EQ(decoded.rgba[9][c], 0.0f);
    EXPECT_GT(decoded.rgba[0][c], 0.0f);
  }
  EXPECT_LT(rms_log2(source, decoded), 0.05);
}

TEST(MunkbergEncoder, EndpointNeighbourhoodSearchNeverLosesToMinMaxAndWinsOnFigure9) {
  std::mt19937 random(3);
  std::uniform_real_distribution<double> spread(-6.0, 6.0);
  for (int trial = 0; trial < 200; ++trial) {
    double target[kTexels];
    const double centre = spread(random);
    for (double& t : target) t = centre + 0.2 * spread(random);
    for (const Mode mode : {Mode::shape_ii, Mode::shape_i}) {
      const LuminanceFit plain = fit_luminance(mode, target, 0);
      const LuminanceFit searched = fit_luminance(mode, target, 2);
      EXPECT_LE(searched.error, plain.error);
    }
  }
  // Figure 9: most values in a cluster plus one outlier; moving the endpoints off min/max lets the levels hit the
  // cluster. Shape I (8 levels) on codes: cluster at code 100.15, outlier at code 103. Min/max (100, 103) has levels
  // 3/7 apart (cluster error 0.15 code); (98, 103) has a level at 100.143.
  double target[kTexels];
  const double code = kLogLumRange / 255.0;
  for (int i = 0; i < kTexels; ++i) target[i] = kLogLumMin + (i == 0 ? 103.0 : 100.15) * code;
  const LuminanceFit plain = fit_luminance(Mode::shape_i, target, 0);
  const LuminanceFit searched = fit_luminance(Mode::shape_i, target, 2);
  EXPECT_LT(searched.error, 0.5 * plain.error);
}

TEST(MunkbergEncoder, BoundedLuminanceFitIsTheFullFitBelowTheBoundAndStopsAtOrAboveIt) {
  // fit_luminance passes the best pair's error as the bound of the next pairs: below it the fit must be the full one
  // bit for bit (indices and error), at or above it any partial error >= the bound.
  std::mt19937 random(5);
  std::uniform_real_distribution<double> spread(-6.0, 6.0);
  std::uniform_int_distribution<int> endpoint(0, kLumEndpointMax);
  int stopped = 0;
  for (int trial = 0; trial < 300; ++trial) {
    double target[kTexels];
    const double centre = spread(random);
    for (double& t : target) t = centre + 0.3 * spread(random);
    const int a = endpoint(random), b = endpoint(random);
    for (const Mode mode : {Mode::shape_ii, Mode::shape_i}) {
      const LuminanceFit full = assign_luminance_indices(mode, std::min(a, b), std::max(a, b), target);
      for (const double bound : {full.error * 2.0 + 1.0, full.error, full.error * 0.5}) {
        const LuminanceFit bounded = assign_luminance_indices(mode, std::min(a, b), std::max(a, b), target, bound);
        if (full.error < bound) {
          EXPECT_EQ(bounded.error, full.error) << trial;
          EXPECT_EQ(bounded.index, full.index) << trial;
        } else {
          EXPECT_GE(bounded.error, bound) << trial;
          stopped += bounded.index != full.index ? 1 : 0;
        }
      }
    }
  }
  EXPECT_GT(stopped, 100);   // the bound really cuts fits short
}

TEST(MunkbergEncoder, LuminanceIndicesAreTheNearestScoredLevelWithTiesToTheLowerIndex) {
  // assign_luminance_indices checks only the closed-form nearest level and its two neighbours:
  // the same indices and error as scanning every level, for random pairs, the black code at either end (scored at
  // -24), equal endpoints (every level ties), adjacent codes (the smallest step), reversed endpoints (descending
  // levels), targets on a level, halfway between two (ties), a rounding step either side of halfway, and targets
  // at the metric floor or beyond the stored range.
  std::mt19937 random(9);
  std::uniform_real_distribution<double> spread(-20.0, 14.0);
  std::uniform_int_distribution<int> endpoint(0, kLumEndpointMax);
  int trials = 0;
  for (int trial = 0; trial < 600; ++trial) {
    int e0 = endpoint(random), e1 = endpoint(random);
    if (trial % 6 == 1) e0 = 0;                         // black code as level 0
    if (trial % 6 == 2) e1 = e0;                        // one level
    if (trial % 6 == 3) std::swap(e0, e1);              // either order
    if (trial % 6 == 4) e1 = 0;                         // black code as level n (descending levels)
    if (trial % 6 == 5) e1 = std::min(kLumEndpointMax, e0 + 1);   // the finest level spacing
    for (const Mode mode : {Mode::shape_ii, Mode::shape_i}) {
      const int n = lum_levels_minus_one(mode);
      double target[kTexels];
      for (int i = 0; i < kTexels; ++i) {
        const int l = i % (n + 1);
        const int next = std::min(n, l + 1);
        const double halfway = 0.5 * (scored_level_log2(mode, e0, e1, l) + scored_level_log2(mode, e0, e1, next));
        if (i % 5 == 0) target[i] = scored_level_log2(mode, e0, e1, l);   // on a level
        else if (i % 5 == 1) target[i] = halfway;
        else if (i % 5 == 2) target[i] = std::nextafter(halfway, i % 2 == 0 ? 100.0 : -100.0);
        else if (i == 3) target[i] = kBlackLog2;          // the metric floor (black wins when there is one)
        else if (i == 8) target[i] = -21.0;               // nearer to black (-24) than to the lowest level (-16)
        else if (i == 13) target[i] = kLogLumMax + 1.0;   // beyond the stored range
        else target[i] = spread(random);
      }
      const LuminanceFit fit = assign_luminance_indices(mode, e0, e1, target);
      double error = 0.0;
      for (int i = 0; i < kTexels; ++i) {
        int best = 0;
        double best_error = 0.0;
        for (int l = 0; l <= n; ++l) {
          const double d = scored_level_log2(mode, e0, e1, l) - target[i];
          if (l == 0 || d * d < best_error) best = l, best_error = d * d;
        }
        EXPECT_EQ(fit.index[static_cast<std::size_t>(i)], best) << trial << " texel " << i;
        error += best_error;
      }
      EXPECT_EQ(fit.error, error) << trial;
      ++trials;
    }
  }
  EXPECT_EQ(trials, 1200);
}

TEST(MunkbergEncoder, BytesAreIdenticalAtOneAndTwoThreads) {
  const Image image = crop(sample("Desk.exr"), 96, 64, 32, 32);
  const std::vector<FormatOptions> variants = {
      FormatOptions{},
      FormatOptions{{"solver", "anneal"}, {"solver_options", "iterations=300,restarts=0"}},
      // A stochastic NLopt algorithm (serialised and seeded per solve by the nlopt solver).
      FormatOptions{{"solver", "nlopt"}, {"solver_options", "algorithm=GN_CRS2_LM,max_evaluations=150"}}};
  for (const FormatOptions& given : variants) {
    const EncodedTexture one = format().encode(image, options(given), CodecContext{1, 1});
    const EncodedTexture two = format().encode(image, options(given), CodecContext{2, 1});
    EXPECT_EQ(one.blocks, two.blocks) << option_text(options(given), "solver");
    EXPECT_EQ(one.block_modes, two.block_modes);
  }
}

TEST(MunkbergEncoder, TheSeedOptionDrivesTheStochasticSolvers) {
  // Without warm start and polish, annealing's answer depends on its per-block streams: another `seed` changes bytes,
  // the same seed reproduces them.
  const Image image = crop(sample("Desk.exr"), 96, 64, 16, 16);
  FormatOptions given = {{"solver", "anneal"}, {"solver_options", "iterations=60,restarts=0"}, {"warm_start", "false"},
                         {"polish", "false"}, {"seed", "1"}};
  const EncodedTexture first = format().encode(image, options(given), CodecContext{1, 1});
  const EncodedTexture again = format().encode(image, options(given), CodecContext{2, 1});
  given["seed"] = "2";
  const EncodedTexture other = format().encode(image, options(given), CodecContext{1, 1});
  EXPECT_EQ(first.blocks, again.blocks);
  EXPECT_NE(first.blocks, other.blocks);
}

TEST(MunkbergEncoder, EverySolverOptionWritesAValidFile) {
  const Image image = crop(sample("hdr-rgb-arboretum.hdr"), 40, 40, 8, 8);
  const std::string path = (std::filesystem::temp_directory_path() / "test_munkberg_solver.blk").string();
  const std::vector<FormatOptions> variants = {
      {{"solver", "procrustes"}},
      {{"solver", "anneal"}, {"solver_options", "iterations=200,restarts=1"}},
      {{"solver", "nlopt"}, {"solver_options", "algorithm=LN_NELDERMEAD,max_evaluations=200"}},
      {{"solver", "nlopt"}, {"solver_options", "algorithm=GN_DIRECT_L,max_evaluations=200"},
       {"warm_start", "false"}},
      {{"solver", "interval_bb"}, {"solver_options", "max_boxes=2000"}},
      {{"chroma_error", "linear"}, {"polish_error", "fit"}, {"index_metric", "fit"}},
  };
  for (const FormatOptions& given : variants) {
    const EncodedTexture texture = format().encode(image, options(given), CodecContext{0, 1});
    write_container(path, texture);
    const EncodedTexture read = read_container(path);
    EXPECT_EQ(read.blocks, texture.blocks);
    const Image decoded = format().decode(read, CodecContext{0, 1});
    double sum = 0.0;
    for (std::size_t i = 0; i < decoded.texel_count(); ++i)
      for (int c = 0; c < 3; ++c) {
        const double d = std::log2(std::max(decoded.pixels[4 * i + c], 0x1p-24f)) -
                         std::log2(std::max(image.pixels[4 * i + c], 0x1p-24f));
        sum += d * d;
      }
    // log2[RGB] of an 8 bpp encoding of a natural crop: far below 1 for every solver.
    EXPECT_LT(std::sqrt(sum / decoded.texel_count()), 0.5) << option_text(options(given), "solver");
  }
  std::filesystem::remove(path);
}

TEST(MunkbergEncoder, CertifiedIntervalBbFitErrorIsNeverAboveProcrustes) {
  const Image image = sample("Desk.exr");
  ChromaSettings settings;
  for (const std::array<int, 2>& at : std::vector<std::array<int, 2>>{{120, 88}, {40, 150}}) {
    BlockTexels texels = load_block(image, BlockGrid(image.width, image.height),
                                    static_cast<std::size_t>(at[1] / 4 * ((image.width + 3) / 4) + at[0] / 4));
    double log_luminance[kTexels];
    ChromaPoints points;
    block_targets(texels, log_luminance, &points);
    const ShapeFitProblem problem = make_shape_fit_problem(
        chroma_fit_data(points, Mode::shape_ii, default_shape_set().shapes[0], settings, nullptr));
    const SolveResult procrustes = procrustes_solver().solve(problem, {}, nullptr, 1);
    std::vector<double> snapped(4);
    for (int p = 0; p < 4; ++p)
      snapped[static_cast<std::size_t>(p)] =
          problem.lattice(p).point(problem.lattice(p).nearest_index(procrustes.parameters[static_cast<std::size_t>(p)]));
    const SolveResult certified = interval_bb_solver().solve(problem, {}, snapped.data(), 1);
    EXPECT_EQ(certified.summary.termination, Termination::optimal);
    EXPECT_LE(certified.summary.final_error, problem.eval(snapped.data()));
  }
}

TEST(MunkbergEncoder, YamlShapeSetTravelsInSideData) {
  const std::string path = (std::filesystem::temp_directory_path() / "test_munkberg_shapes.yaml").string();
  {
    std::ofstream out(path);
    out << "shapes:\n";
    for (int s = 0; s < kShapeCount; ++s)
      out << "  - {name: s" << s << ", landmarks: [[0, 0], [1, 0], [0.5, " << 0.1 * (s + 1) << "], [0.5, -0.3]]}\n";
  }
  const Image image = crop(sample("Desk.exr"), 96, 64, 16, 16);
  const EncodedTexture texture = format().encode(image, options({{"shapes", path}}), CodecContext{0, 1});
  const ShapeSet custom = load_shape_set(path);
  EXPECT_TRUE(shape_set_of(texture.side_data) == custom);
  // Decoding follows the side data: the same blocks with the default set decode differently.
  EncodedTexture with_default = texture;
  with_default.side_data[kShapeSideDataKey] = shape_set_to_side_data(default_shape_set());
  EXPECT_NE(format().decode(texture, CodecContext{0, 1}).pixels, format().decode(with_default, CodecContext{0, 1}).pixels);
  // A texture whose options name custom shapes but whose shape side data is gone is refused, never decoded with the
  // built-in set.
  EncodedTexture without_shapes = texture;
  without_shapes.side_data.erase(kShapeSideDataKey);
  try {
    format().decode(without_shapes, CodecContext{0, 1});
    ADD_FAILURE() << "decoded a custom-shape texture without its shapes";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find(kShapeSideDataKey), std::string::npos) << e.what();
  }
  std::filesystem::remove(path);
}

TEST(MunkbergEncoder, BadOptionsAreRejectedNamingTheKey) {
  const Image image = crop(sample("Desk.exr"), 0, 0, 4, 4);
  const auto expect_error = [&](const FormatOptions& given, const std::string& needle) {
    try {
      format().encode(image, options(given), CodecContext{1, 1});
      ADD_FAILURE() << "accepted " << needle;
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find(needle), std::string::npos) << e.what();
    }
  };
  expect_error({{"solver_options", "iterations"}}, "solver_options");
  expect_error({{"solver", "anneal"}, {"solver_options", "bogus=1"}}, "bogus");
  expect_error({{"solver", "nlopt"}, {"solver_options", "algorithm=NOT_AN_ALGORITHM"}}, "NOT_AN_ALGORITHM");
  expect_error({{"shapes", "/nonexistent/shapes.yaml"}}, "/nonexistent/shapes.yaml");
  EXPECT_THROW(options({{"solver", "simplex"}}), Error);
}

TEST(MunkbergEncoder, NonFiniteOrNegativeTexelsAreRejectedNamingThePixel) {
  Image bad(8, 8, 3);
  for (const float value : {NAN, INFINITY, -1.0f}) {
    bad.texel(1, 2)[1] = value;
    try {
      format().encode(bad, options(), CodecContext{1, 1});
      ADD_FAILURE() << "accepted " << value;
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find("pixel (1, 2) channel G"), std::string::npos) << e.what();
    }
  }
  EXPECT_THROW(options({{"alpha", "0"}}), Error);
}

}  // namespace
}  // namespace blocklab::munkberg
