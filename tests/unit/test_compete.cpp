// `compete` (formats/compete/README.md): the family code splits the code space between BC6H's two-region modes and
// the Munkberg modes; Munkberg-family blocks survive pack(unpack(b)); every pattern decodes like the spec-literal oracle
// to finite non-negative texels and every mode occurs; shape II's anchor swap decodes identically (its lossless bit);
// halved fields keep 0 and their maximum; the encoder's reported error is that of its emitted block, the full
// competition equals the best of the single-family ablations, and BC6H-family blocks decode as standard BC6H blocks;
// the Format records block modes, decodes each block as emitted, and gives the same bytes at 1 and 2 threads.
#include <gtest/gtest.h>

#include "test_float_bits.h"

#include <array>
#include <cmath>
#include <random>
#include <set>

#include "core/error.h"
#include "core/image_io.h"
#include "core/input_policy.h"
#include "formats/bc6h/bc6h_decode.h"
#include "formats/bc6h/bc6h_half.h"
#include "formats/compete/compete_block.h"
#include "formats/compete/compete_encoder.h"
#include "formats/compete/compete_layout.h"
#include "formats/compete/compete_reference_decode.h"
#include "formats/munkberg/munkberg_format.h"
#include "formats/registry.h"

namespace blocklab::compete {
namespace {

using Block = std::array<std::uint8_t, kBlockBytes>;

Block random_bytes(std::mt19937_64& random) {
  Block block{};
  for (auto& byte : block) byte = static_cast<std::uint8_t>(random() & 0xFFu);
  return block;
}

Block random_munkberg_family_block(std::mt19937_64& random) {
  Block block = random_bytes(random);
  block[0] |= 3u;
  return block;
}

void expect_same_texels(const BlockTexels& a, const BlockTexels& b, const std::string& context) {
  for (int texel = 0; texel < 16; ++texel)
    for (int c = 0; c < 4; ++c)
      ASSERT_EQ(float_bits(a.rgba[texel][c]), float_bits(b.rgba[texel][c])) << context << " texel " << texel << " c " << c;
}

TEST(CompeteLayout, PackOfUnpackReproducesRandomMunkbergFamilyBlocks) {
  std::mt19937_64 random(11);
  for (int trial = 0; trial < 20000; ++trial) {
    const Block block = random_munkberg_family_block(random);
    std::uint8_t munkberg_block[kBlockBytes];
    unpack_munkberg_block(block.data(), munkberg_block);
    ASSERT_TRUE(representable(munkberg_block));
    ASSERT_EQ(block_mode_of(block.data()), static_cast<int>(munkberg::block_mode_of(munkberg_block)));
    Block repacked{};
    pack_munkberg_block(munkberg_block, repacked.data());
    ASSERT_EQ(repacked, block) << "trial " << trial;
  }
}

TEST(CompeteLayout, PackRejectsAMunkbergBlockOutsideTheBudgetNamingTheBit) {
  std::uint8_t shape_ii[kBlockBytes] = {};   // selector 0 = shape II
  shape_ii[kShape2AnchorBit / 8] |= static_cast<std::uint8_t>(1u << (kShape2AnchorBit % 8));
  EXPECT_FALSE(representable(shape_ii));
  std::uint8_t out[kBlockBytes];
  try {
    pack_munkberg_block(shape_ii, out);
    FAIL() << "expected an Error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("bit 51"), std::string::npos) << e.what();
  }
}

TEST(CompeteLayout, EveryMunkbergModeDropsTwoBitsAndTheFamilyCodeTakesBc6hsOneRegionQuarter) {
  for (int m = 0; m < kMunkbergModeCount; ++m) {
    const MunkbergBudget& budget = munkberg_budget(static_cast<munkberg::BlockMode>(m));
    EXPECT_LT(budget.dropped[0].position, budget.dropped[1].position);
    EXPECT_GE(budget.dropped[0].position, munkberg::kMaxSelectorBits) << "the selector is stored whole";
  }
  // Bits 0, 1 = 1, 1 opens exactly BC6H's one-region and reserved mode numbers (low two bits 3).
  for (int index = 0; index < bc6h::kModeCount; ++index)
    EXPECT_EQ(bc6h::mode_info(index).mode_number % 4 == 3, bc6h::mode_info(index).subset_count == 1);
}

TEST(CompeteDecode, RandomBlocksDecodeLikeTheReferenceDecoderToFiniteValuesAndEveryModeOccurs) {
  std::mt19937_64 random(12);
  const munkberg::ModeContext context;
  std::set<int> modes;
  for (int trial = 0; trial < 20000; ++trial) {
    const Block block = random_bytes(random);
    modes.insert(block_mode_of(block.data()));
    const BlockTexels fast = decode_block(block.data(), context);
    const BlockTexels oracle = reference_decode_block(block.data(), context);
    expect_same_texels(fast, oracle, "trial " + std::to_string(trial));
    for (const auto& texel : fast.rgba)
      for (int c = 0; c < 3; ++c) ASSERT_TRUE(std::isfinite(texel[c]) && texel[c] >= 0.0f);
  }
  EXPECT_EQ(modes.size(), static_cast<std::size_t>(kModeCount));
}

TEST(CompeteDecode, Bc6hFamilyBlocksDecodeAsStandardBc6hBlocks) {
  std::mt19937_64 random(13);
  const munkberg::ModeContext context;
  for (int trial = 0; trial < 2000; ++trial) {
    Block block = random_bytes(random);
    if (is_munkberg_family(block.data())) block[0] &= 0xFEu;
    std::uint16_t halves[16][3];
    bc6h::decode<false>(bc6h::unpack(block.data()), halves);
    const BlockTexels decoded = decode_block(block.data(), context);
    for (int i = 0; i < 16; ++i)
      for (int c = 0; c < 3; ++c) ASSERT_EQ(float_bits(decoded.rgba[i][c]), float_bits(bc6h::half_bits_to_float(halves[i][c])));
    ASSERT_GE(block_mode_of(block.data()), kBc6hFirstMode);
  }
}

// Shape II's lossless bit: Y0 <-> Y1 with every index l -> 15 - l decodes to the same texels.
TEST(CompeteLayout, ShapeIIAnchorSwapDecodesIdentically) {
  std::mt19937_64 random(14);
  const munkberg::ModeContext context;
  const int endpoints = munkberg::lum_endpoint_position(munkberg::Mode::shape_ii);
  const int indices = munkberg::lum_index_position(munkberg::Mode::shape_ii);
  for (int trial = 0; trial < 3000; ++trial) {
    Block block = random_bytes(random);
    block[0] &= 0xFEu;   // shape II
    Block swapped = block;
    // Y0 and Y1 are bytes 4 and 5 (bits 32..47); the indices are nibbles of bytes 6..13 (bits 48..111).
    ASSERT_EQ(endpoints, 32);
    ASSERT_EQ(indices, 48);
    std::swap(swapped[4], swapped[5]);
    for (int b = 6; b < 14; ++b) swapped[static_cast<std::size_t>(b)] = static_cast<std::uint8_t>(~swapped[static_cast<std::size_t>(b)]);
    expect_same_texels(munkberg::decode_any_block(block.data(), context),
                       munkberg::decode_any_block(swapped.data(), context), "trial " + std::to_string(trial));
  }
}

TEST(CompeteLayout, HalvedFieldsStillReachZeroAndTheirMaximum) {
  for (int m = 0; m < kMunkbergModeCount; ++m) {
    const MunkbergBudget& budget = munkberg_budget(static_cast<munkberg::BlockMode>(m));
    for (int h = 0; h < budget.halved_count; ++h) {
      const Field field = budget.halved[static_cast<std::size_t>(h)];
      for (const bool ones : {false, true}) {
        // A Munkberg block of mode m with the field all zeros / all ones is representable (LSB == MSB).
        std::uint8_t munkberg_block[kBlockBytes] = {};
        const munkberg::BlockModeModel& model = munkberg::block_mode_model(static_cast<munkberg::BlockMode>(m));
        munkberg_block[0] = static_cast<std::uint8_t>(model.selector);
        for (int b = 0; b < field.width; ++b) {
          const int k = field.position + b;
          if (ones) munkberg_block[k / 8] |= static_cast<std::uint8_t>(1u << (k % 8));
        }
        EXPECT_TRUE(representable(munkberg_block)) << "mode " << m << " field " << h << (ones ? " max" : " zero");
      }
    }
  }
}

// Sample blocks: every 7th block of the bundled HDR images (a mix of smooth, bright and dark content).
std::vector<BlockTexels> sample_blocks(int limit) {
  std::vector<BlockTexels> blocks;
  for (const char* name : {"hdr/Desk.exr", "hdr/blender_world_sunset.exr"}) {
    const std::string path = std::string(BLOCKLAB_TEST_SAMPLES) + "/" + name;
    Image image = read_image(path);
    apply_input_policy(image, InputPolicy::clamp, path);
    const BlockGrid grid(image.width, image.height);
    for (std::size_t index = 0; index < grid.block_count() && static_cast<int>(blocks.size()) < limit; index += 37)
      blocks.push_back(load_block(image, grid, index));
  }
  return blocks;
}

EncoderSettings settings_with(const std::array<bool, kFamilyCount>& families) {
  EncoderSettings settings;
  settings.bc6h_family = families[static_cast<std::size_t>(Family::bc6h)];
  for (int m = 0; m < kMunkbergModeCount; ++m)
    settings.munkberg_modes[static_cast<std::size_t>(m)] = families[static_cast<std::size_t>(family_of_mode(m))];
  settings.munkberg = munkberg::mode_context_of(
      resolve_format_options(find_format("munkberg"), {{"preset", "fast"}, {"modes", "all"}}));
  for (int index = 0; index < bc6h::kModeCount; ++index)
    settings.bc6h.mode_enabled[index] = bc6h::mode_info(index).subset_count == 2;
  settings.refit_passes = 1;
  settings.good_enough = 0.0;
  return settings;
}

TEST(CompeteEncoder, ReportedErrorIsTheEmittedBlocksAndTheCompetitionIsTheBestOfItsFamilies) {
  const std::vector<BlockTexels> blocks = sample_blocks(40);
  ASSERT_GE(blocks.size(), 20u);
  const EncoderSettings all = settings_with({true, true, true});
  for (std::size_t b = 0; b < blocks.size(); ++b) {
    Block out{};
    const BlockChoice choice = encode_block(blocks[b], all, 1 + b, nullptr, out.data());
    ASSERT_EQ(block_mode_of(out.data()), choice.mode);
    const BlockTexels decoded = decode_block(out.data(), all.munkberg);
    ASSERT_EQ(munkberg::block_log2_error(blocks[b], decoded), choice.error) << "block " << b;
    expect_same_texels(decoded, reference_decode_block(out.data(), all.munkberg), "block " + std::to_string(b));
    double best_single = 1e300;
    for (int f = 0; f < kFamilyCount; ++f) {
      std::array<bool, kFamilyCount> only{};
      only[static_cast<std::size_t>(f)] = true;
      Block single{};
      const BlockChoice alone = encode_block(blocks[b], settings_with(only), 1 + b, nullptr, single.data());
      ASSERT_EQ(static_cast<int>(family_of_mode(alone.mode)), f);
      best_single = std::min(best_single, alone.error);
    }
    EXPECT_EQ(choice.error, best_single) << "block " << b;
  }
}

// The budget's price on real blocks: fitting a Munkberg block into compete never does better than the block itself
// by more than the refit can find, and a shape II block only moves by its one lossy bit.
TEST(CompeteEncoder, FitToBudgetMakesEveryModesBlockRepresentableWithItsReportedError) {
  const std::vector<BlockTexels> blocks = sample_blocks(20);
  const EncoderSettings settings = settings_with({true, true, true});
  for (std::size_t b = 0; b < blocks.size(); ++b)
    for (const munkberg::BlockModeModel& model : munkberg::block_mode_models()) {
      std::uint8_t munkberg_block[kBlockBytes];
      munkberg::BlockScratch scratch;
      model.encode(blocks[b], settings.munkberg, 1 + b, &scratch, munkberg_block);
      const double error = fit_to_budget(munkberg::texel_log2(blocks[b]), settings.munkberg, 1, munkberg_block);
      ASSERT_TRUE(representable(munkberg_block)) << model.name;
      EXPECT_EQ(error, munkberg::block_log2_error(blocks[b], munkberg::decode_any_block(munkberg_block, settings.munkberg)));
      Block packed{};
      pack_munkberg_block(munkberg_block, packed.data());
      EXPECT_EQ(block_mode_of(packed.data()), static_cast<int>(model.mode));
    }
}

TEST(CompeteFormat, RecordsModesDecodesEachBlockAsEmittedAndGivesTheSameBytesAtAnyThreadCount) {
  const Format& format = find_format("compete");
  EXPECT_EQ(format.modes().size(), static_cast<std::size_t>(kModeCount));
  const std::string path = std::string(BLOCKLAB_TEST_SAMPLES) + "/hdr/Desk.exr";
  Image image = read_image(path);
  apply_input_policy(image, InputPolicy::clamp, path);
  Image crop(32, 24, image.channels);
  for (int y = 0; y < crop.height; ++y)
    for (int x = 0; x < crop.width; ++x)
      for (int c = 0; c < 4; ++c) crop.texel(x, y)[c] = image.texel(x + 40, y + 40)[c];
  const FormatOptions options = resolve_format_options(format, {{"preset", "fast"}});
  const EncodedTexture one = format.encode(crop, options, CodecContext{1, 1});
  const EncodedTexture two = format.encode(crop, options, CodecContext{2, 1});
  ASSERT_EQ(one.blocks, two.blocks);
  ASSERT_EQ(one.block_modes, two.block_modes);
  const Image decoded = format.decode(one, CodecContext{2, 1});
  const munkberg::ModeContext context;
  const BlockGrid grid(crop.width, crop.height);
  for (std::size_t b = 0; b < grid.block_count(); ++b) {
    const std::uint8_t* bytes = one.blocks.data() + b * kBlockBytes;
    EXPECT_EQ(one.block_modes[b], block_mode_of(bytes));
    const BlockTexels block = decode_block(bytes, context);
    for (int i = 0; i < 16; ++i) {
      const int x = static_cast<int>(b % static_cast<std::size_t>(grid.blocks_x)) * 4 + i % 4;
      const int y = static_cast<int>(b / static_cast<std::size_t>(grid.blocks_x)) * 4 + i / 4;
      for (int c = 0; c < 3; ++c) ASSERT_EQ(float_bits(decoded.texel(x, y)[c]), float_bits(block.rgba[i][c]));
    }
  }
}

TEST(CompeteFormat, UnknownFamilyIsAnErrorNamingTheOptionAndTheValidFamilies) {
  const Format& format = find_format("compete");
  const Image image(4, 4, 3);
  try {
    format.encode(image, resolve_format_options(format, {{"families", "shape,bc7"}}), CodecContext{1, 1});
    FAIL() << "expected an Error";
  } catch (const Error& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("families"), std::string::npos) << what;
    EXPECT_NE(what.find("bc7"), std::string::npos) << what;
    EXPECT_NE(what.find("section6"), std::string::npos) << what;
    EXPECT_NE(what.find("two_plane"), std::string::npos) << what;
  }
}

// A single Munkberg mode in `families` encodes every block in that mode: compete[families=m] against munkberg[modes=m]
// isolates the price of m's two dropped bits.
TEST(CompeteFormat, ASingleMunkbergModeInFamiliesEncodesEveryBlockInThatMode) {
  const Format& format = find_format("compete");
  Image image(12, 8, 3);
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x)
      for (int c = 0; c < 3; ++c) image.texel(x, y)[c] = 0.01f * static_cast<float>(1 + x * (c + 1) + 7 * y);
  for (const char* mode : {"shape_ii", "ext_s3tc", "dct"}) {
    const EncodedTexture texture =
        format.encode(image, resolve_format_options(format, {{"families", mode}, {"preset", "fast"}}), CodecContext{1, 1});
    for (const std::uint8_t m : texture.block_modes) EXPECT_EQ(format.modes()[m], mode);
  }
}

}  // namespace
}  // namespace blocklab::compete
