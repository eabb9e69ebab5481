// BC6H encoder (formats/bc6h): every block it writes decodes (fast decoder and oracle alike) to the error it reports,
// flat blocks come back nearly exact, each preset is no worse in mPSNR than the faster one on real HDR crops, each
// error choice leads the search to a different block that it scores best, the bytes do not
// depend on the thread count, presets expand to explicit options, bad options are refused naming the key, the DDS
// writer and reader carry BC6H as dxgiFormat 95 / 96, and the one-region endpoint Problem agrees with the real
// decoder within its documented relaxation.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <random>

#include "core/error.h"
#include "core/image_io.h"
#include "core/input_policy.h"
#include "formats/bc6h/bc6h_decode.h"
#include "formats/bc6h/bc6h_endpoint_problem.h"
#include "formats/bc6h/bc6h_half.h"
#include "formats/bc6h/bc6h_mode_search.h"
#include "formats/bc6h/bc6h_presets.h"
#include "formats/bc6h/bc6h_reference_decode.h"
#include "formats/common/dds.h"
#include "formats/common/hdr_block_error.h"
#include "formats/registry.h"
#include "metrics/metric.h"

namespace blocklab {
namespace {

Image sample_crop(const char* file, int size = 64) {
  const std::string path = std::string(BLOCKLAB_TEST_SAMPLES) + "/" + file;
  Image image = read_image(path);
  apply_input_policy(image, InputPolicy::clamp, path);
  return crop_image(image, 0, 0, std::min(image.width, size), std::min(image.height, size));
}

// The error the encoder's search minimises (bc6h_endpoint_fit.h) of decoded halves against a block target.
double search_error(const bc6h::BlockTarget& target, const std::uint16_t (&decoded)[16][3]) {
  double error = 0.0;
  for (int t = 0; t < 16; ++t)
    for (int c = 0; c < 3; ++c) {
      const int half = bc6h::signed_magnitude(decoded[t][c]);
      if (target.error == HdrBlockError::mpsnr_weighted) {
        error += mpsnr_stop_error(bc6h::gamma_domain(half), bc6h::gamma_domain_unclamped_stops(half),
                                  target.source_error_value[t][c], target.source_unclamped[t][c]);
        continue;
      }
      const double d = bc6h::error_domain(target.error, half) - target.source_error_value[t][c];
      error += target.error_weight[t][c] * d * d;
    }
  return error;
}

TEST(Bc6hEncoder, EveryEncodedBlockDecodesToTheErrorTheEncoderReportsUnderEveryErrorChoice) {
  std::mt19937 random(9);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  bc6h::EncoderSettings settings;
  for (bool& enabled : settings.mode_enabled) enabled = true;
  settings.partitions_to_refine = 4;
  for (const auto& [error_name, error_choice] : hdr_block_error_choices())
    for (const bool is_signed : {false, true})
      for (int trial = 0; trial < 150; ++trial) {
        float texels[16][4];
        const float scale = std::exp2(unit(random) * 20.0f - 10.0f);
        for (auto& texel : texels)
          for (int c = 0; c < 4; ++c)
            texel[c] = trial % 5 == 0 && unit(random) < 0.2f
                           ? 0.0f
                           : scale * unit(random) * (trial % 2 ? 1.0f : 100.0f * unit(random));
        const bc6h::BlockTarget target = bc6h::make_block_target(texels, is_signed, error_choice);
        const bc6h::EncodedBlock encoded = bc6h::encode_block(target, settings);
        std::uint8_t bytes[16];
        bc6h::pack(encoded.params, bytes);
        std::uint16_t fast[16][3], oracle[16][3];
        bc6h::decode(bc6h::unpack(bytes), is_signed, fast);
        bc6h::reference_decode(bytes, is_signed, oracle);
        ASSERT_EQ(std::memcmp(fast, oracle, sizeof fast), 0);
        const double error = search_error(target, fast);
        EXPECT_NEAR(error, encoded.error, 1e-9 * (1.0 + error)) << error_name << " trial " << trial;
      }
}

// A block whose error choices disagree: a smooth gradient over one octave (2^-4 .. 2^-3, tinted) with exact zeros in
// R on two texels. log2_floor pays for the zeros (floored at 2^-24, 20 octaves below their neighbours), log2_skip
// ignores them, and mpsnr_weighted weighs differences of x^(1/2.2) by the exposures that see them.
Image disagreement_block() {
  Image image(4, 4, 4);
  for (int i = 0; i < 16; ++i) {
    float* texel = &image.pixels[static_cast<std::size_t>(i) * 4];
    const int x = i % 4, y = i / 4;
    const float level = std::exp2(-4.0f + static_cast<float>(x + y) / 6.0f);
    texel[0] = i == 5 || i == 10 ? 0.0f : level * (1.2f - 0.1f * static_cast<float>(y));
    texel[1] = level * (0.8f + 0.1f * static_cast<float>(x));
    texel[2] = level * (0.5f + 0.05f * static_cast<float>(x * y));
  }
  return image;
}

TEST(Bc6hEncoder, EachErrorChoiceLeadsTheSearchToABlockItScoresBestOnABlockWhereTheChoicesDisagree) {
  const Image image = disagreement_block();
  float texels[16][4];
  std::memcpy(texels, image.pixels.data(), sizeof texels);
  const Format& format = find_format("bc6h");
  const auto& choices = hdr_block_error_choices();
  std::vector<bc6h::BlockTarget> targets;
  std::vector<std::vector<std::uint8_t>> bytes;
  std::vector<bc6h::EncodedBlock> encoded;
  for (const auto& [name, error] : choices) {
    targets.push_back(bc6h::make_block_target(texels, false, error));
    // The default preset's search with this error.
    const FormatOptions options = bc6h::expand_bc6h_options(resolve_format_options(format, {{"error", name}}), "test");
    const bc6h::EncoderSettings settings = bc6h::encoder_settings(options, "test");
    EXPECT_EQ(settings.error, error);
    encoded.push_back(bc6h::encode_block(targets.back(), settings));
    bytes.emplace_back(16);
    bc6h::pack(encoded.back().params, bytes.back().data());
  }
  // The format's option reaches the search: the same bytes through the registry.
  for (std::size_t i = 0; i < choices.size(); ++i) {
    const FormatOptions options = resolve_format_options(format, {{"error", choices[i].first}});
    EXPECT_EQ(format.encode(image, options, CodecContext{1, 1}).blocks, bytes[i]) << choices[i].first;
  }
  for (std::size_t own = 0; own < choices.size(); ++own)
    for (std::size_t other = 0; other < choices.size(); ++other) {
      if (own == other) continue;
      EXPECT_NE(bytes[own], bytes[other]) << choices[own].first << " vs " << choices[other].first;
      std::uint16_t decoded[16][3];
      bc6h::decode(encoded[other].params, false, decoded);
      EXPECT_LT(encoded[own].error, search_error(targets[own], decoded))
          << choices[own].first << "'s block against " << choices[other].first << "'s";
    }
}

TEST(Bc6hEncoder, FlatBlocksComeBackWithinTheirEndpointPrecisionInEveryOneSubsetMode) {
  for (const bool is_signed : {false, true})
    for (const float value : {0.0f, 1e-4f, 0.18f, 1.0f, 37.5f, 2000.0f, 60000.0f}) {
      float texels[16][4];
      for (auto& texel : texels) texel[0] = texel[1] = texel[2] = texel[3] = value;
      const bc6h::BlockTarget target = bc6h::make_block_target(texels, is_signed);
      for (const int mode_number : {3, 7, 11, 15}) {
        const bc6h::EncodedBlock encoded =
            bc6h::encode_in_mode(target, bc6h::mode_index_of_number(mode_number), 0, 1);
        std::uint16_t decoded[16][3];
        bc6h::decode(encoded.params, is_signed, decoded);
        // 16-bit endpoints (mode 15) are exact; fewer bits land within the step of their unquantised lattice.
        const int tolerance = mode_number == 15 ? 1 : (is_signed ? 64 : 32);
        for (int t = 0; t < 16; ++t)
          for (int c = 0; c < 3; ++c)
            EXPECT_LE(std::abs(bc6h::signed_magnitude(decoded[t][c]) - target.half[t][c]), tolerance)
                << value << " mode " << mode_number << (is_signed ? " SF16" : " UF16");
      }
    }
}

// The presets minimise error=mpsnr_weighted, so a slower preset must not lose mPSNR.
TEST(Bc6hEncoder, SlowerPresetsAreNeverWorseInMpsnrOnTheBundledHdrCrops) {
  for (const char* name : {"bc6h", "bc6h_sf"}) {
    const Format& format = find_format(name);
    for (const char* file : {"hdr/Desk.exr", "hdr/hdr-rgb-arboretum.hdr", "hdr/blender_world_sunset.exr"}) {
      const Image image = sample_crop(file, 32);
      double previous = -INFINITY;
      for (const char* preset : {"fast", "medium", "thorough"}) {
        const EncodedTexture texture =
            format.encode(image, resolve_format_options(format, {{"preset", preset}}), CodecContext{2, 1});
        const double mpsnr = find_metric("mpsnr").compute(image, format.decode(texture, CodecContext{2, 1}), {}).value;
        EXPECT_GE(mpsnr, previous) << name << " " << file << " " << preset;
        previous = mpsnr;
      }
    }
  }
}

TEST(Bc6hEncoder, BytesAreIdenticalAtOneAndFourThreads) {
  const Image image = sample_crop("hdr/Desk.exr", 61);   // not a multiple of 4: padded edge blocks too
  for (const char* name : {"bc6h", "bc6h_sf"}) {
    const Format& format = find_format(name);
    const FormatOptions options = resolve_format_options(format, {});
    const EncodedTexture one = format.encode(image, options, CodecContext{1, 1});
    const EncodedTexture four = format.encode(image, options, CodecContext{4, 1});
    EXPECT_EQ(one.blocks, four.blocks) << name;
    EXPECT_EQ(one.block_modes, four.block_modes) << name;
  }
}

TEST(Bc6hEncoder, PresetsExpandToExplicitOptionsAndBadModesAreRefusedNamingTheKey) {
  const Format& format = find_format("bc6h");
  const FormatOptions fast = resolve_format_options(format, {{"preset", "fast"}});
  EXPECT_EQ(fast.at("partitions_to_refine"), "1");
  const EncodedTexture texture = format.encode(sample_crop("hdr/Desk.exr", 8), fast, CodecContext{1, 1});
  EXPECT_EQ(texture.options.at("modes"), "1,14,3,7,11,15");   // canonical: table order
  for (const char* bad : {"19", "3,", "x", "", "4"}) {
    try {
      format.encode(sample_crop("hdr/Desk.exr", 8), resolve_format_options(format, {{"modes", bad}}),
                    CodecContext{1, 1});
      ADD_FAILURE() << "modes=" << bad << " accepted";
    } catch (const Error& error) {
      EXPECT_NE(std::string(error.what()).find("modes"), std::string::npos) << error.what();
    }
  }
}

TEST(Bc6hEncoder, DdsCarriesBc6hAsDxgiFormat95And96AndReadsBackTheSameBlocks) {
  const Image image = sample_crop("hdr/blender_world_sunset.exr", 13);
  for (const auto& [name, dxgi] : {std::pair<const char*, std::uint32_t>{"bc6h", 95}, {"bc6h_sf", 96}}) {
    const Format& format = find_format(name);
    const EncodedTexture texture = format.encode(image, resolve_format_options(format, {}), CodecContext{1, 1});
    ASSERT_EQ(format.gpu_textures(texture).size(), 1u);
    const std::vector<std::uint8_t> bytes = dds_bytes(texture, "test");
    std::uint32_t stored = 0;
    std::memcpy(&stored, bytes.data() + 128, 4);
    EXPECT_EQ(stored, dxgi) << name;
    const EncodedTexture back = parse_dds(bytes, "test");
    EXPECT_EQ(back.format, name);
    EXPECT_EQ(back.channels, 3);
    EXPECT_EQ(back.blocks, texture.blocks);
    EXPECT_EQ(format.decode(back, CodecContext{1, 1}).pixels, format.decode(texture, CodecContext{1, 1}).pixels);
  }
}

TEST(Bc6hEncoder, OneRegionProblemIsWithinItsRelaxationOfTheRealDecoderAtTheBuiltinFit) {
  const Image image = sample_crop("hdr/hdr-rgb-arboretum.hdr", 16);
  const BlockGrid grid(image.width, image.height);
  for (const bool is_signed : {false, true})
    for (std::size_t index = 0; index < grid.block_count(); ++index) {
      const BlockTexels block = load_block(image, grid, index);
      const bc6h::BlockTarget target = bc6h::make_block_target(block.rgba, is_signed);
      const bc6h::EncodedBlock fit = bc6h::encode_in_mode(target, bc6h::mode_index_of_number(3), 0, 1);
      const auto problem = bc6h::make_one_region_endpoint_problem(target.half, fit.params.indices, is_signed);
      double x[6];
      for (int p = 0; p < 6; ++p) x[p] = is_signed ? bc6h::sign_extend(fit.params.fields[p], 10) : fit.params.fields[p];
      double residuals[48];
      problem.error().residuals(x, residuals);
      std::uint16_t decoded[16][3];
      bc6h::decode(fit.params, is_signed, decoded);
      for (int t = 0; t < 16; ++t)
        for (int c = 0; c < 3; ++c) {
          const double exact = bc6h::signed_magnitude(decoded[t][c]) - target.half[t][c];
          // Relaxation: the unquantisation offset (<= 32 of 65536), the dropped +32 >> 6 rounding and the final
          // truncation together stay within 2 half steps (the saturated top/bottom codes excepted, see the header).
          const double top = is_signed ? 511 : 1023;
          const bool saturated = x[c] >= top || x[3 + c] >= top || x[c] <= 0 || x[3 + c] <= 0;
          if (!saturated) {
            EXPECT_LE(std::fabs(residuals[t * 3 + c] - exact), 2.0) << "block " << index;
          }
        }
    }
}

}  // namespace
}  // namespace blocklab
