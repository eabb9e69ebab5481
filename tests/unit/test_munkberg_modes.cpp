// `munkberg` plug-in modes (formats/munkberg/munkberg_modes.h; Munkberg et al. 2008, section 6): the selector is a
// complete prefix code and every mode's field widths sum to 128; for every mode pack(unpack(b)) == b on random blocks
// and the decoder equals the spec-literal reference decoder bit for bit; extended S3TC reproduces a block on its own
// line exactly (both spaces) and its anchor swap decodes identically; the two-plane luminance fit recovers two exact
// quantised planes; letting the rejected modes compete never raises a block's error; the `modes` option parses lists
// and names bad tokens; Format::modes() lists every mode in selector order.
#include <gtest/gtest.h>

#include "test_float_bits.h"

#include <ceres/jet.h>

#include <cstring>
#include <random>
#include <set>

#include "core/error.h"
#include "core/interval.h"
#include "formats/munkberg/ext_s3tc_encoder.h"
#include "formats/munkberg/munkberg_modes.h"
#include "formats/munkberg/two_plane_encoder.h"
#include "formats/registry.h"

namespace blocklab::munkberg {
namespace {

void expect_same_texels(const BlockTexels& a, const BlockTexels& b, const std::string& context) {
  for (int texel = 0; texel < 16; ++texel)
    for (int c = 0; c < 4; ++c)
      ASSERT_EQ(float_bits(a.rgba[texel][c]), float_bits(b.rgba[texel][c])) << context << " texel " << texel << " c " << c;
}

// A random block of `mode`: random bytes with the mode's selector written over the first bits.
std::array<std::uint8_t, kBlockBytes> random_block(std::mt19937_64& random, const BlockModeModel& model) {
  std::array<std::uint8_t, kBlockBytes> block{};
  for (auto& byte : block) byte = static_cast<std::uint8_t>(random() & 0xFFu);
  const unsigned keep = ~((1u << model.selector_bits) - 1u) & 0xFFu;
  block[0] = static_cast<std::uint8_t>((block[0] & keep) | model.selector);
  return block;
}

TEST(MunkbergModes, EveryModesFieldWidthsSumTo128AndTheSelectorIsACompletePrefixCode) {
  double kraft = 0.0;
  for (const BlockModeModel& model : block_mode_models()) {
    const std::vector<int> widths = model.field_widths();
    int sum = 0;
    for (const int w : widths) sum += w;
    EXPECT_EQ(sum, kBlockBits) << model.name;
    EXPECT_EQ(widths.front(), model.selector_bits) << model.name;
    kraft += 1.0 / static_cast<double>(1 << model.selector_bits);
    // No selector is a prefix of another.
    for (const BlockModeModel& other : block_mode_models()) {
      if (other.mode == model.mode) continue;
      const int n = std::min(model.selector_bits, other.selector_bits);
      EXPECT_NE(model.selector & ((1u << n) - 1u), other.selector & ((1u << n) - 1u)) << model.name << " / " << other.name;
    }
  }
  EXPECT_EQ(kraft, 1.0);   // complete: every bit pattern is some mode's block
  EXPECT_EQ(kExtS3tcTotalBits, 128);
  EXPECT_EQ(kTwoPlaneTotalBits, 128);
}

TEST(MunkbergModes, PackOfUnpackReproducesRandomBlocksOfEveryMode) {
  std::mt19937_64 random(101);
  for (const BlockModeModel& model : block_mode_models())
    for (int trial = 0; trial < 5000; ++trial) {
      const auto block = random_block(random, model);
      ASSERT_EQ(block_mode_of(block.data()), model.mode) << model.name;
      std::uint8_t packed[kBlockBytes];
      model.repack(block.data(), packed);
      ASSERT_EQ(0, std::memcmp(packed, block.data(), kBlockBytes)) << model.name << " trial " << trial;
    }
}

TEST(MunkbergModes, EveryModeDecodesRandomBlocksLikeItsReferenceDecoderToFiniteValues) {
  std::mt19937_64 random(102);
  for (const ExtS3tcSpace space : {ExtS3tcSpace::rgb, ExtS3tcSpace::logyuv}) {
    ModeContext context;
    context.ext_s3tc_space = space;
    for (const BlockModeModel& model : block_mode_models())
      for (int trial = 0; trial < 3000; ++trial) {
        const auto block = random_block(random, model);
        const BlockTexels fast = decode_any_block(block.data(), context);
        expect_same_texels(fast, model.reference_decode(block.data(), context),
                           std::string(model.name) + " trial " + std::to_string(trial));
        for (int i = 0; i < kTexels; ++i)
          for (int c = 0; c < 3; ++c) {
            ASSERT_TRUE(std::isfinite(fast.rgba[i][c])) << model.name;
            ASSERT_GE(fast.rgba[i][c], 0.0f) << model.name;
          }
      }
  }
}

TEST(MunkbergModes, TemplatedDecodersOfTheRejectedModesWorkWithIntervalsAndJets) {
  std::mt19937_64 random(108);
  using Jet = ceres::Jet<double, 6>;
  for (const ExtS3tcSpace space : {ExtS3tcSpace::rgb, ExtS3tcSpace::logyuv})
    for (int trial = 0; trial < 100; ++trial) {
      const auto block = random_block(random, block_mode_model(BlockMode::ext_s3tc));
      const ExtS3tcParams p = unpack_ext_s3tc(block.data());
      const std::array<double, 6> x = ext_s3tc_parameters(p, space);
      double rgb[kTexels][3];
      Interval rgb_i[kTexels][3];
      Jet rgb_j[kTexels][3];
      Interval xi[6];
      Jet xj[6];
      for (int k = 0; k < 6; ++k) {
        xi[k] = Interval(x[static_cast<std::size_t>(k)]);
        xj[k] = Jet(x[static_cast<std::size_t>(k)], k);
      }
      decode_ext_s3tc(p, space, x.data(), rgb);
      decode_ext_s3tc(p, space, xi, rgb_i);
      decode_ext_s3tc(p, space, xj, rgb_j);
      for (int i = 0; i < kTexels; ++i)
        for (int c = 0; c < 3; ++c) {
          EXPECT_LE(rgb_i[i][c].lower(), rgb[i][c]);
          EXPECT_GE(rgb_i[i][c].upper(), rgb[i][c]);
          EXPECT_NEAR(rgb_j[i][c].a, rgb[i][c], 1e-12 * (1.0 + std::abs(rgb[i][c])));
        }
    }
  for (int trial = 0; trial < 100; ++trial) {
    const auto block = random_block(random, block_mode_model(BlockMode::two_plane));
    const TwoPlaneParams p = unpack_two_plane(block.data());
    double x[4], rgb[kTexels][3];
    Interval xi[4], rgb_i[kTexels][3];
    for (int k = 0; k < 4; ++k) {
      x[k] = base_value(p.base[static_cast<std::size_t>(k)]);
      xi[k] = Interval(x[k]);
    }
    decode_two_plane(p, default_shape_set(), x, rgb);
    decode_two_plane(p, default_shape_set(), xi, rgb_i);
    for (int i = 0; i < kTexels; ++i)
      for (int c = 0; c < 3; ++c) {
        EXPECT_LE(rgb_i[i][c].lower(), rgb[i][c]);
        EXPECT_GE(rgb_i[i][c].upper(), rgb[i][c]);
      }
  }
}

TEST(MunkbergModes, ExtS3tcAnchorSwapDecodesIdentically) {
  std::mt19937_64 random(103);
  for (const ExtS3tcSpace space : {ExtS3tcSpace::rgb, ExtS3tcSpace::logyuv})
    for (int trial = 0; trial < 300; ++trial) {
      ExtS3tcParams p;
      for (auto& e : p.endpoint)
        for (int c = 0; c < 3; ++c) e[static_cast<std::size_t>(c)] = static_cast<int>(random() % (1u << kExtS3tcChannelBits[static_cast<std::size_t>(c)]));
      for (auto& l : p.index) l = static_cast<std::uint8_t>(random() % 32);
      ExtS3tcParams canonical = p;
      canonicalize_ext_s3tc(&canonical);
      EXPECT_LE(canonical.index[0], kExtS3tcAnchorIndexMax);
      expect_same_texels(decode_ext_s3tc_params(p, space), decode_ext_s3tc_params(canonical, space), "anchor");
      std::uint8_t bytes[kBlockBytes];
      pack_ext_s3tc(canonical, bytes);
      EXPECT_EQ(unpack_ext_s3tc(bytes), canonical);
      if (p.index[0] > kExtS3tcAnchorIndexMax) {
        EXPECT_THROW(pack_ext_s3tc(p, bytes), Error);
      }
    }
}

TEST(MunkbergModes, ExtS3tcReproducesABlockOnItsOwnLineExactly) {
  std::mt19937_64 random(104);
  for (const ExtS3tcSpace space : {ExtS3tcSpace::rgb, ExtS3tcSpace::logyuv})
    for (int trial = 0; trial < 40; ++trial) {
      ExtS3tcParams p;
      for (auto& e : p.endpoint) {
        e[0] = 60 + static_cast<int>(random() % 150);   // well inside the range: no clamping, no black
        e[1] = 20 + static_cast<int>(random() % 60);
        e[2] = 20 + static_cast<int>(random() % 40);
      }
      // The line's two ends occur, the rest anywhere on it.
      for (auto& l : p.index) l = static_cast<std::uint8_t>(random() % 32);
      p.index[3] = 0;
      p.index[9] = 31;
      const BlockTexels texels = decode_ext_s3tc_params(p, space);
      ExtS3tcSettings settings;
      settings.space = space;
      double error = -1.0;
      const ExtS3tcParams fit = encode_ext_s3tc(texels, settings, &error);
      EXPECT_EQ(error, 0.0) << "space " << static_cast<int>(space) << " trial " << trial;
      expect_same_texels(decode_ext_s3tc_params(fit, space), texels, "reproduced");
    }
}

TEST(MunkbergModes, TwoPlaneLuminanceFitRecoversTwoExactQuantisedPlanes) {
  std::mt19937_64 random(105);
  for (int trial = 0; trial < 40; ++trial) {
    TwoPlaneParams truth;
    truth.plane[0] = {100 + static_cast<int>(random() % 60), static_cast<int>(random() % 9) - 4, static_cast<int>(random() % 9) - 4};
    truth.plane[1] = {300 + static_cast<int>(random() % 60), static_cast<int>(random() % 9) - 4, static_cast<int>(random() % 9) - 4};
    truth.mask = static_cast<std::uint16_t>(random() & 0xFFFFu);
    double target[kTexels];
    for (int i = 0; i < kTexels; ++i)
      target[i] = plane_log_luminance(truth.plane[static_cast<std::size_t>((truth.mask >> i) & 1u)], i % 4, i / 4);
    TwoPlaneParams fit;
    const double error = fit_two_plane_luminance(target, &fit);
    EXPECT_LT(error, 1e-20) << "trial " << trial;
    for (int i = 0; i < kTexels; ++i) {
      const Plane& p = fit.plane[static_cast<std::size_t>((fit.mask >> i) & 1u)];
      EXPECT_EQ(plane_log_luminance(p, i % 4, i / 4), target[i]) << "trial " << trial << " texel " << i;
    }
  }
}

TEST(MunkbergModes, TwoPlaneReproducesABlockOfTwoPlanesWithOneChromaExactly) {
  std::mt19937_64 random(110);
  const ModeContext context;
  for (int trial = 0; trial < 20; ++trial) {
    TwoPlaneParams p;
    p.plane[0] = {120 + static_cast<int>(random() % 60), static_cast<int>(random() % 13) - 6, static_cast<int>(random() % 13) - 6};
    p.plane[1] = {300 + static_cast<int>(random() % 60), static_cast<int>(random() % 13) - 6, static_cast<int>(random() % 13) - 6};
    p.mask = static_cast<std::uint16_t>(random() & 0xFFFFu);
    const int u = 10 + static_cast<int>(random() % 30), v = 20 + static_cast<int>(random() % 40);
    p.base = {u, v, u, v};   // one chroma: every landmark is (u, v) / 127
    const BlockTexels texels = decode_two_plane_params(p, context.shapes);
    double error = -1.0;
    const TwoPlaneParams fit = encode_two_plane(texels, context.shapes, context.settings, 5 + trial, &error);
    EXPECT_EQ(error, 0.0) << "trial " << trial;
    expect_same_texels(decode_two_plane_params(fit, context.shapes), texels, "trial " + std::to_string(trial));
  }
}

TEST(MunkbergModes, TwoPlaneBlackPlaneDecodesToTrueBlack) {
  TwoPlaneParams p;
  p.plane[0] = {0, 17, -5};   // offset code 0: black whatever the slopes
  p.plane[1] = {255, 0, 0};
  p.mask = 0xFF00u;
  p.base = {14, 38, 14, 38};
  const BlockTexels t = decode_two_plane_params(p, default_shape_set());
  for (int i = 0; i < kTexels; ++i)
    for (int c = 0; c < 3; ++c) {
      if (i < 8) EXPECT_EQ(t.rgba[i][c], 0.0f);
      else EXPECT_GT(t.rgba[i][c], 0.0f);
    }
}

BlockTexels random_hdr_block(std::mt19937_64& random) {
  BlockTexels t;
  std::uniform_real_distribution<double> stops(-6.0, 6.0), tint(0.2, 1.0);
  const double base = stops(random);
  for (int i = 0; i < kTexels; ++i) {
    const double y = std::exp2(base + 0.5 * stops(random) * (i % 3 == 0 ? 1.0 : 0.1));
    for (int c = 0; c < 3; ++c) t.rgba[i][c] = static_cast<float>(y * tint(random));
    t.rgba[i][3] = 1.0f;
  }
  return t;
}

// A block on an extended-S3TC line (trial % 3 == 1), a grey block of two steep luminance planes (trial % 3 == 2),
// or noisy HDR texels.
BlockTexels competition_block(std::mt19937_64& random, int trial) {
  if (trial % 3 == 1) {
    ExtS3tcParams p;
    for (auto& e : p.endpoint) e = {60 + static_cast<int>(random() % 150), 20 + static_cast<int>(random() % 200), 20 + static_cast<int>(random() % 100)};
    for (int i = 0; i < kTexels; ++i) p.index[static_cast<std::size_t>(i)] = static_cast<std::uint8_t>((2 * i + static_cast<int>(random() % 2)) % 32);
    return decode_ext_s3tc_params(p, ExtS3tcSpace::rgb);
  }
  if (trial % 3 == 2) {
    TwoPlaneParams p;
    p.plane[0] = {150 + static_cast<int>(random() % 40), 20 + static_cast<int>(random() % 20), -15};
    p.plane[1] = {320 + static_cast<int>(random() % 40), -25, 20 + static_cast<int>(random() % 20)};
    p.mask = 0xCCCCu;
    p.base = {14, 38, 14, 38};   // grey
    return decode_two_plane_params(p, default_shape_set());
  }
  return random_hdr_block(random);
}

TEST(MunkbergModes, LettingTheRejectedModesCompeteNeverRaisesABlocksError) {
  std::mt19937_64 random(106);
  ModeContext paper, all;
  all.settings.modes.fill(true);
  std::set<BlockMode> winners;
  for (int trial = 0; trial < 30; ++trial) {
    const BlockTexels texels = competition_block(random, trial);
    std::uint8_t a[kBlockBytes], b[kBlockBytes];
    double error_paper = 0.0, error_all = 0.0;
    const BlockMode mode_paper = encode_best_block(texels, paper, 7 + trial, a, &error_paper);
    const BlockMode mode_all = encode_best_block(texels, all, 7 + trial, b, &error_all);
    EXPECT_LE(error_all, error_paper) << "trial " << trial;
    EXPECT_TRUE(mode_paper == BlockMode::shape_ii || mode_paper == BlockMode::shape_i);
    EXPECT_EQ(block_mode_of(b), mode_all);
    // The reported error is the error of the emitted block's decode.
    EXPECT_EQ(error_all, block_log2_error(texels, decode_any_block(b, all)));
    expect_same_texels(decode_any_block(b, all), reference_decode_any_block(b, all), "emitted");
    winners.insert(mode_all);
  }
  // The competition is real: each rejected mode wins the blocks it is made for.
  EXPECT_EQ(winners.count(BlockMode::ext_s3tc), 1u);
  EXPECT_EQ(winners.count(BlockMode::two_plane), 1u);
}

TEST(MunkbergModes, TwoPlaneLowerBoundNeverExceedsTheModesError) {
  std::mt19937_64 random(113);
  ModeContext context;
  int positive = 0;
  for (int trial = 0; trial < 30; ++trial) {
    const BlockTexels texels = competition_block(random, trial);
    const BlockAnalysis analysis = analyse_block(texels);
    TwoPlaneParams planes;
    fit_two_plane_luminance(analysis.log_luminance.data(), &planes);
    const double bound = two_plane_lower_bound(texels, analysis, planes);
    double error = 0.0, error_reusing = 0.0;
    const TwoPlaneParams fresh = encode_two_plane(texels, context.shapes, context.settings, 3, &error);
    const TwoPlaneParams reusing =
        encode_two_plane(texels, context.shapes, context.settings, 3, &error_reusing, nullptr, nullptr, &planes);
    EXPECT_LE(bound, error) << "trial " << trial;
    // The planes handed in are the ones the encoder fits itself: the same block.
    EXPECT_EQ(error_reusing, error) << "trial " << trial;
    EXPECT_EQ(reusing.mask, fresh.mask) << "trial " << trial;
    positive += bound > 0.0 ? 1 : 0;
  }
  EXPECT_GT(positive, 10);   // informative, not a trivial 0
}

TEST(MunkbergModes, ModePredictorOnlyAddsWinnersToTheShapeModesCompetition) {
  // With the predictor the shape modes run first exactly as in the paper's two-mode competition (same order, same
  // good_enough stop), and a section 6 mode replaces their block only with a strictly lower error: never worse than
  // modes=both, and the reported error is the emitted block's.
  std::mt19937_64 random(127);
  for (const double good_enough : {0.0, 2.0}) {
    ModeContext paper, predicted;
    paper.settings.good_enough = predicted.settings.good_enough = good_enough;
    predicted.settings.modes.fill(true);
    predicted.settings.mode_predictor = 0.5;
    int section6_wins = 0;
    for (int trial = 0; trial < 30; ++trial) {
      const BlockTexels texels = competition_block(random, trial);
      std::uint8_t a[kBlockBytes], b[kBlockBytes];
      double error_paper = 0.0, error_predicted = 0.0;
      const BlockMode mode_paper = encode_best_block(texels, paper, 11 + trial, a, &error_paper);
      const BlockMode mode_predicted = encode_best_block(texels, predicted, 11 + trial, b, &error_predicted);
      EXPECT_LE(error_predicted, error_paper) << "trial " << trial;
      EXPECT_EQ(error_predicted, block_log2_error(texels, decode_any_block(b, predicted)));
      if (mode_predicted == mode_paper) {
        EXPECT_EQ(std::memcmp(a, b, kBlockBytes), 0) << "trial " << trial;
      } else {
        EXPECT_LT(error_predicted, error_paper) << "trial " << trial;
        ++section6_wins;
      }
    }
    EXPECT_GT(section6_wins, 0) << "good_enough " << good_enough;   // the predictor lets section 6 modes win
  }
}

TEST(MunkbergModes, TwoPlaneReusingShapeOnesSolvesGivesTheSameBlock) {
  std::mt19937_64 random(109);
  const ModeContext context;
  for (int trial = 0; trial < 12; ++trial) {
    const BlockTexels texels = competition_block(random, trial);
    double fresh_error = 0.0, cached_error = 0.0;
    const TwoPlaneParams fresh = encode_two_plane(texels, context.shapes, context.settings, 11 + trial, &fresh_error);
    ShapeSolveCache cache;
    encode_mode(texels, Mode::shape_i, context.shapes, context.settings, 11 + trial, &cache);
    EXPECT_TRUE(cache.valid);
    const TwoPlaneParams cached =
        encode_two_plane(texels, context.shapes, context.settings, 11 + trial, &cached_error, &cache);
    EXPECT_EQ(fresh, cached) << "trial " << trial;
    EXPECT_EQ(fresh_error, cached_error);
  }
}

TEST(MunkbergModes, ModesOptionParsesListsAndNamesBadTokens) {
  EXPECT_EQ(parse_mode_list("both"), kPaperModes);
  EXPECT_EQ(parse_mode_list("all"), (ModeMask{true, true, true, true, true}));
  EXPECT_EQ(parse_mode_list("shape_i, ext_s3tc"), (ModeMask{false, true, true, false, false}));
  EXPECT_EQ(parse_mode_list("two_plane"), (ModeMask{false, false, false, true, false}));
  EXPECT_EQ(parse_mode_list("dct"), (ModeMask{false, false, false, false, true}));
  try {
    parse_mode_list("shape_i,wavelet");
    ADD_FAILURE() << "accepted wavelet";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("'wavelet'"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("two_plane, dct"), std::string::npos) << e.what();
  }
  EXPECT_THROW(parse_mode_list(""), Error);
  const Format& format = find_format("munkberg");
  EXPECT_EQ(format.modes(), (std::vector<std::string>{"shape_ii", "shape_i", "ext_s3tc", "two_plane", "dct"}));
  Image image(8, 4);
  EXPECT_THROW(format.encode(image, resolve_format_options(format, {{"modes", "bogus"}}), CodecContext{1, 1}), Error);
}

TEST(MunkbergModes, FormatWithEveryModeRecordsModesAndSpaceAndDecodesEachBlockAsEmitted) {
  const Format& format = find_format("munkberg");
  std::mt19937_64 random(107);
  Image image(16, 16);
  for (int by = 0; by < 4; ++by)
    for (int bx = 0; bx < 4; ++bx) {
      const BlockTexels t = random_hdr_block(random);
      for (int i = 0; i < kTexels; ++i)
        for (int c = 0; c < 3; ++c) image.texel(4 * bx + i % 4, 4 * by + i / 4)[c] = t.rgba[i][c];
    }
  for (const char* space : {"rgb", "logyuv"}) {
    const FormatOptions options = resolve_format_options(format, {{"modes", "all"}, {"ext_s3tc_space", space}});
    const EncodedTexture texture = format.encode(image, options, CodecContext{2, 1});
    // Bytes do not depend on the thread count.
    EXPECT_EQ(texture.blocks, format.encode(image, options, CodecContext{1, 1}).blocks);
    ASSERT_EQ(texture.side_data.at(kExtS3tcSpaceKey).size(), 1u);
    ModeContext context;
    context.ext_s3tc_space = ext_s3tc_space_of(texture.side_data);
    EXPECT_EQ(context.ext_s3tc_space == ExtS3tcSpace::logyuv, std::string(space) == "logyuv");
    const Image decoded = format.decode(texture, CodecContext{1, 1});
    for (std::size_t b = 0; b < 16; ++b) {
      const std::uint8_t* bytes = texture.blocks.data() + b * kBlockBytes;
      EXPECT_EQ(texture.block_modes[b], static_cast<int>(block_mode_of(bytes)));
      const BlockTexels t = decode_any_block(bytes, context);
      const int bx = static_cast<int>(b % 4), by = static_cast<int>(b / 4);
      for (int i = 0; i < kTexels; ++i)
        for (int c = 0; c < 3; ++c)
          ASSERT_EQ(float_bits(decoded.texel(4 * bx + i % 4, 4 * by + i / 4)[c]), float_bits(t.rgba[i][c]));
    }
  }
}

}  // namespace
}  // namespace blocklab::munkberg
