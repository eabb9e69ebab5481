// BC6H block layer (formats/bc6h): the transcribed layouts cover the spec's header bits exactly, pack/unpack round
// trips, the fast decoder equals the spec-literal oracle in every mode for UF16 and SF16, reserved modes decode to 0,
// and the unquantisation edge cases of the KDFS pseudocode.
#include <gtest/gtest.h>

#include <cstring>
#include <random>
#include <set>

#include "formats/bc6h/bc6h_decode.h"
#include "formats/bc6h/bc6h_params.h"
#include "formats/bc6h/bc6h_reference_decode.h"
#include "formats/bc6h/bc6h_tables.h"

namespace blocklab {
namespace {

using namespace bc6h;

TEST(Bc6hTables, EveryModeLayoutFillsTheHeaderBitsAndEachFieldBitExactlyOnce) {
  for (int index = 0; index < kModeCount; ++index) {
    const ModeInfo& mode = mode_info(index);
    int total = mode.mode_bits;
    std::set<std::pair<int, int>> seen;   // (field, bit)
    for (int r = 0; r < mode.run_count; ++r) {
      const LayoutRun& run = mode.runs[r];
      total += run.count;
      for (int i = 0; i < run.count; ++i) {
        const int bit = run.reversed ? run.first_bit - i : run.first_bit + i;
        EXPECT_TRUE(seen.insert({run.field, bit}).second) << "mode " << mode.mode_number << " field " << int(run.field);
      }
    }
    EXPECT_EQ(total, index_start_bit(mode.subset_count)) << "mode " << mode.mode_number;
    const int fields = mode.subset_count == 2 ? 12 : 6;
    for (int field = 0; field < fields; ++field)
      for (int bit = 0; bit < field_bits(mode, field); ++bit)
        EXPECT_TRUE(seen.count({field, bit})) << "mode " << mode.mode_number << " field " << field << " bit " << bit;
    if (mode.subset_count == 2) {
      for (int bit = 0; bit < 5; ++bit) EXPECT_TRUE(seen.count({kPartitionField, bit}));
    }
    // Total bits: header + 46 (two subsets) or 63 (one subset) index bits = 128.
    EXPECT_EQ(total + 16 * index_bits(mode.subset_count) - mode.subset_count, 128);
  }
}

TEST(Bc6hTables, ModeNumbersMapToTheirRowsAndReservedNumbersToNone) {
  for (int index = 0; index < kModeCount; ++index)
    EXPECT_EQ(mode_index_of_number(mode_info(index).mode_number), index);
  for (int reserved : {19, 23, 27, 31}) EXPECT_EQ(mode_index_of_number(reserved), kReservedModeIndex);
}

TEST(Bc6hTables, UnquantizeFollowsTheSpecPseudocodeAtItsEdges) {
  EXPECT_EQ(unquantize(0, 10, false), 0);
  EXPECT_EQ(unquantize(1023, 10, false), 0xFFFF);
  EXPECT_EQ(unquantize(1, 10, false), ((1 << 15) + 0x4000) >> 9);
  EXPECT_EQ(unquantize(40000, 16, false), 40000);   // EPB >= 15: as stored
  EXPECT_EQ(unquantize(511, 10, true), 0x7FFF);     // saturates at 2^(EPB-1) - 1
  EXPECT_EQ(unquantize(-511, 10, true), -0x7FFF);
  EXPECT_EQ(unquantize(-3, 10, true), -(((3 << 15) + 0x4000) >> 9));
  EXPECT_EQ(unquantize(-32768, 16, true), -32768);
  EXPECT_EQ(finish_unquantize(0xFFFF, false), 0x7BFF);   // 65504
  EXPECT_EQ(finish_unquantize(-0x7FFF, true), 0xFBFF);   // -65504
  EXPECT_EQ(finish_unquantize(-0x8000, true), 0xFC00);   // the "accidental" -infinity
}

// Both decoders give `expected` half bits for every texel and channel of `bytes`.
void expect_both_decoders_give(const std::uint8_t* bytes, bool is_signed, std::uint16_t expected) {
  std::uint16_t fast[16][3], oracle[16][3];
  decode(unpack(bytes), is_signed, fast);
  reference_decode(bytes, is_signed, oracle);
  for (int t = 0; t < 16; ++t)
    for (int c = 0; c < 3; ++c) {
      EXPECT_EQ(fast[t][c], expected);
      EXPECT_EQ(oracle[t][c], expected);
    }
}

TEST(Bc6hBlock, Mode3WithBothEndpointsAtTheTopCodeDecodesTo65504Everywhere) {
  Params params;
  params.mode_index = mode_index_of_number(3);
  for (int c = 0; c < 6; ++c) params.fields[c] = 1023;
  std::uint8_t bytes[16];
  pack(params, bytes);
  EXPECT_EQ(bytes[0] & 31, 3);
  expect_both_decoders_give(bytes, false, 0x7BFF);
}

Params random_params(std::mt19937_64& random, int mode_index) {
  const ModeInfo& mode = mode_info(mode_index);
  Params params;
  params.mode_index = mode_index;
  params.partition = mode.subset_count == 2 ? static_cast<int>(random() % 32) : 0;
  for (int field = 0; field < (mode.subset_count == 2 ? 12 : 6); ++field)
    params.fields[field] = static_cast<int>(random() & ((1u << field_bits(mode, field)) - 1));
  const int width = index_bits(mode.subset_count);
  for (int texel = 0; texel < kTexels; ++texel) {
    const int stored = width - (is_anchor(mode.subset_count, params.partition, texel) ? 1 : 0);
    params.indices[texel] = static_cast<std::uint8_t>(random() & ((1u << stored) - 1));
  }
  return params;
}

TEST(Bc6hBlock, PackThenUnpackGivesTheSameParamsInEveryMode) {
  std::mt19937_64 random(11);
  for (int index = 0; index < kModeCount; ++index)
    for (int trial = 0; trial < 500; ++trial) {
      const Params params = random_params(random, index);
      std::uint8_t bytes[16];
      pack(params, bytes);
      const Params back = unpack(bytes);
      ASSERT_EQ(back.mode_index, params.mode_index);
      EXPECT_EQ(back.partition, params.partition);
      for (int f = 0; f < 12; ++f) EXPECT_EQ(back.fields[f], params.fields[f]) << "mode index " << index << " field " << f;
      for (int t = 0; t < 16; ++t) EXPECT_EQ(back.indices[t], params.indices[t]);
    }
}

// Random bytes with the low mode bits set to `mode_number` (2 bits for modes 0 and 1, else 5).
void random_block_of_mode(std::mt19937_64& random, int mode_number, std::uint8_t (&bytes)[16]) {
  for (auto& byte : bytes) byte = static_cast<std::uint8_t>(random());
  const int mask = mode_number < 2 ? 3 : 31;
  bytes[0] = static_cast<std::uint8_t>((bytes[0] & ~mask) | mode_number);
}

TEST(Bc6hBlock, FastDecoderEqualsTheSpecLiteralOracleInEveryModeUnsignedAndSigned) {
  std::mt19937_64 random(5);
  for (int index = 0; index < kModeCount; ++index)
    for (int trial = 0; trial < 2000; ++trial) {
      const ModeInfo& mode = mode_info(index);
      std::uint8_t bytes[16];
      random_block_of_mode(random, mode.mode_number, bytes);
      for (const bool is_signed : {false, true}) {
        std::uint16_t fast[16][3], oracle[16][3];
        decode(unpack(bytes), is_signed, fast);
        reference_decode(bytes, is_signed, oracle);
        ASSERT_EQ(std::memcmp(fast, oracle, sizeof fast), 0)
            << "mode " << mode.mode_number << (is_signed ? " SF16" : " UF16") << " trial " << trial;
      }
    }
}

TEST(Bc6hBlock, ReservedModesDecodeToZeroInBothDecoders) {
  std::mt19937_64 random(3);
  for (const int reserved : {19, 23, 27, 31})
    for (int trial = 0; trial < 50; ++trial) {
      std::uint8_t bytes[16];
      random_block_of_mode(random, reserved, bytes);
      for (const bool is_signed : {false, true}) expect_both_decoders_give(bytes, is_signed, 0);
    }
}

}  // namespace
}  // namespace blocklab
