// Packing, unpacking, the transform and the decoder of a DCT block (formats/munkberg/dct_block.h; Munkberg et al.
// 2008, section 6.2).
#include "formats/munkberg/dct_block.h"

#include <algorithm>
#include <string>

#include "core/bits.h"
#include "core/color_spaces.h"
#include "core/error.h"
#include "formats/munkberg/munkberg_block.h"

namespace blocklab::munkberg {

namespace {

// basis[a][x], computed once with dct_basis (the same doubles as the oracle's calls).
const std::array<std::array<double, 4>, 4>& basis_table() {
  static const std::array<std::array<double, 4>, 4> table = [] {
    std::array<std::array<double, 4>, 4> t{};
    for (int a = 0; a < 4; ++a)
      for (int x = 0; x < 4; ++x) t[static_cast<std::size_t>(a)][static_cast<std::size_t>(x)] = dct_basis(a, x);
    return t;
  }();
  return table;
}

}  // namespace

double dct_dequantise(const DctChannelTable& table, int k, unsigned code) {
  const int bits = table.bits[static_cast<std::size_t>(k)];
  if (k == 0) {
    // No DC bits: the middle of the range.
    if (bits == 0) return 0.5 * (table.dc_min + table.dc_max);
    const double steps = static_cast<double>((1u << bits) - 1u);
    return table.dc_min + (table.dc_max - table.dc_min) * static_cast<double>(code) / steps;
  }
  if (bits == 0) return 0.0;   // an AC coefficient without bits is dropped
  return table.levels[static_cast<std::size_t>(k)][code];
}

void pack_dct(const DctParams& params, const DctTables& tables, std::uint8_t* bytes) {
  BitWriter128 writer;
  writer.write(kDctSelector, kDctSelectorBits);
  for (int c = 0; c < kDctChannelCount; ++c)
    for (int k = 0; k < kDctCoefficientCount; ++k) {
      const int bits = tables.channel[static_cast<std::size_t>(c)].bits[static_cast<std::size_t>(k)];
      const unsigned code = params.codes[static_cast<std::size_t>(c)][static_cast<std::size_t>(k)];
      if (code >= (1u << bits))
        fail("munkberg", std::string("dct ") + kDctChannelNames[static_cast<std::size_t>(c)] + " coefficient " +
                             std::to_string(k) + ": code " + std::to_string(code) + " does not fit in " +
                             std::to_string(bits) + " bits");
      if (bits > 0) writer.write(code, bits);
    }
  if (!writer.full()) fail("munkberg", "internal: dct block not full after packing (table budgets)");
  writer.to_bytes(bytes);
}

DctParams unpack_dct(const std::uint8_t* bytes, const DctTables& tables) {
  if (block_mode_of(bytes) != BlockMode::dct) fail("munkberg", "unpack_dct: the selector is not 1,1,1,1");
  BitReader128 reader(bytes);
  reader.read(kDctSelectorBits);
  DctParams params;
  for (int c = 0; c < kDctChannelCount; ++c)
    for (int k = 0; k < kDctCoefficientCount; ++k) {
      const int bits = tables.channel[static_cast<std::size_t>(c)].bits[static_cast<std::size_t>(k)];
      params.codes[static_cast<std::size_t>(c)][static_cast<std::size_t>(k)] =
          bits > 0 ? static_cast<std::uint16_t>(reader.read(bits)) : std::uint16_t{0};
    }
  return params;
}

std::array<double, kDctCoefficientCount> forward_dct(const std::array<double, kTexels>& samples) {
  const auto& basis = basis_table();
  std::array<double, kDctCoefficientCount> out{};
  for (int b = 0; b < 4; ++b)
    for (int a = 0; a < 4; ++a) {
      double sum = 0.0;
      for (int y = 0; y < 4; ++y)
        for (int x = 0; x < 4; ++x)
          sum += (samples[static_cast<std::size_t>(x + 4 * y)] * basis[static_cast<std::size_t>(a)][static_cast<std::size_t>(x)]) *
                 basis[static_cast<std::size_t>(b)][static_cast<std::size_t>(y)];
      out[static_cast<std::size_t>(a + 4 * b)] = sum;
    }
  return out;
}

std::array<double, kTexels> inverse_dct(const std::array<double, kDctCoefficientCount>& coefficients) {
  const auto& basis = basis_table();
  std::array<double, kTexels> out{};
  for (int y = 0; y < 4; ++y)
    for (int x = 0; x < 4; ++x) {
      double sum = 0.0;
      for (int k = 0; k < kDctCoefficientCount; ++k)
        sum += (coefficients[static_cast<std::size_t>(k)] * basis[static_cast<std::size_t>(k % 4)][static_cast<std::size_t>(x)]) *
               basis[static_cast<std::size_t>(k / 4)][static_cast<std::size_t>(y)];
      out[static_cast<std::size_t>(x + 4 * y)] = sum;
    }
  return out;
}

DctChannelValues dct_channel_samples(const DctParams& params, const DctTables& tables, int c) {
  std::array<double, kDctCoefficientCount> coefficients{};
  for (int k = 0; k < kDctCoefficientCount; ++k)
    coefficients[static_cast<std::size_t>(k)] = dct_dequantise(
        tables.channel[static_cast<std::size_t>(c)], k, params.codes[static_cast<std::size_t>(c)][static_cast<std::size_t>(k)]);
  return inverse_dct(coefficients);
}

BlockTexels decode_dct_params(const DctParams& params, const DctTables& tables) {
  std::array<DctChannelValues, kDctChannelCount> channel{};
  for (int c = 0; c < kDctChannelCount; ++c) channel[static_cast<std::size_t>(c)] = dct_channel_samples(params, tables, c);
  return dct_texels_from_samples(channel);
}

BlockTexels dct_texels_from_samples(const std::array<DctChannelValues, kDctChannelCount>& channel) {
  double rgb[kTexels][3];
  for (int i = 0; i < kTexels; ++i) {
    const std::size_t ii = static_cast<std::size_t>(i);
    // The transform can overshoot the ranges: Ybar to the half range, u and v to [0, 1].
    const double ybar = std::min(kLogLumMax, std::max(kLogLumMin, channel[0][ii]));
    const double u = std::min(1.0, std::max(0.0, channel[1][ii]));
    const double v = std::min(1.0, std::max(0.0, channel[2][ii]));
    // Eq. (3) carried to the transform: the bottom of the range is true black.
    const double luminance = ybar <= kLogLumMin ? 0.0 : std::exp2(ybar);
    rgb[i][0] = (v * luminance) / kRec601WeightR;
    rgb[i][1] = (std::max(0.0, 1.0 - u - v) * luminance) / kRec601WeightG;
    rgb[i][2] = (u * luminance) / kRec601WeightB;
  }
  return texels_from_rgb(rgb);
}

}  // namespace blocklab::munkberg
