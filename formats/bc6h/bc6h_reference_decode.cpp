// Spec-literal BC6H decoder (bc6h_reference_decode.h), step by step as KDFS "BC6H" describes it:
//   1. mode number M: the low two bits if they are 0 or 1, else the low five bits; 19, 23, 27, 31 are reserved (0);
//   2. walk the mode's block description left to right, LSB first: element v[a..b] moves the next |a - b| + 1 block
//      bits into bits b, ..., a of v when a >= b (so the first block bit lands in bit b), reversed when a < b;
//   3. sign-extend E0 when signed; E1..E3 when signed or transformed (by their own width);
//      transformed: Ek = (E0 + Ek) & ((1 << EPB) - 1), sign-extended again when signed;
//   4. unquantise each endpoint (the two pseudocode listings), interpolate with the BPTC weights
//      ((64 - w) E0 + w E1 + 32) >> 6, then the final unquantisation to half bits;
//   5. indices from bit 65 (one subset, 4 bits) or 82 (two subsets, 3 bits), each anchor one bit shorter.
#include "formats/bc6h/bc6h_reference_decode.h"

#include <cstdlib>
#include <cstring>
#include <map>
#include <string>

#include "formats/bc7/bc7_tables.h"

namespace blocklab {
namespace bc6h {

namespace {

struct SpecRow {
  int mode_number;
  bool transformed;
  int epb;
  const char* description;   // KDFS table-bptcblockformat, M first; partition bits "PB"
};

// Transcribed from KDFS table-bptcblockformat ("Block descriptions for BC6H block modes (LSB..MSB)").
const SpecRow kRows[] = {
    {0, true, 10,
     "M[1..0] G2[4] B2[4] B3[4] R0[9..0] G0[9..0] B0[9..0] R1[4..0] G3[4] G2[3..0] G1[4..0] B3[0] G3[3..0] B1[4..0] "
     "B3[1] B2[3..0] R2[4..0] B3[2] R3[4..0] B3[3] PB[4..0]"},
    {1, true, 7,
     "M[1..0] G2[5] G3[4] G3[5] R0[6..0] B3[0] B3[1] B2[4] G0[6..0] B2[5] B3[2] G2[4] B0[6..0] B3[3] B3[5] B3[4] "
     "R1[5..0] G2[3..0] G1[5..0] G3[3..0] B1[5..0] B2[3..0] R2[5..0] R3[5..0] PB[4..0]"},
    {2, true, 11,
     "M[4..0] R0[9..0] G0[9..0] B0[9..0] R1[4..0] R0[10] G2[3..0] G1[3..0] G0[10] B3[0] G3[3..0] B1[3..0] B0[10] "
     "B3[1] B2[3..0] R2[4..0] B3[2] R3[4..0] B3[3] PB[4..0]"},
    {6, true, 11,
     "M[4..0] R0[9..0] G0[9..0] B0[9..0] R1[3..0] R0[10] G3[4] G2[3..0] G1[4..0] G0[10] G3[3..0] B1[3..0] B0[10] "
     "B3[1] B2[3..0] R2[3..0] B3[0] B3[2] R3[3..0] G2[4] B3[3] PB[4..0]"},
    {10, true, 11,
     "M[4..0] R0[9..0] G0[9..0] B0[9..0] R1[3..0] R0[10] B2[4] G2[3..0] G1[3..0] G0[10] B3[0] G3[3..0] B1[4..0] "
     "B0[10] B2[3..0] R2[3..0] B3[1] B3[2] R3[3..0] B3[4] B3[3] PB[4..0]"},
    {14, true, 9,
     "M[4..0] R0[8..0] B2[4] G0[8..0] G2[4] B0[8..0] B3[4] R1[4..0] G3[4] G2[3..0] G1[4..0] B3[0] G3[3..0] B1[4..0] "
     "B3[1] B2[3..0] R2[4..0] B3[2] R3[4..0] B3[3] PB[4..0]"},
    {18, true, 8,
     "M[4..0] R0[7..0] G3[4] B2[4] G0[7..0] B3[2] G2[4] B0[7..0] B3[3] B3[4] R1[5..0] G2[3..0] G1[4..0] B3[0] "
     "G3[3..0] B1[4..0] B3[1] B2[3..0] R2[5..0] R3[5..0] PB[4..0]"},
    {22, true, 8,
     "M[4..0] R0[7..0] B3[0] B2[4] G0[7..0] G2[5] G2[4] B0[7..0] G3[5] B3[4] R1[4..0] G3[4] G2[3..0] G1[5..0] "
     "G3[3..0] B1[4..0] B3[1] B2[3..0] R2[4..0] B3[2] R3[4..0] B3[3] PB[4..0]"},
    {26, true, 8,
     "M[4..0] R0[7..0] B3[1] B2[4] G0[7..0] B2[5] G2[4] B0[7..0] B3[5] B3[4] R1[4..0] G3[4] G2[3..0] G1[4..0] B3[0] "
     "G3[3..0] B1[5..0] B2[3..0] R2[4..0] B3[2] R3[4..0] B3[3] PB[4..0]"},
    {30, false, 6,
     "M[4..0] R0[5..0] G3[4] B3[0] B3[1] B2[4] G0[5..0] G2[5] B2[5] B3[2] G2[4] B0[5..0] G3[5] B3[3] B3[5] B3[4] "
     "R1[5..0] G2[3..0] G1[5..0] G3[3..0] B1[5..0] B2[3..0] R2[5..0] R3[5..0] PB[4..0]"},
    {3, false, 10, "M[4..0] R0[9..0] G0[9..0] B0[9..0] R1[9..0] G1[9..0] B1[9..0]"},
    {7, true, 11, "M[4..0] R0[9..0] G0[9..0] B0[9..0] R1[8..0] R0[10] G1[8..0] G0[10] B1[8..0] B0[10]"},
    {11, true, 12, "M[4..0] R0[9..0] G0[9..0] B0[9..0] R1[7..0] R0[10..11] G1[7..0] G0[10..11] B1[7..0] B0[10..11]"},
    {15, true, 16, "M[4..0] R0[9..0] G0[9..0] B0[9..0] R1[3..0] R0[10..15] G1[3..0] G0[10..15] B1[3..0] B0[10..15]"},
};

int block_bit(const std::uint8_t* bytes, int position) { return (bytes[position / 8] >> (position % 8)) & 1; }

// Reads the block description: fills variables (name -> value) and the number of bits each variable received.
int read_description(const std::uint8_t* bytes, const char* description, std::map<std::string, long>& values,
                     std::map<std::string, int>& widths) {
  int position = 0;
  const char* cursor = description;
  while (*cursor != '\0') {
    while (*cursor == ' ') ++cursor;
    if (*cursor == '\0') break;
    const char* open = std::strchr(cursor, '[');
    const std::string name(cursor, open);
    char* end = nullptr;
    const long a = std::strtol(open + 1, &end, 10);
    long b = a;
    if (end[0] == '.' && end[1] == '.') b = std::strtol(end + 2, &end, 10);
    cursor = end + 1;   // past ']'
    const long step = a >= b ? 1 : -1;   // a >= b: first block bit -> bit b, upwards; else downwards from b
    for (long target = b;; target += step) {
      values[name] |= static_cast<long>(block_bit(bytes, position++)) << target;
      ++widths[name];
      if (target == a) break;
    }
  }
  return position;
}

long extend(long value, int bits) {
  const long sign = 1L << (bits - 1);
  value &= (1L << bits) - 1;
  return value >= sign ? value - (1L << bits) : value;
}

long unquantize_unsigned(long x, int epb) {
  if (epb >= 15) return x;
  if (x == 0) return 0;
  if (x == ((1L << epb) - 1)) return 0xFFFF;
  return ((x << 15) + 0x4000) >> (epb - 1);
}

long unquantize_signed(long x, int epb) {
  long unq;
  bool s = false;
  if (epb >= 16) return x;
  if (x < 0) {
    s = true;
    x = -x;
  }
  if (x == 0)
    unq = 0;
  else if (x >= ((1L << (epb - 1)) - 1))
    unq = 0x7FFF;
  else
    unq = ((x << 15) + 0x4000) >> (epb - 1);
  return s ? -unq : unq;
}

const int kWeights3[8] = {0, 9, 18, 27, 37, 46, 55, 64};
const int kWeights4[16] = {0, 4, 9, 13, 17, 21, 26, 30, 34, 38, 43, 47, 51, 55, 60, 64};

}  // namespace

void reference_decode(const std::uint8_t* bytes, bool is_signed, std::uint16_t (&out)[16][3]) {
  for (auto& texel : out) texel[0] = texel[1] = texel[2] = 0;
  int mode_number = block_bit(bytes, 0) | (block_bit(bytes, 1) << 1);
  if (mode_number >= 2)
    for (int i = 2; i < 5; ++i) mode_number |= block_bit(bytes, i) << i;
  const SpecRow* row = nullptr;
  for (const SpecRow& candidate : kRows)
    if (candidate.mode_number == mode_number) row = &candidate;
  if (row == nullptr) return;   // reserved mode

  std::map<std::string, long> values;
  std::map<std::string, int> widths;
  read_description(bytes, row->description, values, widths);
  const bool two_subsets = widths.count("PB") != 0;
  const int endpoint_count = two_subsets ? 4 : 2;
  const char channel_names[3] = {'R', 'G', 'B'};
  long endpoints[4][3];
  for (int c = 0; c < 3; ++c) {
    for (int e = 0; e < endpoint_count; ++e) {
      const std::string name = std::string(1, channel_names[c]) + std::to_string(e);
      long value = values[name];
      if (is_signed || (e > 0 && row->transformed)) value = extend(value, widths[name]);
      if (e > 0 && row->transformed) {
        value = (endpoints[0][c] + value) & ((1L << row->epb) - 1);
        if (is_signed) value = extend(value, row->epb);
      }
      endpoints[e][c] = value;
    }
  }
  for (int e = 0; e < endpoint_count; ++e)
    for (int c = 0; c < 3; ++c)
      endpoints[e][c] = is_signed ? unquantize_signed(endpoints[e][c], row->epb)
                                  : unquantize_unsigned(endpoints[e][c], row->epb);

  const int partition = two_subsets ? static_cast<int>(values["PB"]) : 0;
  const int bits_per_index = two_subsets ? 3 : 4;
  int position = two_subsets ? 82 : 65;
  for (int texel = 0; texel < 16; ++texel) {
    const int subset = two_subsets ? bc7::subset_of_texel(2, partition, texel) : 0;
    const bool anchor = texel == 0 || (two_subsets && texel == bc7::anchor_texel(2, partition, 1));
    int index = 0;
    for (int i = 0; i < bits_per_index - (anchor ? 1 : 0); ++i) index |= block_bit(bytes, position++) << i;
    const int weight = two_subsets ? kWeights3[index] : kWeights4[index];
    for (int c = 0; c < 3; ++c) {
      const long interpolated =
          ((64 - weight) * endpoints[2 * subset][c] + weight * endpoints[2 * subset + 1][c] + 32) >> 6;
      long result;
      if (!is_signed)
        result = (interpolated * 31) >> 6;
      else
        result = interpolated < 0 ? (((-interpolated) * 31) >> 5) | 0x8000 : (interpolated * 31) >> 5;
      out[texel][c] = static_cast<std::uint16_t>(result);
    }
  }
}

}  // namespace bc6h
}  // namespace blocklab
