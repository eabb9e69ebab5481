// The `mavridis` oracle: one wavelet plane decoded straight from the paper (Mavridis & Papaioannou 2012) and the
// DXT5 text, sharing no code with the decoder of mavridis_plane_codec.cpp.
//   DXT5 (KDFS S3TC "BC3"): bytes 0-1 alpha0, alpha1; bytes 2-7 48 bits of 3-bit alpha codes; bytes 8-11 two RGB565
//   colours; bytes 12-15 32 bits of 2-bit colour codes, always the 4-colour palette (c0, c1, (2c0+c1)/3,
//   (c0+2c1)/3), every value an exact fraction of the bit-replicated 8-bit endpoints.
//   Section 3.1: alpha holds LL, RGB hold HL', LH', HH' (Haar: HL, LH, HH).
//   Section 3.2: x = c + r sign(n) |n|^(1/g), n = 2s - 1 (LL: g = 1).
//   Eq. 2 inverted; eq. 1, "the inverse of itself", gives the four texels a, b, c, d of the group (the
//   S-transform of Table 3: its integer inverse on the rounded coefficients).
#include <cmath>

#include "formats/bc7/bc7_reference_decode.h"
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

double unmap(double s, double centre, double half_range, double gamma) {
  const double n = 2.0 * s - 1.0;
  const double magnitude = std::pow(std::fabs(n), 1.0 / gamma);
  return centre + half_range * (n < 0.0 ? -magnitude : magnitude);
}

}  // namespace

Plane reference_decode_wavelet_plane(const std::uint8_t* bytes, int width, int height, const BandMapping& mapping,
                                     Transform transform, double w, Packing packing) {
  Plane out;
  out.width = width;
  out.height = height;
  out.values.assign(static_cast<std::size_t>(width) * height, 0.0);
  const int blocks_x = (width + 7) / 8, blocks_y = (height + 7) / 8;
  for (int by = 0; by < blocks_y; ++by)
    for (int bx = 0; bx < blocks_x; ++bx) {
      const std::uint8_t* block = bytes + (static_cast<std::size_t>(by) * blocks_x + bx) * 16;
      unsigned long long alpha_bits = 0;
      for (int b = 7; b >= 2; --b) alpha_bits = (alpha_bits << 8) | block[b];
      const unsigned c0 = block[8] | (block[9] << 8), c1 = block[10] | (block[11] << 8);
      const unsigned long color_bits =
          block[12] | (block[13] << 8) | (block[14] << 16) | (static_cast<unsigned long>(block[15]) << 24);
      int e0[3] = {static_cast<int>(c0 >> 11), static_cast<int>((c0 >> 5) & 63), static_cast<int>(c0 & 31)};
      int e1[3] = {static_cast<int>(c1 >> 11), static_cast<int>((c1 >> 5) & 63), static_cast<int>(c1 & 31)};
      for (int k = 0; k < 3; ++k) {
        const bool six = k == 1;
        e0[k] = six ? (e0[k] << 2) | (e0[k] >> 4) : (e0[k] << 3) | (e0[k] >> 2);
        e1[k] = six ? (e1[k] << 2) | (e1[k] >> 4) : (e1[k] << 3) | (e1[k] >> 2);
      }
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
          const double texel[4] = {(ll + hl + lh) / 2.0, (ll - hl + lh) / 2.0, (ll + hl - lh) / 2.0, (ll - hl - lh) / 2.0};
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
        const int color_code = static_cast<int>((color_bits >> (2 * i)) & 3);
        double s[4];
        s[0] = alpha_value(block[0], block[1], alpha_code);
        for (int k = 0; k < 3; ++k) {
          const int weights0[4] = {3, 0, 2, 1};
          s[k + 1] = (weights0[color_code] * e0[k] + (3 - weights0[color_code]) * e1[k]) / (3.0 * 255.0);
        }
        const double ll = unmap(s[0], mapping.centre[0], mapping.half_range[0], 1.0);
        double hl = unmap(s[1], mapping.centre[1], mapping.half_range[1], mapping.gamma);
        double lh = unmap(s[2], mapping.centre[2], mapping.half_range[2], mapping.gamma);
        double hh = unmap(s[3], mapping.centre[3], mapping.half_range[3], mapping.gamma);
        if (transform == Transform::pi_haar) {
          // HL' + LH' = 2 LH;  LH' + HH' = -2 w HH;  HL' = HL + LH + w HH.
          const double p1 = hl, p2 = lh, p3 = hh;
          lh = (p1 + p2) / 2.0;
          hh = -(p2 + p3) / (2.0 * w);
          hl = p1 - lh - w * hh;
        }
        // Eq. 1 applied to (LL, HL, LH, HH) returns (a, b, c, d).
        double texel[4] = {(ll + hl + lh + hh) / 2.0, (ll - hl + lh - hh) / 2.0, (ll + hl - lh - hh) / 2.0,
                           (ll - hl - lh + hh) / 2.0};
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
        const int gx = bx * 4 + i % 4, gy = by * 4 + i / 4;
        for (int t = 0; t < 4; ++t) {
          const int x = 2 * gx + t % 2, y = 2 * gy + t / 2;
          if (x < width && y < height) out.values[static_cast<std::size_t>(y) * width + x] = texel[t];
        }
      }
    }
  return out;
}

}  // namespace mavridis
}  // namespace blocklab
