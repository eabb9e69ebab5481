// Extended S3TC, a rejected mode of Munkberg et al. 2008 (section 6.1): "2 x 24 bits (RGB888) for the reference
// colors and a color palette with 32 entries, computed using linear interpolation between the base colors", one 5-bit
// index per texel, 2 x 24 + 16 x 5 = 128 bits. As a plug-in mode of the `munkberg` format it shares the block with
// shape I / shape II and gives 3 bits to the mode selector (munkberg_layout.h). blocklab's design (README.md, "Modes"):
//   * anchor index: swapping the endpoints and mirroring every index (l -> 31 - l) decodes identically, so texel 0's
//     index is stored in 4 bits (its MSB is 0): 1 bit won back losslessly;
//   * the third channel of both endpoints has 7 bits instead of 8: the other 2 selector bits (blue in RGB, the
//     least-weighted channel of the luminance; v in logYuv);
//   * HDR endpoints: "extend S3TC to handle HDR" needs range, so an RGB channel code c of w bits stands for
//     2^(-16 + 32 c / (2^w - 1)) (the half type's range, like the luminance endpoints of the shape modes), code 0 is
//     true 0; the palette interpolates the DECODED endpoints linearly in RGB (a line in RGB space, as in S3TC).
//   * space logyuv (format option ext_s3tc_space, recorded in side data kExtS3tcSpaceKey): channel 0 is the 8-bit
//     log-luminance code of the shape modes (Ybar = -16 + 32 e / 255), channel 1 u = c / 255, channel 2 v = c / 127;
//     the palette interpolates (Ybar, u, v) linearly ("a line in ... logYuv space", section 5) and decodes by eq. 2.
//
// LAYOUT (LSB-first): [0, 3) selector 1,1,0; [3, 26) endpoint 0 = channel 0 (8), 1 (8), 2 (7); [26, 49) endpoint 1;
// [49, 53) texel 0's index (4 bits, anchor); [53, 128) texels 1..15, 5 bits each, texel i at 53 + 5 (i - 1).
//
// DECODING (normative, double, one rounding to float): level l in [0, 31], weights w0 = 31 - l, w1 = l.
//   rgb     A_c = value(code0_c), B_c = value(code1_c); channel = (w0 A_c + w1 B_c) / 31 (w0 A + w1 B is symmetric
//           under the anchor swap, so both orientations decode bit-identically).
//   logyuv  q = w0 e0 + w1 e1; Y = 0 when q == 0 (eq. 3 true black), else 2^(-16 + 32 q / (255 * 31));
//           u = (w0 u0 + w1 u1) / 31 and v = (w0 v0 + w1 v1) / 31 with u_k = code / 255, v_k = code / 127;
//           R = v Y / wr, G = max(0, 1 - u - v) Y / wg, B = u Y / wb (core/color_spaces.h Rec. 601 weights).
#pragma once

#include <array>
#include <cmath>
#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "core/blocks.h"
#include "formats/munkberg/munkberg_color_spaces.h"
#include "core/scalar.h"
#include "formats/munkberg/munkberg_layout.h"

namespace blocklab::munkberg {

constexpr int kExtS3tcChannels = 3;
constexpr std::array<int, kExtS3tcChannels> kExtS3tcChannelBits = {8, 8, 7};
constexpr int kExtS3tcEndpointBits = 8 + 8 + 7;                       // 23 per endpoint
constexpr int kExtS3tcIndexBits = 5;                                  // 32-entry line
constexpr int kExtS3tcLevelsMinusOne = (1 << kExtS3tcIndexBits) - 1;  // 31
constexpr int kExtS3tcAnchorIndexBits = kExtS3tcIndexBits - 1;        // texel 0
constexpr int kExtS3tcAnchorIndexMax = (1 << kExtS3tcAnchorIndexBits) - 1;   // 15
constexpr int kExtS3tcEndpointPosition = kExtS3tcSelectorBits;
constexpr int kExtS3tcIndexPosition = kExtS3tcEndpointPosition + 2 * kExtS3tcEndpointBits;   // 49
constexpr int kExtS3tcTotalBits =
    kExtS3tcSelectorBits + 2 * kExtS3tcEndpointBits + kExtS3tcAnchorIndexBits + (kTexels - 1) * kExtS3tcIndexBits;
static_assert(kExtS3tcChannelBits[0] + kExtS3tcChannelBits[1] + kExtS3tcChannelBits[2] == kExtS3tcEndpointBits,
              "endpoint channel widths");
static_assert(kExtS3tcTotalBits == kBlockBits, "extended S3TC fields must fill the 128-bit block exactly");

enum class ExtS3tcSpace { rgb = 0, logyuv = 1 };
// Side-data key: one value, 0 = rgb, 1 = logyuv (absent = rgb).
constexpr const char* kExtS3tcSpaceKey = "munkberg_ext_s3tc_space";
// The space recorded in a texture's side data; Error on a malformed value.
ExtS3tcSpace ext_s3tc_space_of(const std::map<std::string, std::vector<double>>& side_data);

struct ExtS3tcParams {
  std::array<std::array<int, kExtS3tcChannels>, 2> endpoint{};   // codes, channel c in 0 .. 2^bits[c] - 1
  std::array<std::uint8_t, kTexels> index{};                       // 0 .. 31; index[0] <= 15 (anchor)
  bool operator==(const ExtS3tcParams& other) const { return endpoint == other.endpoint && index == other.index; }
};

// Error("munkberg: ext_s3tc <field>: ...") on an out-of-range field (also index[0] > 15: canonicalize first).
void pack_ext_s3tc(const ExtS3tcParams& params, std::uint8_t* bytes);
// Error unless block_mode_of(bytes) == ext_s3tc. pack(unpack(b)) == b for every such b.
ExtS3tcParams unpack_ext_s3tc(const std::uint8_t* bytes);
// Anchor convention: when index[0] > 15, swap the endpoints and mirror the indices; decoding is unchanged.
void canonicalize_ext_s3tc(ExtS3tcParams* params);

// Dequantised RGB endpoint channel: code 0 is 0, otherwise 2^(-16 + 32 c / (2^bits - 1)).
inline double ext_s3tc_rgb_value(int code, int bits) {
  if (code == 0) return 0.0;   // code 0: true zero (the HDR analogue of eq. 3's black level)
  return std::exp2(kLogLumMin + (kLogLumRange * static_cast<double>(code)) / static_cast<double>((1 << bits) - 1));
}

// The templated decoder. x[6] = the dequantised endpoint values (rgb: the linear channel values A_0..2, B_0..2;
// logyuv: e0 in code units, u0, v0 as values, e1, u1, v1), as T (double, Jet, Interval). Integer decisions (true
// black in logyuv) are taken on params' codes, never on T.
template <typename T>
void decode_ext_s3tc(const ExtS3tcParams& params, ExtS3tcSpace space, const T x[6], T rgb[kTexels][3]) {
  using std::exp2;
  const double n = static_cast<double>(kExtS3tcLevelsMinusOne);
  for (int i = 0; i < kTexels; ++i) {
    const int l = params.index[static_cast<std::size_t>(i)];
    const T w0(static_cast<double>(kExtS3tcLevelsMinusOne - l)), w1(static_cast<double>(l));
    if (space == ExtS3tcSpace::rgb) {
      for (int c = 0; c < 3; ++c) rgb[i][c] = (w0 * x[c] + w1 * x[3 + c]) / T(n);
      continue;
    }
    const std::int64_t q_code = static_cast<std::int64_t>(kExtS3tcLevelsMinusOne - l) * params.endpoint[0][0] +
                                static_cast<std::int64_t>(l) * params.endpoint[1][0];
    const T q = w0 * x[0] + w1 * x[3];
    const T log_luminance = T(kLogLumMin) + (T(kLogLumRange) * q) / T(255.0 * n);
    // Eq. (3): q == 0 (both weighted codes 0) is true black.
    const T luminance = logyuv_luminance_from_code(q_code, std::int64_t{0}, log_luminance);
    const T u = (w0 * x[1] + w1 * x[4]) / T(n);
    const T v = (w0 * x[2] + w1 * x[5]) / T(n);
    rgb[i][0] = (v * luminance) / T(kRec601WeightR);
    rgb[i][1] = (max(T(0.0), T(1.0) - u - v) * luminance) / T(kRec601WeightG);
    rgb[i][2] = (u * luminance) / T(kRec601WeightB);
  }
}

// x of decode_ext_s3tc for a params value.
std::array<double, 6> ext_s3tc_parameters(const ExtS3tcParams& params, ExtS3tcSpace space);
// decode_ext_s3tc<double> as float texels, alpha 1.
BlockTexels decode_ext_s3tc_params(const ExtS3tcParams& params, ExtS3tcSpace space);
// The oracle (ext_s3tc_reference_decode.cpp): bits read one at a time, no shared code with the above.
BlockTexels reference_decode_ext_s3tc(const std::uint8_t* bytes, ExtS3tcSpace space);

}  // namespace blocklab::munkberg
