// core/bits.h: LSB-first little-endian bit packing of 64- and 128-bit blocks (BCn convention: bit k of a block is
// bit k % 8 of byte k / 8). Random field sequences against a bit-by-bit reference, fields straddling bytes and
// bit 64, known byte patterns, signed fields and every misuse reported as an Error.
#include <gtest/gtest.h>

#include <array>
#include <cstdint>
#include <random>
#include <utility>
#include <vector>

#include "core/bits.h"
#include "core/error.h"

namespace blocklab {
namespace {

struct Field {
  std::uint64_t value;
  int width;
};

std::uint64_t random_value(std::mt19937_64& engine, int width) {
  const std::uint64_t value = engine();
  return width == 64 ? value : value & ((std::uint64_t{1} << width) - 1);
}

// Random widths 0..64 that add up to exactly `total` bits, with random values of those widths.
std::vector<Field> random_fields(std::mt19937_64& engine, int total) {
  std::vector<Field> fields;
  int used = 0;
  while (used < total) {
    const int width = std::uniform_int_distribution<int>(0, std::min(64, total - used))(engine);
    fields.push_back({random_value(engine, width), width});
    used += width;
  }
  return fields;
}

// Independent reference: places each field bit by bit, bit k of the block in bit k % 8 of byte k / 8.
template <std::size_t kBytes>
std::array<std::uint8_t, kBytes> reference_pack(const std::vector<Field>& fields) {
  std::array<std::uint8_t, kBytes> bytes{};
  int position = 0;
  for (const Field& field : fields)
    for (int j = 0; j < field.width; ++j, ++position)
      if ((field.value >> j) & 1u) bytes[position / 8] |= static_cast<std::uint8_t>(1u << (position % 8));
  return bytes;
}

template <int kBits>
void check_random_sequences(std::uint64_t seed) {
  std::mt19937_64 engine(seed);
  for (int trial = 0; trial < 20000; ++trial) {
    const std::vector<Field> fields = random_fields(engine, kBits);
    BitWriter<kBits> writer;
    for (const Field& field : fields) writer.write(field.value, field.width);
    ASSERT_TRUE(writer.full());
    const auto bytes = writer.bytes();
    ASSERT_EQ(bytes, reference_pack<kBits / 8>(fields)) << "trial " << trial;
    BitReader<kBits> reader(bytes);
    for (const Field& field : fields) ASSERT_EQ(reader.read(field.width), field.value) << "trial " << trial;
    ASSERT_EQ(reader.remaining(), 0);
  }
}

TEST(BitPacking, RandomFieldSequencesFilling64BitsRoundTripAndMatchTheBitByBitLayout) {
  check_random_sequences<64>(64);
}

TEST(BitPacking, RandomFieldSequencesFilling128BitsRoundTripAndMatchTheBitByBitLayout) {
  check_random_sequences<128>(128);
}

TEST(BitPacking, FieldsStraddlingBit64RoundTripAtEveryOffsetAndWidth) {
  std::mt19937_64 engine(6464);
  for (int width = 1; width <= 64; ++width)
    for (int position = std::max(0, 65 - width); position < 64; ++position) {   // every field covering bits 63, 64
      const std::uint64_t value = random_value(engine, width);
      BitWriter128 writer;
      writer.write(0, position);   // width 0..63 zero padding before the field
      writer.write(value, width);
      const auto bytes = writer.bytes();
      ASSERT_EQ(bytes, (reference_pack<16>({{0, position}, {value, width}}))) << position << "+" << width;
      BitReader128 reader(bytes);
      reader.seek(position);
      ASSERT_EQ(reader.read(width), value) << position << "+" << width;
      ASSERT_EQ(BitBlock128::from_bytes(bytes.data()).get(position, width), value);
    }
}

TEST(BitPacking, Full64BitFieldsFillBothHalvesOfA128BitBlock) {
  BitWriter128 writer;
  writer.write(0x0123456789ABCDEFull, 64);
  writer.write(0xFEDCBA9876543210ull, 64);
  const std::array<std::uint8_t, 16> expected = {0xEF, 0xCD, 0xAB, 0x89, 0x67, 0x45, 0x23, 0x01,
                                                 0x10, 0x32, 0x54, 0x76, 0x98, 0xBA, 0xDC, 0xFE};
  EXPECT_EQ(writer.bytes(), expected);
}

TEST(BitPacking, Bc1StyleBlockHasTheKnownLittleEndianBytes) {
  // BC1: c0 (u16), c1 (u16), then 2-bit codes for texels 0..15 (code(i) = bits 2i+1..2i of the index word).
  BitWriter64 writer;
  writer.write(0xF800, 16);   // c0 = pure red in RGB565
  writer.write(0x001F, 16);   // c1 = pure blue
  for (int texel = 0; texel < 16; ++texel) writer.write(static_cast<std::uint64_t>(texel % 4), 2);
  const std::array<std::uint8_t, 8> expected = {0x00, 0xF8, 0x1F, 0x00, 0xE4, 0xE4, 0xE4, 0xE4};
  EXPECT_EQ(writer.bytes(), expected);
}

TEST(BitPacking, Bc7ModeIsTheNumberOfTrailingZeroBitsOfByte0) {
  // BC7 mode 6: six 0 bits then a 1 -> byte 0 = 0x40.
  BitWriter128 writer;
  writer.write(0, 6);
  writer.write(1, 1);
  EXPECT_EQ(writer.bytes()[0], 0x40);
  EXPECT_EQ(writer.position(), 7);
  EXPECT_EQ(writer.remaining(), 121);
}

TEST(BitPacking, FieldAcrossAByteBoundaryIsSplitLsbFirst) {
  BitWriter64 writer;
  writer.write(0x5, 3);      // bits 0..2
  writer.write(0x1FF, 9);    // bits 3..11: low 5 bits in byte 0, top 4 in byte 1
  const auto bytes = writer.bytes();
  EXPECT_EQ(bytes[0], 0xFD);   // 11111 101
  EXPECT_EQ(bytes[1], 0x0F);
  for (int i = 2; i < 8; ++i) EXPECT_EQ(bytes[i], 0);
}

TEST(BitPacking, ZeroWidthFieldsAreNoOpsAndReadAsZero) {
  BitWriter64 writer;
  writer.write(0, 0);
  EXPECT_EQ(writer.position(), 0);
  writer.write(0xFFFFFFFFFFFFFFFFull, 64);
  writer.write(0, 0);   // allowed at the very end
  EXPECT_TRUE(writer.full());
  BitReader64 reader(writer.bytes());
  EXPECT_EQ(reader.read(0), 0u);
  EXPECT_EQ(reader.read(64), 0xFFFFFFFFFFFFFFFFull);
  EXPECT_EQ(reader.read(0), 0u);
}

TEST(BitPacking, SignedFieldsRoundTripThroughTwosComplement) {
  for (int width = 1; width <= 64; ++width) {
    const std::int64_t lowest = width == 64 ? INT64_MIN : -(std::int64_t{1} << (width - 1));
    const std::int64_t highest = width == 64 ? INT64_MAX : (std::int64_t{1} << (width - 1)) - 1;
    for (std::int64_t value : {lowest, highest, std::int64_t{0}}) {
      BitWriter128 writer;
      writer.write(1, 3);
      writer.write_signed(value, width);
      BitReader128 reader(writer.bytes());
      EXPECT_EQ(reader.read(3), 1u);
      EXPECT_EQ(reader.read_signed(width), value) << width;
    }
  }
  EXPECT_EQ(sign_extend(0x1F, 5), -1);
  EXPECT_EQ(sign_extend(0x10, 5), -16);
  EXPECT_EQ(sign_extend(0x0F, 5), 15);
  EXPECT_EQ(sign_extend(0xFFF0, 5), -16);   // bits above the field are ignored
}

TEST(BitPacking, RandomAccessSetReplacesOnlyItsFieldIncludingAcrossBit64) {
  std::mt19937_64 engine(77);
  for (int trial = 0; trial < 5000; ++trial) {
    BitBlock128 block;
    std::array<std::uint8_t, 16> expected{};
    for (auto& byte : expected) byte = static_cast<std::uint8_t>(engine());
    block = BitBlock128::from_bytes(expected.data());
    const int width = std::uniform_int_distribution<int>(1, 64)(engine);
    const int position = std::uniform_int_distribution<int>(0, 128 - width)(engine);
    const std::uint64_t value = random_value(engine, width);
    block.set(position, width, value);
    for (int j = 0; j < width; ++j) {
      const int bit = position + j;
      expected[bit / 8] = static_cast<std::uint8_t>((expected[bit / 8] & ~(1u << (bit % 8))) |
                                                    (((value >> j) & 1u) << (bit % 8)));
    }
    ASSERT_EQ(block.bytes(), expected) << position << "+" << width;
    ASSERT_EQ(block.get(position, width), value);
  }
}

TEST(BitPacking, MisuseIsReportedAsAnErrorNamingTheProblem) {
  BitWriter64 writer;
  EXPECT_THROW(writer.write(0, 65), Error);
  EXPECT_THROW(writer.write(0, -1), Error);
  EXPECT_THROW(writer.write(4, 2), Error);          // value wider than its field
  EXPECT_THROW(writer.write_signed(2, 2), Error);   // 2 does not fit in 2-bit two's complement
  EXPECT_THROW(writer.write_signed(-3, 2), Error);
  writer.write(0, 60);
  try {
    writer.write(0, 5);   // bits 60..64 of a 64-bit block
    FAIL() << "writing past the end must throw";
  } catch (const Error& error) {
    EXPECT_NE(std::string(error.what()).find("runs past the end of the 64-bit block"), std::string::npos)
        << error.what();
  }
  EXPECT_EQ(writer.position(), 60);   // a failed write leaves the writer unchanged
  writer.write(0xF, 4);
  EXPECT_TRUE(writer.full());

  BitReader128 reader(BitBlock128{});
  reader.read(64);
  reader.read(36);
  EXPECT_THROW(reader.read(29), Error);   // bits 100..128 of a 128-bit block
  EXPECT_EQ(reader.read(28), 0u);
  EXPECT_THROW(reader.seek(129), Error);
  EXPECT_THROW(reader.seek(-1), Error);
  EXPECT_THROW(BitBlock128{}.get(127, 2), Error);
  EXPECT_THROW(BitBlock128::from_bytes(std::vector<std::uint8_t>(15)), Error);
  EXPECT_THROW(sign_extend(0, 0), Error);
}

}  // namespace
}  // namespace blocklab
