// BC7 encoder (formats/bc7): every emitted block decodes identically with the fast and the reference decoder,
// opaque sources keep alpha 255 exactly, translucent blocks use alpha modes, each mode the search can pick gives a
// faithful result, per-channel weights steer the error, presets expand into explicit recorded options, bad options
// are rejected naming the key, thread count does not change the bytes, and the endpoint Problem stays within its
// documented relaxation bound of the exact error; the per-lane endpoint rounding and the lattice polish never
// lose against the plain nearest codes / their input.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <random>

#include "core/error.h"
#include "formats/bc7/bc7_decode.h"
#include "formats/bc7/bc7_endpoint_polish.h"
#include "formats/bc7/bc7_endpoint_problem.h"
#include "formats/bc7/bc7_endpoint_rounding.h"
#include "formats/bc7/bc7_mode_search.h"
#include "formats/bc7/bc7_presets.h"
#include "formats/bc7/bc7_reference_decode.h"
#include "formats/registry.h"

namespace blocklab {
namespace {

const Format& bc7() { return find_format("bc7"); }
FormatOptions options(const FormatOptions& given = {}) { return resolve_format_options(bc7(), given); }

// A smooth image with an edge and some noise (deterministic), values on the 8-bit grid.
Image test_image(int width, int height, int channels, std::uint32_t seed = 5) {
  Image image(width, height, channels);
  std::mt19937 random(seed);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      float* t = image.texel(x, y);
      const float edge = (x + y / 2) % 11 < 5 ? 0.3f : 0.0f;
      t[0] = std::round(255.0f * std::fmod(0.2f + 0.01f * x + edge, 1.0f)) / 255.0f;
      t[1] = std::round(255.0f * std::fmod(0.5f + 0.007f * y, 1.0f)) / 255.0f;
      t[2] = static_cast<float>(100 + 3 * (x % 16) + random() % 16) / 255.0f;   // gradient + mild noise
      t[3] = channels == 4 ? static_cast<float>((x * 9 + y * 5) % 256) / 255.0f : 1.0f;
    }
  return image;
}

double psnr_rgb(const Image& a, const Image& b) {
  double sum = 0.0;
  for (std::size_t i = 0; i < a.texel_count(); ++i)
    for (int c = 0; c < 3; ++c) {
      const double d = 255.0 * (a.pixels[i * 4 + c] - b.pixels[i * 4 + c]);
      sum += d * d;
    }
  return 10.0 * std::log10(255.0 * 255.0 / (sum / (3.0 * a.texel_count())));
}

void expect_reference_agrees(const EncodedTexture& texture) {
  for (std::size_t block = 0; block * 16 < texture.blocks.size(); ++block) {
    const std::uint8_t* bytes = texture.blocks.data() + block * 16;
    std::uint8_t reference[16][4], fast[16][4];
    bc7::reference_decode(bytes, reference);
    bc7::decode(bc7::unpack(bytes), fast);
    ASSERT_EQ(std::memcmp(reference, fast, sizeof fast), 0) << "block " << block;
  }
}

TEST(Bc7Encoder, EveryPresetEmitsBlocksThatBothDecodersAgreeOn) {
  const Image image = test_image(32, 24, 3);
  for (const char* preset : {"fast", "medium", "thorough"}) {
    const EncodedTexture texture = bc7().encode(image, options({{"preset", preset}}), CodecContext{1, 1});
    expect_reference_agrees(texture);
    const Image decoded = bc7().decode(texture, {});
    EXPECT_GT(psnr_rgb(image, decoded), 30.0) << preset;
  }
}

TEST(Bc7Encoder, EachModeAloneEncodesFaithfully) {
  // Forcing one mode at a time exercises every fitting path (partitions, 3 subsets, rotations, index selection).
  const Image image = test_image(16, 16, 3);
  for (int mode = 0; mode < 8; ++mode) {
    const EncodedTexture texture = bc7().encode(
        image, options({{"modes", std::to_string(mode)}, {"rotation_search", "on"}, {"pbit_search", "on"}}), {1, 1});
    for (std::uint8_t used : texture.block_modes) EXPECT_EQ(used, mode);
    expect_reference_agrees(texture);
    EXPECT_GT(psnr_rgb(image, bc7().decode(texture, {})), 24.0) << "mode " << mode;
  }
}

TEST(Bc7Encoder, OpaqueSourcesDecodeWithAlpha255InEveryMode) {
  const Image image = test_image(16, 16, 4);
  Image opaque = image;
  for (std::size_t i = 0; i < opaque.texel_count(); ++i) opaque.pixels[i * 4 + 3] = 1.0f;
  for (int mode = 0; mode < 8; ++mode) {
    const EncodedTexture texture = bc7().encode(opaque, options({{"modes", std::to_string(mode)}}), {1, 1});
    for (std::size_t block = 0; block * 16 < texture.blocks.size(); ++block) {
      std::uint8_t reference[16][4];
      bc7::reference_decode(texture.blocks.data() + block * 16, reference);
      for (int i = 0; i < 16; ++i) ASSERT_EQ(reference[i][3], 255) << "mode " << mode << " block " << block;
    }
  }
}

TEST(Bc7Encoder, TranslucentBlocksUseAlphaModesAndKeepAlpha) {
  const Image image = test_image(16, 16, 4);
  const EncodedTexture texture = bc7().encode(image, options(), {1, 1});
  for (std::uint8_t mode : texture.block_modes) EXPECT_GE(mode, 4);
  const Image decoded = bc7().decode(texture, {});
  double alpha_error = 0.0;
  for (std::size_t i = 0; i < image.texel_count(); ++i)
    alpha_error = std::max(alpha_error, std::fabs(double(image.pixels[i * 4 + 3]) - decoded.pixels[i * 4 + 3]));
  EXPECT_LT(alpha_error, 12.0 / 255.0);
}

TEST(Bc7Encoder, ConstantBlocksAreNearlyExact) {
  for (int value : {0, 1, 77, 128, 254, 255}) {
    std::uint8_t rgba[16][4];
    for (auto& texel : rgba) {
      texel[0] = static_cast<std::uint8_t>(value);
      texel[1] = static_cast<std::uint8_t>(255 - value);
      texel[2] = static_cast<std::uint8_t>(value / 2);
      texel[3] = 255;
    }
    const bc7::EncoderSettings settings;
    const bc7::Params params = bc7::encode_block(rgba, settings);
    EXPECT_LE(bc7::block_error(params, rgba, settings.weights), 16.0 * 3.0) << value;   // <= 1 code per channel
  }
}

TEST(Bc7Encoder, ChannelWeightsShiftErrorAwayFromTheWeightedChannel) {
  const Image image = test_image(32, 32, 3, 11);
  auto channel_mse = [&](const Image& decoded, int c) {
    double sum = 0.0;
    for (std::size_t i = 0; i < image.texel_count(); ++i) {
      const double d = 255.0 * (image.pixels[i * 4 + c] - decoded.pixels[i * 4 + c]);
      sum += d * d;
    }
    return sum / image.texel_count();
  };
  const Image uniform = bc7().decode(bc7().encode(image, options(), {1, 1}), {});
  const Image red_heavy = bc7().decode(bc7().encode(image, options({{"weights", "10,1,1,1"}}), {1, 1}), {});
  EXPECT_LT(channel_mse(red_heavy, 0), channel_mse(uniform, 0));
}

TEST(Bc7Encoder, PresetsExpandIntoExplicitRecordedOptions) {
  const EncodedTexture texture = bc7().encode(test_image(8, 8, 3), options({{"preset", "fast"}}), {1, 1});
  EXPECT_EQ(texture.options.at("preset"), "fast");
  EXPECT_EQ(texture.options.at("modes"), "6");
  EXPECT_EQ(texture.options.at("partitions_to_refine"), "1");
  EXPECT_EQ(texture.options.at("refine_iterations"), "1");
  EXPECT_EQ(texture.options.at("pbit_search"), "off");
  // Explicit knobs win over the preset, and the mode list is canonicalised.
  const FormatOptions expanded =
      bc7::expand_bc7_options(options({{"preset", "thorough"}, {"modes", " 6, 1,1"}, {"refine_iterations", "0"}}));
  EXPECT_EQ(expanded.at("modes"), "1,6");
  EXPECT_EQ(expanded.at("refine_iterations"), "0");
  EXPECT_EQ(expanded.at("partitions_to_refine"), "3");
  EXPECT_EQ(expanded.at("three_subset_threshold"), "200");
  EXPECT_EQ(expanded.at("partition_candidates"), "8");
  // Expansion is idempotent and the expanded map is a valid option map.
  EXPECT_EQ(bc7::expand_bc7_options(resolve_format_options(bc7(), expanded)), expanded);
}

TEST(Bc7Encoder, BadOptionsAreRejectedNamingTheKey) {
  const Image image = test_image(4, 4, 3);
  auto message = [&](const FormatOptions& given) -> std::string {
    try {
      bc7().encode(image, options(given), {1, 1});
    } catch (const Error& error) {
      return error.what();
    }
    return "";
  };
  EXPECT_NE(message({{"modes", "1,9"}}).find("modes"), std::string::npos);
  EXPECT_NE(message({{"modes", ""}}).find("modes"), std::string::npos);
  EXPECT_NE(message({{"alpha_modes", "1"}}).find("alpha_modes"), std::string::npos);
  EXPECT_NE(message({{"weights", "1,1,1"}}).find("weights"), std::string::npos);
  EXPECT_NE(message({{"weights", "1,x,1,1"}}).find("weights"), std::string::npos);
  EXPECT_NE(message({{"weights", "0,0,0,0"}}).find("weights"), std::string::npos);
  EXPECT_NE(message({{"partitions_to_refine", "0"}}).find("partitions_to_refine"), std::string::npos);
  EXPECT_NE(message({{"partition_candidates", "65"}}).find("partition_candidates"), std::string::npos);
  EXPECT_THROW(options({{"solver", "anneal"}}), Error);
  EXPECT_THROW(options({{"preset", "best"}}), Error);
}

TEST(Bc7Encoder, BytesAreIdenticalAtOneTwoAndAllThreads) {
  const Image image = test_image(61, 37, 4);   // not a multiple of 4
  const auto opts = options();
  const EncodedTexture one = bc7().encode(image, opts, CodecContext{1, 1});
  const EncodedTexture two = bc7().encode(image, opts, CodecContext{2, 1});
  const EncodedTexture all = bc7().encode(image, opts, CodecContext{0, 1});
  EXPECT_EQ(one.blocks, two.blocks);
  EXPECT_EQ(one.blocks, all.blocks);
  EXPECT_EQ(one.block_modes, all.block_modes);
  EXPECT_EQ(one.blocks.size(), 16u * 10u * 16u);
  const Image decoded = bc7().decode(one, CodecContext{2, 1});
  EXPECT_EQ(decoded.width, 61);
  EXPECT_EQ(decoded.height, 37);
  EXPECT_EQ(decoded.channels, 4);
}

TEST(Bc7Encoder, NanInputIsRejectedAndHdrValuesClamp) {
  Image image(4, 4, 3);
  image.texel(1, 2)[1] = NAN;
  EXPECT_THROW(bc7().encode(image, options(), {1, 1}), Error);
  Image bright(4, 4, 3);
  for (float& v : bright.pixels) v = 7.5f;
  const Image decoded = bc7().decode(bc7().encode(bright, options(), {1, 1}), {});
  for (std::size_t i = 0; i < decoded.texel_count(); ++i) EXPECT_FLOAT_EQ(decoded.pixels[i * 4], 1.0f);
}

TEST(Bc7Encoder, DecodeRejectsInconsistentTextures) {
  EncodedTexture texture = bc7().encode(test_image(8, 8, 3), options(), {1, 1});
  texture.blocks.pop_back();
  EXPECT_THROW(bc7().decode(texture, {}), Error);
}

TEST(Bc7EndpointProblem, RelaxedErrorAtTheBuiltinFitIsWithinTheRoundingBoundOfTheExactError) {
  // Subset of 16 texels on a noisy line; indices and P-bits fixed from the builtin fit. At the fit's lattice point
  // the Problem's relaxed error is within the relaxation bound of the exact (decoder) error, and the Jet value
  // equals the double value.
  float texels[16][4];
  std::mt19937 random(2);
  for (int i = 0; i < 16; ++i) {
    const float t = i / 15.0f;
    texels[i][0] = 20 + 200 * t + random() % 5;
    texels[i][1] = 90 + 60 * t + random() % 5;
    texels[i][2] = 200 - 150 * t + random() % 5;
    texels[i][3] = 255;
  }
  bc7::SubsetFitSettings settings;
  settings.index_bits = 4;
  settings.lattice.lane_bits[0] = settings.lattice.lane_bits[1] = settings.lattice.lane_bits[2] = 7;
  settings.lattice.pbit = bc7::PbitKind::per_endpoint;
  settings.weights[3] = 0.0f;
  const bc7::SubsetFit fit = bc7::fit_subset(texels, 16, settings);
  const std::uint8_t pbits[2] = {fit.endpoints.pbits[0], fit.endpoints.pbits[1]};
  const auto problem = bc7::make_subset_endpoint_problem(texels, 16, settings, fit.indices, pbits);
  ASSERT_EQ(problem.dim(), 8);
  double x[8];
  for (int e = 0; e < 2; ++e)
    for (int lane = 0; lane < 4; ++lane) x[e * 4 + lane] = fit.endpoints.codes[e][lane];
  const double relaxed = problem.eval(x);
  // The relaxation (linear expansion, no rounding) differs from the exact decode by < 1 code value per channel:
  // |sqrt(relaxed) - sqrt(exact)| <= sqrt(16 texels * 3 lanes) * 1.
  EXPECT_LT(std::fabs(std::sqrt(relaxed) - std::sqrt(fit.error)), std::sqrt(48.0) + 1e-9);
  double gradient[8];
  EXPECT_NEAR(problem.eval_with_gradient(x, gradient), relaxed, 1e-9 * (1 + relaxed));
  EXPECT_EQ(problem.residual_count(), 64);
  EXPECT_TRUE(problem.has_full_lattice());
}

}  // namespace
}  // namespace blocklab

namespace blocklab {
namespace {

// Noisy texels around a colour line (deterministic), 8-bit values, alpha 255.
void noisy_line_texels(std::uint32_t seed, int count, float (&texels)[16][4]) {
  std::mt19937 random(seed);
  for (int i = 0; i < count; ++i) {
    const float t = static_cast<float>(random() % 64) / 63.0f;
    texels[i][0] = std::round(30 + 180 * t) + static_cast<float>(random() % 9);
    texels[i][1] = std::round(200 - 120 * t) + static_cast<float>(random() % 9);
    texels[i][2] = std::round(60 + 40 * t) + static_cast<float>(random() % 9);
    texels[i][3] = 255;
  }
}

// Mode 1's subset lattice (6-bit RGB, shared P-bit, 3-bit indices), alpha not stored.
bc7::SubsetFitSettings mode1_settings() {
  bc7::SubsetFitSettings settings;
  settings.index_bits = 3;
  settings.lattice.lane_bits[0] = settings.lattice.lane_bits[1] = settings.lattice.lane_bits[2] = 6;
  settings.lattice.pbit = bc7::PbitKind::shared;
  settings.weights[3] = 0.0f;
  return settings;
}

// The exact weighted error of `indices` with `endpoints` (decoder interpolation), lanes 0-2.
float error_for_indices(const float (&texels)[16][4], int count, const bc7::QuantisedEndpoints& endpoints,
                        const std::uint8_t* indices, int index_bits) {
  float total = 0.0f;
  for (int i = 0; i < count; ++i)
    for (int lane = 0; lane < 3; ++lane) {
      const int value = bc7::interpolate(endpoints.expanded[0][lane], endpoints.expanded[1][lane],
                                         bc7::index_weights(index_bits)[indices[i]]);
      total += (texels[i][lane] - value) * (texels[i][lane] - value);
    }
  return total;
}

TEST(Bc7EndpointRounding, PerLaneRoundingIsNeverWorseThanNearestCodesForTheSameIndices) {
  const bc7::SubsetFitSettings settings = mode1_settings();
  for (std::uint32_t seed = 1; seed <= 200; ++seed) {
    float texels[16][4];
    noisy_line_texels(seed, 9, texels);
    const bc7::SubsetFit fit = bc7::fit_subset(texels, 9, settings);
    float ideal[2][4];
    if (!bc7::least_squares_endpoints(texels, 9, fit.indices, settings.index_bits, ideal)) continue;
    float rounded_error = 0.0f;
    const bc7::QuantisedEndpoints rounded = bc7::round_endpoints_for_indices(
        texels, 9, fit.indices, settings.index_bits, ideal, settings.lattice, settings.weights, true, &rounded_error);
    EXPECT_EQ(rounded_error, error_for_indices(texels, 9, rounded, fit.indices, settings.index_bits)) << seed;
    for (int pbit = 0; pbit < 2; ++pbit) {
      const bc7::QuantisedEndpoints nearest = bc7::quantise_endpoints(ideal, settings.lattice, pbit, pbit);
      EXPECT_LE(rounded_error, error_for_indices(texels, 9, nearest, fit.indices, settings.index_bits)) << seed;
    }
  }
}

TEST(Bc7EndpointPolish, PolishNeverIncreasesTheErrorAndReportsTheExactErrorOfItsIndices) {
  const bc7::SubsetFitSettings settings = mode1_settings();
  int improved = 0;
  for (std::uint32_t seed = 1; seed <= 200; ++seed) {
    float texels[16][4];
    noisy_line_texels(seed, 8, texels);
    bc7::SubsetFit fit = bc7::fit_subset(texels, 8, settings);
    const float before = fit.error;
    bc7::polish_endpoints(texels, 8, settings.index_bits, settings.lattice, settings.weights, 4, fit.endpoints,
                          fit.indices, fit.error);
    EXPECT_LE(fit.error, before) << seed;
    EXPECT_EQ(fit.error, error_for_indices(texels, 8, fit.endpoints, fit.indices, settings.index_bits)) << seed;
    if (fit.error < before) ++improved;
  }
  EXPECT_GT(improved, 0);   // the polish does find better lattice points on some of these subsets
}

}  // namespace
}  // namespace blocklab
