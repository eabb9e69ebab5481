// The DCT-mode oracle (Munkberg et al. 2008, section 6.2; layout and decoding rules: dct_block.h file comment):
// bits read one at a time, the dequantisation and the inverse transform written out from the rules, no code shared
// with pack/unpack/decode_dct_params except the basis function and the tables; tests compare them bit for bit.
#include <algorithm>
#include <cmath>
#include <cstdint>

#include "formats/munkberg/dct_block.h"
#include "formats/munkberg/reference_decode_bits.h"

namespace blocklab::munkberg {

BlockTexels reference_decode_dct(const std::uint8_t* bytes, const DctTables& tables) {
  double value[3][16];   // channel, texel
  int position = 4;      // after the selector 1,1,1,1
  for (int c = 0; c < 3; ++c) {
    const DctChannelTable& table = tables.channel[static_cast<std::size_t>(c)];
    double coefficient[16];
    for (int k = 0; k < 16; ++k) {
      const int bits = table.bits[static_cast<std::size_t>(k)];
      const unsigned code = reference_field(bytes, position, bits);
      position += bits;
      if (k == 0)
        coefficient[k] = bits == 0 ? 0.5 * (table.dc_min + table.dc_max)
                                   : table.dc_min + (table.dc_max - table.dc_min) * static_cast<double>(code) /
                                                        static_cast<double>((1u << bits) - 1u);
      else
        coefficient[k] = bits == 0 ? 0.0 : table.levels[static_cast<std::size_t>(k)][code];
    }
    for (int y = 0; y < 4; ++y)
      for (int x = 0; x < 4; ++x) {
        double sum = 0.0;
        for (int b = 0; b < 4; ++b)
          for (int a = 0; a < 4; ++a) sum += (coefficient[a + 4 * b] * dct_basis(a, x)) * dct_basis(b, y);
        value[c][x + 4 * y] = sum;
      }
  }
  BlockTexels texels;
  for (int i = 0; i < 16; ++i) {
    const double ybar = std::min(16.0, std::max(-16.0, value[0][i]));
    const double u = std::min(1.0, std::max(0.0, value[1][i]));
    const double v = std::min(1.0, std::max(0.0, value[2][i]));
    const double luminance = ybar == -16.0 ? 0.0 : std::exp2(ybar);   // the bottom of the range: true black
    texels.rgba[i][0] = static_cast<float>((v * luminance) / 0.299);
    texels.rgba[i][1] = static_cast<float>((std::max(0.0, 1.0 - u - v) * luminance) / 0.587);
    texels.rgba[i][2] = static_cast<float>((u * luminance) / 0.114);
    texels.rgba[i][3] = 1.0f;
  }
  return texels;
}

}  // namespace blocklab::munkberg
