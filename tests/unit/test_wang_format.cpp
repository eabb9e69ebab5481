// The `wang` Format and its codecs (formats/wang/): decode through the Format equals the oracle on encoded samples,
// thread-count independence, the 1D codec against the plain BC3 encoder, the block Problems against the codecs'
// errors, the zone splits, and option / side-data errors.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <string>

#include "core/error.h"
#include "core/image_io.h"
#include "formats/registry.h"
#include "formats/wang/wang_block.h"
#include "formats/wang/wang_block_problem.h"
#include "formats/wang/wang_dds.h"
#include "formats/bc4/bc4_encoder.h"
#include "formats/common/dds.h"
#include "formats/wang/wang_joint_codes.h"
#include "formats/wang/wang_luminance_codec.h"
#include "formats/wang/wang_residual_codec.h"
#include "formats/wang/wang_side_data.h"
#include "formats/wang/wang_zone_encoding.h"
#include "formats/wang/wang_zone_split.h"
#include "tests/unit/test_wang_random_block.h"

namespace blocklab {
namespace {

Image sample_crop() {
  const Image image = read_image(std::string(BLOCKLAB_TEST_SAMPLES) + "/hdr/Desk.exr");
  return crop_image(image, 0, 0, std::min(image.width, 37), std::min(image.height, 29));
}

EncodedTexture encode(const Image& image, const FormatOptions& given, int threads = 2) {
  const Format& format = find_format("wang");
  return format.encode(image, resolve_format_options(format, given), CodecContext{threads, 1});
}

TEST(WangFormat, DecodeEqualsTheOracleAndBytesDoNotDependOnThreadsForEveryVariant) {
  const Image image = sample_crop();
  const Format& format = find_format("wang");
  const std::vector<FormatOptions> variants = {
      {}, {{"space", "luv"}}, {{"residual", "ratio"}}, {{"residual", "none"}}, {{"l_bits", "1x12"}},
      {{"codec", "bc3"}}, {{"preset", "fast"}}};
  for (const FormatOptions& given : variants) {
    SCOPED_TRACE(given.empty() ? "default" : given.begin()->first + "=" + given.begin()->second);
    const EncodedTexture texture = encode(image, given, 2);
    EXPECT_EQ(texture.blocks, encode(image, given, 1).blocks);
    const Image decoded = format.decode(texture, CodecContext{2, 1});
    const std::string space = option_text(texture.options, "space");
    const std::string residual_name = option_text(texture.options, "residual");
    const wang::Residual residual = residual_name == "s"     ? wang::Residual::s
                                    : residual_name == "ratio" ? wang::Residual::ratio
                                                               : wang::Residual::none;
    const wang::LuminanceSplit split = option_text(texture.options, "l_bits") == "2x6"
                                           ? wang::LuminanceSplit::two_zones
                                           : wang::LuminanceSplit::one_range;
    const wang::SideData side = wang::read_side_data(texture, split, residual, "test");
    const BlockGrid grid(image.width, image.height);
    for (std::size_t block = 0; block < grid.block_count(); ++block) {
      const BlockTexels oracle = wang::reference_decode_block(
          side.zones, split, space == "luv" ? wang::ColorSpace::luv : wang::ColorSpace::luvw, residual,
          texture.blocks.data() + block * wang::kBlockBytes);
      const std::size_t bx = block % grid.blocks_x, by = block / grid.blocks_x;
      for (int texel = 0; texel < 16; ++texel) {
        const int x = static_cast<int>(bx * 4) + texel % 4, y = static_cast<int>(by * 4) + texel / 4;
        if (x >= image.width || y >= image.height) continue;
        for (int channel = 0; channel < 3; ++channel)
          ASSERT_EQ(decoded.texel(x, y)[channel], oracle.rgba[texel][channel]);
      }
    }
  }
}

// The 1D codec descends from the plain 8-value BC4 fit of the eq. 3 targets in every mode pair, so per block it is
// never worse than that start; the plain BC3 encoder also tries a 6-value start, which the 1D codec leaves out (a
// worse start for the log-domain error on the measured images), so against plain BC3 the claim is on the total.
TEST(WangFormat, OneDimensionalCodecNeverLosesToItsStartBeatsPlainBc3InTotalAndMatchesItsProblem) {
  std::mt19937 rng(5);
  std::lognormal_distribution<double> luminance(0.0, 2.5);
  wang::Zones zones;
  zones.tmin = 0.0;
  zones.t1 = 3.0;
  zones.tmax = 400.0;
  const wang::ShaderConstants c = wang::shader_constants(zones, wang::LuminanceSplit::two_zones, wang::Residual::none);
  const wang::SearchEffort effort = wang::preset_effort("medium", "test");
  const BlockSolverSetup builtin;
  double one_d_total = 0.0, plain_total = 0.0;
  for (int trial = 0; trial < 60; ++trial) {
    wang::LuminanceBlockError error;
    error.high = c.l_high;
    error.low = c.l_low;
    error.tmin = c.tmin;
    for (int texel = 0; texel < 16; ++texel) {
      error.luminance[texel] = std::min(luminance(rng), zones.tmax);
      error.weight[texel] = 1.0 / (error.luminance[texel] + 1.0 / 16384.0);
    }
    const wang::LuminanceFit plain = wang::fit_luminance_block(error, zones, wang::LuminanceSplit::two_zones, effort,
                                                               wang::Codec::bc3, builtin, 0);
    const wang::LuminanceFit one_d = wang::fit_luminance_block(error, zones, wang::LuminanceSplit::two_zones, effort,
                                                               wang::Codec::one_d, builtin, 0);
    float targets[2][16];
    for (int texel = 0; texel < 16; ++texel) {
      const std::array<double, 2> t = wang::luminance_targets(error.luminance[texel], zones, wang::LuminanceSplit::two_zones);
      targets[0][texel] = static_cast<float>(t[0] * 255.0);
      targets[1][texel] = static_cast<float>(t[1] * 255.0);
    }
    const double start_error = wang::luminance_error_with_codes(
        error, fit_bc4_block(targets[0], effort.luminance_start, false),
        fit_bc4_block(targets[1], effort.luminance_start, false));
    EXPECT_LE(one_d.error, start_error) << "trial " << trial;
    one_d_total += one_d.error;
    plain_total += plain.error;
    // The Problem's error at the answer (codes chosen per texel) is the codec's error.
    wang::LuminanceBlockError problem_error = error;
    problem_error.modes = {one_d.tex0.mode, one_d.tex1.mode};
    const auto problem = wang::make_luminance_block_problem(problem_error);
    const double x[4] = {double(one_d.tex0.endpoints[0]), double(one_d.tex0.endpoints[1]),
                         double(one_d.tex1.endpoints[0]), double(one_d.tex1.endpoints[1])};
    EXPECT_NEAR(problem.eval(x), one_d.error, 1e-9 * (1.0 + one_d.error));
    const Interval box[4] = {Interval(x[0], x[0] + 1), Interval(x[1], x[1] + 1), Interval(x[2]), Interval(x[3])};
    const Interval enclosure = problem.eval(box);
    EXPECT_LE(enclosure.lower(), problem.eval(x));
    EXPECT_GE(enclosure.upper(), problem.eval(x));
    double gradient[4];
    EXPECT_NEAR(problem.eval_with_gradient(x, gradient), problem.eval(x), 1e-9 * (1.0 + one_d.error));
  }
  EXPECT_LT(one_d_total, plain_total);
}

TEST(WangFormat, ResidualProblemIntervalEnclosesLatticePointsAndJetValueEqualsDouble) {
  wang::ResidualBlockError error;
  error.ranges = {0.5, 0.25, 2.0};
  error.rmin = -0.4;
  std::mt19937 rng(6);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  for (int texel = 0; texel < 16; ++texel) {
    error.luminance[texel] = 1.0 + 3.0 * unit(rng);
    error.decoded[texel] = error.luminance[texel] + 0.3 * (unit(rng) - 0.5);
    error.weight[texel] = 1.0 / error.luminance[texel];
  }
  const auto problem = wang::make_residual_block_problem(error);
  const double x[6] = {12, 40, 3, 20, 7, 30};
  const Interval box[6] = {Interval(11, 13), Interval(40), Interval(3), Interval(20), Interval(5, 8), Interval(30)};
  const Interval enclosure = problem.eval(box);
  for (double r : {11.0, 12.0, 13.0})
    for (double b : {5.0, 6.0, 7.0, 8.0}) {
      const double point[6] = {r, 40, 3, 20, b, 30};
      EXPECT_LE(enclosure.lower(), problem.eval(point));
      EXPECT_GE(enclosure.upper(), problem.eval(point));
    }
  double gradient[6];
  EXPECT_NEAR(problem.eval_with_gradient(x, gradient), problem.eval(x), 1e-12);
}

TEST(WangFormat, JointCodeChoiceNeverRaisesABlocksErrorAndReportsTheDecodedError) {
  std::mt19937 rng(8);
  for (int trial = 0; trial < 200; ++trial) {
    test_wang::RandomJointBlock block = test_wang::random_joint_block(rng, 1.0, trial % 2 == 1, 1e-3, 40.0);
    wang::BlockParams& params = block.params;
    const wang::LuminanceBlockError& luminance = block.luminance;
    wang::ResidualBlockError& residual = block.residual;
    wang::decoded_luminance(luminance, params.tex0.alpha, params.tex1.alpha, residual.decoded.data());
    const double sequential = wang::residual_error_with_codes(residual, params.tex1.color);
    const double joint = wang::choose_codes_jointly(luminance, residual, params);
    EXPECT_LE(joint, sequential) << "trial " << trial;
    std::uint8_t packed[wang::kBlockBytes];
    wang::pack_block(params, packed);   // still a valid (canonical-order) block
    wang::decoded_luminance(luminance, params.tex0.alpha, params.tex1.alpha, residual.decoded.data());
    EXPECT_NEAR(wang::residual_error_with_codes(residual, params.tex1.color), joint, 1e-9 * (1.0 + joint));
  }
}

TEST(WangFormat, TwoDxt5DdsFilesReadBackAsBc3AndJoinToTheSameDecodedImage) {
  const Image image = sample_crop();
  const EncodedTexture texture = encode(image, {});
  const std::string dir = ::testing::TempDir();
  wang::write_dxt5_pair(dir + "wang_tex0.dds", dir + "wang_tex1.dds", texture);
  const EncodedTexture tex0 = read_dds(dir + "wang_tex0.dds"), tex1 = read_dds(dir + "wang_tex1.dds");
  EXPECT_EQ(tex0.format, "bc3");
  EXPECT_EQ(tex1.width, image.width);
  EncodedTexture joined = wang::join_dxt5_textures(tex0, tex1, texture.options, texture.side_data, "test");
  joined.channels = texture.channels;
  EXPECT_EQ(joined.blocks, texture.blocks);
  const Format& format = find_format("wang");
  EXPECT_EQ(format.decode(joined, CodecContext{1, 1}).pixels, format.decode(texture, CodecContext{1, 1}).pixels);
  // tex1 alone is an ordinary DXT5 texture: the bc3 decoder reads it.
  EXPECT_NO_THROW(find_format("bc3").decode(tex1, CodecContext{1, 1}));
  EXPECT_THROW(wang::join_dxt5_textures(tex0, texture, texture.options, texture.side_data, "test"), Error);
}

TEST(WangFormat, ZoneSplitsRecordEq2AndTheSolverPathFindsAQuantisationErrorNoWorseOnItsLattice) {
  std::mt19937 rng(7);
  std::lognormal_distribution<double> luminance(0.0, 2.0);
  std::vector<double> values(5000), weights(5000);
  for (std::size_t k = 0; k < values.size(); ++k) {
    values[k] = luminance(rng);
    weights[k] = 1.0 / (values[k] + 1e-3);
  }
  const wang::SplitResult linear = wang::fit_luminance_split(values, weights, wang::SplitSearch{});
  ASSERT_EQ(linear.split.size(), 1u);
  EXPECT_GE(linear.split[0], linear.low);
  EXPECT_LE(linear.split[0], linear.high);
  // Eq. 2 is minimal at the linear answer among every sample value.
  for (std::size_t k = 0; k < values.size(); k += 97) {
    double below = 0, above = 0;
    for (double v : values) (v <= values[k] ? below : above) += 1;
    EXPECT_LE(linear.eq2, (below * (values[k] - linear.low) + above * (linear.high - values[k])) / 256.0 + 1e-9);
  }
  wang::SplitSearch exhaustive;
  exhaustive.solver = "exhaustive";
  const wang::SplitResult solved = wang::fit_luminance_split(values, weights, exhaustive);
  EXPECT_GE(solved.split[0], solved.low);
  EXPECT_LE(solved.split[0], solved.high);
  EXPECT_TRUE(std::isfinite(solved.quantisation));
  EXPECT_LE(solved.quantisation, linear.quantisation * 1.05);   // linear's point is off the lattice by < 1/8192
  const wang::SplitResult residual = wang::fit_residual_split(values, weights, wang::SplitSearch{});
  ASSERT_EQ(residual.split.size(), 2u);
  EXPECT_LE(residual.low, residual.split[0]);
  EXPECT_LE(residual.split[0], residual.split[1]);
  EXPECT_LE(residual.split[1], residual.high);
}

TEST(WangFormat, SolverOptionsRunAndBadOptionsOrSideDataAreClearErrors) {
  const Image image = crop_image(sample_crop(), 0, 0, 8, 8);
  const EncodedTexture texture =
      encode(image, {{"t1_solver", "anneal"}, {"s_solver", "nlopt"}, {"solver", "anneal"},
                     {"solver_options", "iterations=200"}});
  EXPECT_EQ(texture.side_data.count("luminance_zones"), 1u);
  EXPECT_THROW(encode(image, {{"t1_solver", "nonsense"}}), Error);
  const Format& format = find_format("wang");
  EncodedTexture bad = encode(image, {});
  bad.side_data["luminance_zones"] = {1.0, 0.5, 2.0};   // t1 < tmin
  try {
    format.decode(bad, CodecContext{1, 1});
    FAIL() << "unordered zones decoded";
  } catch (const Error& error) {
    EXPECT_NE(std::string(error.what()).find("luminance_zones"), std::string::npos) << error.what();
  }
  bad = encode(image, {});
  bad.side_data.erase("residual_zones");
  EXPECT_THROW(format.decode(bad, CodecContext{1, 1}), Error);
  bad = encode(image, {});
  bad.options["space"] = "xyz";
  try {
    format.decode(bad, CodecContext{1, 1});
    FAIL() << "an unknown colour space decoded";
  } catch (const Error& error) {
    EXPECT_NE(std::string(error.what()).find("space"), std::string::npos) << error.what();
  }
}

}  // namespace
}  // namespace blocklab
