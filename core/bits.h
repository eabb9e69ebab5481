// Bit packing for fixed-size compressed blocks (64-bit BC1/BC4 blocks, 128-bit BC3/BC7/BC6H/HDR blocks).
//
// Bit order is the BCn convention (Khronos Data Format Specification, "S3TC" / "BPTC" chapters; Microsoft BC7
// format reference): a block is little-endian and fields are packed LSB-first, so bit k of a block is bit (k % 8)
// of byte k / 8, and a field of width w written at bit position p occupies bits p .. p + w - 1 with its least
// significant bit at p. Fields may straddle byte and 64-bit word boundaries (e.g. a BC7 field over bits 60..67).
//
// Error handling (the decision for every caller): all misuse throws blocklab::Error, in Release too, naming the
// class, the position and the reason: a width outside 0..64, a field running past the end of the block, a value
// that does not fit in `width` bits, a byte buffer of the wrong size. The checks are a few integer compares per
// field; a block is packed once per encode, so they are not worth disabling.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "core/error.h"

namespace blocklab {

namespace bits_detail {

// All-ones mask of the low `width` bits, width in 0..64 (no shift by 64: width 64 is handled explicitly).
constexpr std::uint64_t low_mask(int width) {
  return width >= 64 ? ~std::uint64_t{0} : ((std::uint64_t{1} << width) - 1);
}

inline std::string describe_block(int block_bits) { return std::to_string(block_bits) + "-bit block"; }

// True when a field of `width` (0..64) bits at `position` lies inside a `block_bits`-bit block. Kept tiny and
// separate from the reporting below so the compiler sees the bound at every access.
constexpr bool field_fits(int block_bits, int position, int width) {
  return width >= 0 && width <= 64 && position >= 0 && position <= block_bits - width;
}

[[noreturn]] inline void field_error(const char* who, int block_bits, int position, int width) {
  if (width < 0 || width > 64) fail(who, "field width " + std::to_string(width) + " is outside 0..64");
  fail(who, "field of width " + std::to_string(width) + " at bit " + std::to_string(position) +
                " runs past the end of the " + describe_block(block_bits));
}

}  // namespace bits_detail

// Sign-extends the low `width` bits of `value` (two's complement field, width 1..64) to a signed 64-bit integer,
// e.g. for BC6H signed endpoints and deltas.
inline std::int64_t sign_extend(std::uint64_t value, int width) {
  if (width < 1 || width > 64) fail("sign_extend", "field width " + std::to_string(width) + " is outside 1..64");
  const std::uint64_t field = value & bits_detail::low_mask(width);
  const std::uint64_t sign_bit = std::uint64_t{1} << (width - 1);
  // (field ^ sign) - sign maps [2^(w-1), 2^w) to [-2^(w-1), 0) and leaves non-negative fields unchanged; done in
  // unsigned arithmetic (wraps modulo 2^64) and converted once, so there is no signed overflow.
  const std::uint64_t extended = (field ^ sign_bit) - sign_bit;
  return static_cast<std::int64_t>(extended);
}

// A block of kBits bits held as little-endian 64-bit words (word i = bytes 8i .. 8i+7).
template <int kBits>
class BitBlock {
 public:
  static_assert(kBits > 0 && kBits % 64 == 0, "blocks are a whole number of 64-bit words");
  static constexpr int kBitCount = kBits;
  static constexpr int kByteCount = kBits / 8;
  static constexpr int kWordCount = kBits / 64;

  BitBlock() = default;

  // From exactly kByteCount bytes (byte k holds block bits 8k .. 8k+7).
  static BitBlock from_bytes(const std::uint8_t* bytes) {
    BitBlock block;
    for (int i = 0; i < kByteCount; ++i)
      block.words_[i / 8] |= std::uint64_t{bytes[i]} << (8 * (i % 8));
    return block;
  }
  static BitBlock from_bytes(const std::array<std::uint8_t, kByteCount>& bytes) { return from_bytes(bytes.data()); }
  static BitBlock from_bytes(const std::vector<std::uint8_t>& bytes) {
    if (bytes.size() != static_cast<std::size_t>(kByteCount))
      fail("BitBlock::from_bytes", "got " + std::to_string(bytes.size()) + " bytes for a " +
                                       bits_detail::describe_block(kBits) + " (" + std::to_string(kByteCount) +
                                       " bytes)");
    return from_bytes(bytes.data());
  }

  void to_bytes(std::uint8_t* out) const {
    for (int i = 0; i < kByteCount; ++i) out[i] = static_cast<std::uint8_t>(words_[i / 8] >> (8 * (i % 8)));
  }
  std::array<std::uint8_t, kByteCount> bytes() const {
    std::array<std::uint8_t, kByteCount> out{};
    to_bytes(out.data());
    return out;
  }

  // Random access: the `width`-bit field whose least significant bit is block bit `position`.
  std::uint64_t get(int position, int width) const {
    if (!bits_detail::field_fits(kBits, position, width))
      bits_detail::field_error("BitBlock::get", kBits, position, width);
    if (width == 0) return 0;
    const int word = position / 64;
    const int shift = position % 64;
    std::uint64_t value = words_[word] >> shift;
    // Straddles into the next word: shift > 0 here (shift + width > 64 with width <= 64), so 64 - shift < 64.
    if (shift + width > 64) value |= words_[word + 1] << (64 - shift);
    return value & bits_detail::low_mask(width);
  }

  // Random access write: replaces the `width`-bit field at `position` with `value` (which must fit in width bits).
  void set(int position, int width, std::uint64_t value) {
    if (!bits_detail::field_fits(kBits, position, width))
      bits_detail::field_error("BitBlock::set", kBits, position, width);
    if ((value & ~bits_detail::low_mask(width)) != 0)
      fail("BitBlock::set", "value " + std::to_string(value) + " does not fit in " + std::to_string(width) +
                                " bits (field at bit " + std::to_string(position) + ")");
    if (width == 0) return;
    const int word = position / 64;
    const int shift = position % 64;
    const std::uint64_t mask = bits_detail::low_mask(width);
    words_[word] = (words_[word] & ~(mask << shift)) | (value << shift);
    // Straddling field: its top (shift + width - 64) bits go to the low end of the next word.
    if (shift + width > 64) {
      const int spill = 64 - shift;   // 1..63: bits already placed in `word`
      words_[word + 1] = (words_[word + 1] & ~(mask >> spill)) | (value >> spill);
    }
  }

  std::uint64_t word(int index) const { return words_[index]; }
  bool operator==(const BitBlock& other) const {
    for (int i = 0; i < kWordCount; ++i)
      if (words_[i] != other.words_[i]) return false;
    return true;
  }
  bool operator!=(const BitBlock& other) const { return !(*this == other); }

 private:
  std::uint64_t words_[kWordCount] = {};
};

// Sequential writer: fields are appended LSB-first from bit 0. Unwritten bits are 0.
template <int kBits>
class BitWriter {
 public:
  static constexpr int kBitCount = kBits;
  static constexpr int kByteCount = kBits / 8;

  // Appends `value` as a `width`-bit field (width 0..64; width 0 writes nothing and needs value 0).
  // Throws Error if the field would run past the end or `value` has bits set at or above `width`.
  void write(std::uint64_t value, int width) {
    if (width < 0 || width > 64)
      fail(who(), "field width " + std::to_string(width) + " is outside 0..64");
    if ((value & ~bits_detail::low_mask(width)) != 0)
      fail(who(), "value " + std::to_string(value) + " does not fit in " + std::to_string(width) +
                      " bits (field at bit " + std::to_string(position_) + ")");
    if (width > kBits - position_)
      fail(who(), "field of width " + std::to_string(width) + " at bit " + std::to_string(position_) +
                      " runs past the end of the " + bits_detail::describe_block(kBits));
    block_.set(position_, width, value);
    position_ += width;
  }
  // Appends a two's complement field: `value` must lie in [-2^(width-1), 2^(width-1) - 1], width 1..64.
  void write_signed(std::int64_t value, int width) {
    if (width < 1 || width > 64) fail(who(), "signed field width " + std::to_string(width) + " is outside 1..64");
    if (width < 64) {
      const std::int64_t limit = std::int64_t{1} << (width - 1);
      if (value < -limit || value >= limit)
        fail(who(), "signed value " + std::to_string(value) + " does not fit in " + std::to_string(width) +
                        " bits (field at bit " + std::to_string(position_) + ")");
    }
    write(static_cast<std::uint64_t>(value) & bits_detail::low_mask(width), width);
  }

  int position() const { return position_; }
  int remaining() const { return kBits - position_; }
  bool full() const { return position_ == kBits; }

  const BitBlock<kBits>& block() const { return block_; }
  std::array<std::uint8_t, kByteCount> bytes() const { return block_.bytes(); }
  void to_bytes(std::uint8_t* out) const { block_.to_bytes(out); }

 private:
  static std::string who() { return "BitWriter<" + std::to_string(kBits) + ">::write"; }
  BitBlock<kBits> block_;
  int position_ = 0;
};

// Sequential reader: fields are consumed LSB-first from bit 0.
template <int kBits>
class BitReader {
 public:
  static constexpr int kBitCount = kBits;
  static constexpr int kByteCount = kBits / 8;

  explicit BitReader(const BitBlock<kBits>& block) : block_(block) {}
  // Reads exactly kByteCount bytes.
  explicit BitReader(const std::uint8_t* bytes) : block_(BitBlock<kBits>::from_bytes(bytes)) {}
  explicit BitReader(const std::array<std::uint8_t, kByteCount>& bytes) : block_(BitBlock<kBits>::from_bytes(bytes)) {}

  // Consumes a `width`-bit field (width 0..64; width 0 returns 0). Throws Error past the end of the block.
  std::uint64_t read(int width) {
    if (width < 0 || width > 64) fail(who(), "field width " + std::to_string(width) + " is outside 0..64");
    if (width > kBits - position_)
      fail(who(), "field of width " + std::to_string(width) + " at bit " + std::to_string(position_) +
                      " runs past the end of the " + bits_detail::describe_block(kBits));
    const std::uint64_t value = block_.get(position_, width);
    position_ += width;
    return value;
  }
  // Consumes a two's complement field of width 1..64 and sign-extends it.
  std::int64_t read_signed(int width) {
    if (width < 1 || width > 64) fail(who(), "signed field width " + std::to_string(width) + " is outside 1..64");
    return sign_extend(read(width), width);
  }

  // Moves to block bit `position` (0..kBits).
  void seek(int position) {
    if (position < 0 || position > kBits)
      fail("BitReader<" + std::to_string(kBits) + ">::seek",
           "position " + std::to_string(position) + " is outside 0.." + std::to_string(kBits));
    position_ = position;
  }

  int position() const { return position_; }
  int remaining() const { return kBits - position_; }
  const BitBlock<kBits>& block() const { return block_; }

 private:
  static std::string who() { return "BitReader<" + std::to_string(kBits) + ">::read"; }
  BitBlock<kBits> block_;
  int position_ = 0;
};

using BitBlock64 = BitBlock<64>;
using BitBlock128 = BitBlock<128>;
using BitWriter64 = BitWriter<64>;
using BitWriter128 = BitWriter<128>;
using BitReader64 = BitReader<64>;
using BitReader128 = BitReader<128>;

}  // namespace blocklab
