// The BC4 / BC3-alpha oracle: a plain transcription of the Khronos Data Format Specification, RGTC chapter "BC4
// unsigned" (identical to the S3TC BC3 alpha block; SPECS.md 2.2), with blocklab's reference decoding (exact
// fractions, formats/common/s3tc_common.h). It shares no code with the search-time decoder on purpose.
#include <cstdint>

#include "formats/bc4/bc4_block.h"

namespace blocklab {

std::array<float, 16> reference_decode_bc4_block(const std::uint8_t* bytes) {
  const int red0 = bytes[0];
  const int red1 = bytes[1];
  // "bits is a 48-bit unsigned integer, from which a three-bit control code is extracted for a texel at location
  // (x, y) in the block using: code(x, y) = bits[3 * (4 * y + x) + 2 .. 3 * (4 * y + x) + 0]."
  unsigned long long bits = 0;
  for (int b = 5; b >= 0; --b) bits = bits * 256ull + bytes[2 + b];

  std::array<float, 16> values{};
  for (int y = 0; y < 4; ++y) {
    for (int x = 0; x < 4; ++x) {
      const int i = 4 * y + x;
      const int code = static_cast<int>((bits >> (3 * i)) & 7ull);
      int numerator = 0, denominator = 1;   // the value is numerator / denominator in 8-bit units
      if (red0 > red1) {
        // "red0 > red1": red0, red1, (6 red0 + red1)/7, (5 red0 + 2 red1)/7, ..., (red0 + 6 red1)/7.
        if (code == 0) numerator = red0;
        else if (code == 1) numerator = red1;
        else { numerator = (8 - code) * red0 + (code - 1) * red1; denominator = 7; }
      } else {
        // "red0 <= red1": red0, red1, (4 red0 + red1)/5, ..., (red0 + 4 red1)/5, RED_min (0), RED_max (1.0).
        if (code == 0) numerator = red0;
        else if (code == 1) numerator = red1;
        else if (code <= 5) { numerator = (6 - code) * red0 + (code - 1) * red1; denominator = 5; }
        else if (code == 6) numerator = 0;
        else numerator = 255;
      }
      // One rounding of the exact rational into [0, 1].
      values[i] = static_cast<float>(static_cast<double>(numerator) / (denominator * 255.0));
    }
  }
  return values;
}

}  // namespace blocklab
