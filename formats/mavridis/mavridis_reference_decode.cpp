// The `mavridis` oracle: one wavelet plane decoded straight from the paper (Mavridis & Papaioannou 2012) and the
// DXT5 text, sharing no code with the decoder of mavridis_plane_codec.cpp.
//   DXT5 (KDFS S3TC "BC3"): bytes 0-1 alpha0, alpha1; bytes 2-7 48 bits of 3-bit alpha codes; bytes 8-11 two RGB565
//   colours; bytes 12-15 32 bits of 2-bit colour codes, always the 4-colour palette (c0, c1, (2c0+c1)/3,
//   (c0+2c1)/3), every value an exact fraction of the bit-replicated 8-bit endpoints.
//   Section 3.1: alpha holds LL, RGB hold HL', LH', HH' (Haar: HL, LH, HH).
//   Section 3.2: x = c + r sign(n) |n|^(1/g), n = 2s - 1 (LL: g = 1).
//   Eq. 2 inverted; eq. 1, "the inverse of itself", gives the four texels a, b, c, d of the group, its terms summed
//   in the order LL, HH, LH, HL (so every texel is bit-identical to eq. 3's, which accumulates in that order: the
//   exact DXT fractions, the same dequantisation and these sums leave no rounding difference) (the
//   S-transform of Table 3: its integer inverse on the rounded coefficients; PLHaar: the rounded coefficients looked
//   up in a table of its forward map, which is a bijection of the domain's square, over every pair).
#include <cmath>
#include <utility>
#include <vector>

#include "formats/bc7/bc7_reference_decode.h"
#include "formats/mavridis/mavridis_multilevel.h"
#include "formats/mavridis/mavridis_plane_codec.h"

namespace blocklab {
namespace mavridis {

namespace {

double alpha_value(int a0, int a1, int code) {
  if (code == 0) return a0 / 255.0;
  if (code == 1) return a1 / 255.0;
  if (a0 > a1) return ((8 - code) * a0 + (code - 1) * a1) / (7.0 * 255.0);
  if (code <= 5) return ((6 - code) * a0 + (code - 1) * a1) / (5.0 * 255.0);
  return code == 6 ? 0.0 : 1.0;
}

// The 16 texels' RGB fractions of an S3TC colour half (8 bytes): two RGB565 colours, bit-replicated to 8 bits, and
// 32 bits of 2-bit codes; the 4-colour palette (c0, c1, (2c0+c1)/3, (c0+2c1)/3) always in DXT5, in DXT1 only when
// the packed c0 > c1 (else c0, c1, (c0+c1)/2, black).
void colour_half(const std::uint8_t* half, bool always_four, double rgb[16][3]) {
  const unsigned c0 = half[0] | (half[1] << 8), c1 = half[2] | (half[3] << 8);
  const unsigned long codes =
      half[4] | (half[5] << 8) | (half[6] << 16) | (static_cast<unsigned long>(half[7]) << 24);
  int e0[3] = {static_cast<int>(c0 >> 11), static_cast<int>((c0 >> 5) & 63), static_cast<int>(c0 & 31)};
  int e1[3] = {static_cast<int>(c1 >> 11), static_cast<int>((c1 >> 5) & 63), static_cast<int>(c1 & 31)};
  for (int k = 0; k < 3; ++k) {
    const bool six = k == 1;
    e0[k] = six ? (e0[k] << 2) | (e0[k] >> 4) : (e0[k] << 3) | (e0[k] >> 2);
    e1[k] = six ? (e1[k] << 2) | (e1[k] >> 4) : (e1[k] << 3) | (e1[k] >> 2);
  }
  const bool four = always_four || c0 > c1;
  for (int i = 0; i < 16; ++i) {
    const int code = static_cast<int>((codes >> (2 * i)) & 3);
    for (int k = 0; k < 3; ++k) {
      if (four) {
        const int weights0[4] = {3, 0, 2, 1};
        rgb[i][k] = (weights0[code] * e0[k] + (3 - weights0[code]) * e1[k]) / (3.0 * 255.0);
      } else {
        const int weights0[4] = {2, 0, 1, 0}, weights1[4] = {0, 2, 1, 0};
        rgb[i][k] = (weights0[code] * e0[k] + weights1[code] * e1[k]) / (2.0 * 255.0);
      }
    }
  }
}

double unmap(double s, double centre, double half_range, double gamma) {
  const double n = 2.0 * s - 1.0;
  const double magnitude = std::pow(std::fabs(n), 1.0 / gamma);
  return centre + half_range * (n < 0.0 ? -magnitude : magnitude);
}

// PLHaar inverted by tabulating its forward map: entry (L + half) * 2 half + (H + half) holds the pair (a, b).
std::vector<std::pair<int, int>> plhaar_inverse_table(int half) {
  const int side = 2 * half;
  std::vector<std::pair<int, int>> table(static_cast<std::size_t>(side) * side);
  for (int a = -half; a < half; ++a)
    for (int b = -half; b < half; ++b) {
      const PlhaarPair lh = plhaar_forward(a, b);
      table[static_cast<std::size_t>(lh.low + half) * side + (lh.high + half)] = {a, b};
    }
  return table;
}

}  // namespace

Plane reference_decode_wavelet_plane(const std::uint8_t* bytes, int width, int height, const BandMapping& mapping,
                                     Transform transform, double w, Packing packing, PlhaarDomain domain) {
  const std::vector<std::pair<int, int>> plhaar_table =
      transform == Transform::plhaar ? plhaar_inverse_table(domain.half) : std::vector<std::pair<int, int>>{};
  Plane out = Plane::zeros(width, height);
  const int blocks_x = (width + 7) / 8, blocks_y = (height + 7) / 8;
  for (int by = 0; by < blocks_y; ++by)
    for (int bx = 0; bx < blocks_x; ++bx) {
      const std::uint8_t* block = bytes + (static_cast<std::size_t>(by) * blocks_x + bx) * 16;
      unsigned long long alpha_bits = 0;
      for (int b = 7; b >= 2; --b) alpha_bits = (alpha_bits << 8) | block[b];
      double colours[16][3];
      colour_half(block + 8, true, colours);
      if (packing == Packing::bc7) {
        // Section 3.1 BC7 packing: R = LL, G = HL + LH, B = HL - LH (Haar: HL, LH), HH = 0; the block by the BPTC
        // oracle (formats/bc7/bc7_reference_decode.h), then eq. 1.
        std::uint8_t rgba[16][4];
        bc7::reference_decode(block, rgba);
        for (int i = 0; i < 16; ++i) {
          const double ll = unmap(rgba[i][0] / 255.0, mapping.centre[0], mapping.half_range[0], 1.0);
          const double g = unmap(rgba[i][1] / 255.0, mapping.centre[1], mapping.half_range[1], mapping.gamma);
          const double b = unmap(rgba[i][2] / 255.0, mapping.centre[2], mapping.half_range[2], mapping.gamma);
          const double hl = transform == Transform::pi_haar ? (g + b) / 2.0 : g;
          const double lh = transform == Transform::pi_haar ? (g - b) / 2.0 : b;
          const double texel[4] = {(ll + lh + hl) / 2.0, (ll + lh - hl) / 2.0, (ll - lh + hl) / 2.0, (ll - lh - hl) / 2.0};
          const int gx = bx * 4 + i % 4, gy = by * 4 + i / 4;
          for (int t = 0; t < 4; ++t) {
            const int x = 2 * gx + t % 2, y = 2 * gy + t / 2;
            if (x < width && y < height) out.values[static_cast<std::size_t>(y) * width + x] = texel[t];
          }
        }
        continue;
      }
      for (int i = 0; i < 16; ++i) {
        const int alpha_code = static_cast<int>((alpha_bits >> (3 * i)) & 7);
        double s[4];
        s[0] = alpha_value(block[0], block[1], alpha_code);
        for (int k = 0; k < 3; ++k) s[k + 1] = colours[i][k];
        const double ll = unmap(s[0], mapping.centre[0], mapping.half_range[0], 1.0);
        double hl = unmap(s[1], mapping.centre[1], mapping.half_range[1], mapping.gamma);
        double lh = unmap(s[2], mapping.centre[2], mapping.half_range[2], mapping.gamma);
        double hh = unmap(s[3], mapping.centre[3], mapping.half_range[3], mapping.gamma);
        if (transform == Transform::pi_haar) {
          // HL' + LH' = 2 LH;  LH' + HH' = -2 w HH;  HL' = HL + LH + w HH.
          const double p1 = hl, p2 = lh, p3 = hh;
          lh = (p1 + p2) / 2.0;
          hh = (p2 + p3) * (-0.5 / w);
          hl = p1 - lh - w * hh;
        }
        // Eq. 1 applied to (LL, HL, LH, HH) returns (a, b, c, d).
        double texel[4] = {(ll + hh + lh + hl) / 2.0, (ll - hh + lh - hl) / 2.0, (ll - hh - lh + hl) / 2.0,
                           (ll + hh - lh - hl) / 2.0};
        if (transform == Transform::s_transform) {
          // S-transform (CDSY97) on the rounded coefficients: undo the column pairs (LL, LH) and (HL, HH), then the
          // row pairs; x = l + floor((h + 1) / 2), y = x - h.
          const double sll = std::round(std::fmax(std::fmin(ll, 1e9), -1e9));
          const double shl = std::round(std::fmax(std::fmin(hl, 1e9), -1e9));
          const double slh = std::round(std::fmax(std::fmin(lh, 1e9), -1e9));
          const double shh = std::round(std::fmax(std::fmin(hh, 1e9), -1e9));
          const double l1 = sll + std::floor((slh + 1.0) / 2.0), l2 = l1 - slh;
          const double h1 = shl + std::floor((shh + 1.0) / 2.0), h2 = h1 - shh;
          texel[0] = l1 + std::floor((h1 + 1.0) / 2.0);
          texel[1] = texel[0] - h1;
          texel[2] = l2 + std::floor((h2 + 1.0) / 2.0);
          texel[3] = texel[2] - h2;
        }
        if (transform == Transform::plhaar) {
          // The coefficients are LL, HL, LH, HH of the row-then-column PLHaar: undo the columns (LL, LH) and
          // (HL, HH), then the rows.
          const int side = 2 * domain.half;
          auto coefficient = [&](double v) {
            return static_cast<int>(std::fmax(std::fmin(std::round(v), domain.half - 1.0), -double(domain.half)));
          };
          auto invert = [&](int low, int high) {
            return plhaar_table[static_cast<std::size_t>(low + domain.half) * side + (high + domain.half)];
          };
          const std::pair<int, int> lows = invert(coefficient(ll), coefficient(lh));
          const std::pair<int, int> highs = invert(coefficient(hl), coefficient(hh));
          const std::pair<int, int> row1 = invert(lows.first, highs.first), row2 = invert(lows.second, highs.second);
          texel[0] = row1.first + domain.offset;
          texel[1] = row1.second + domain.offset;
          texel[2] = row2.first + domain.offset;
          texel[3] = row2.second + domain.offset;
        }
        const int gx = bx * 4 + i % 4, gy = by * 4 + i / 4;
        for (int t = 0; t < 4; ++t) {
          const int x = 2 * gx + t % 2, y = 2 * gy + t / 2;
          if (x < width && y < height) out.values[static_cast<std::size_t>(y) * width + x] = texel[t];
        }
      }
    }
  return out;
}

Plane reference_decode_multilevel_plane(const std::uint8_t* bytes, int width, int height,
                                        const std::vector<BandMapping>& detail, const BandMapping& last,
                                        Transform transform, double w, Packing packing) {
  const int levels = static_cast<int>(detail.size()) + 1;
  std::vector<int> widths(1, width), heights(1, height);
  for (int k = 1; k < levels; ++k) {
    widths.push_back((widths.back() + 1) / 2);
    heights.push_back((heights.back() + 1) / 2);
  }
  // Level k's DXT1 blocks start after those of levels 1 .. k-1 (8 bytes per 4x4 groups of the level).
  std::vector<std::size_t> offsets(1, 0);
  for (int k = 1; k < levels; ++k)
    offsets.push_back(offsets.back() + static_cast<std::size_t>((widths[k - 1] + 7) / 8) * ((heights[k - 1] + 7) / 8) * 8);
  Plane scale = reference_decode_wavelet_plane(bytes + offsets.back(), widths.back(), heights.back(), last, transform,
                                               w, packing);
  for (int k = levels - 1; k >= 1; --k) {
    const BandMapping& mapping = detail[static_cast<std::size_t>(k - 1)];
    const int level_width = widths[k - 1], level_height = heights[k - 1];
    Plane out = Plane::zeros(level_width, level_height);
    const int blocks_x = (level_width + 7) / 8, blocks_y = (level_height + 7) / 8;
    for (int by = 0; by < blocks_y; ++by)
      for (int bx = 0; bx < blocks_x; ++bx) {
        double colours[16][3];
        colour_half(bytes + offsets[static_cast<std::size_t>(k - 1)] + (static_cast<std::size_t>(by) * blocks_x + bx) * 8,
                    false, colours);
        for (int i = 0; i < 16; ++i) {
          const int gx = bx * 4 + i % 4, gy = by * 4 + i / 4;
          if (2 * gx >= level_width || 2 * gy >= level_height) continue;
          const double ll = scale.values[static_cast<std::size_t>(gy) * scale.width + gx];
          double hl = unmap(colours[i][0], mapping.centre[1], mapping.half_range[1], mapping.gamma);
          double lh = unmap(colours[i][1], mapping.centre[2], mapping.half_range[2], mapping.gamma);
          double hh = unmap(colours[i][2], mapping.centre[3], mapping.half_range[3], mapping.gamma);
          if (transform == Transform::pi_haar) {
            const double p1 = hl, p2 = lh, p3 = hh;
            lh = (p1 + p2) / 2.0;
            hh = (p2 + p3) * (-0.5 / w);
            hl = p1 - lh - w * hh;
          }
          const double texel[4] = {(ll + hh + lh + hl) / 2.0, (ll - hh + lh - hl) / 2.0, (ll - hh - lh + hl) / 2.0,
                                   (ll + hh - lh - hl) / 2.0};
          for (int t = 0; t < 4; ++t) {
            const int x = 2 * gx + t % 2, y = 2 * gy + t / 2;
            if (x < level_width && y < level_height) out.values[static_cast<std::size_t>(y) * level_width + x] = texel[t];
          }
        }
      }
    scale = out;
  }
  return scale;
}

}  // namespace mavridis
}  // namespace blocklab
