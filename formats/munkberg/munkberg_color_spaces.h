// The colour spaces of "Practical HDR Texture Compression" (Munkberg et al. 2008) that only the `munkberg` format
// uses, each a forward and an inverse transform, templated on the scalar type like core/color_spaces.h (whose Rgb,
// Rec. 601 weights and chrominance regulariser they share):
//   logYuv      section 3.1, eq. (2); the black-level rule of the stored codes, eq. (3).
//   Roimela Yuv section 3.2, eq. (4) (Roimela, Aarnio, Itaranta 2006), a colour space the paper compares against.
//   LUVW        section 3.3, eq. (5) (Wang et al. 2007, their eq. 1 and its inverse R,G,B = (U,V,W) L), another; the
//               `wang` format has its own bit-exact encoder-side version (formats/wang/wang_color_space.h).
#pragma once

#include <cmath>
#include <cstdint>

#include "core/color_spaces.h"
#include "core/scalar.h"

namespace blocklab {

// logYuv (Practical HDR 2008): log2 luminance and two chrominance channels in [0, 1].
template <typename T>
struct LogYuv {
  T log_luminance;   // Ybar = log2(Y)
  T u;               // ubar = wb B / Y
  T v;               // vbar = wr R / Y
};

// Roimela et al. Yuv: linear luminance Y~ and two chrominance channels (u, v, u + v in [0, 1] for non-negative RGB).
template <typename T>
struct RoimelaYuv {
  T luminance;   // Y~ = (R + 2G + B) / 4
  T u;           // R / (4 Y~)
  T v;           // B / (4 Y~)
};

// Smallest luminance logYuv takes the log of: 2^-28. Every non-black texel whose channels are half values has
// Y >= wb * 2^-24 (the smallest positive half, 2^-24, in blue alone) = 2^-27.13 > 2^-28, so every non-black fp16 texel
// keeps its true log-luminance and round-trips; black (Y = 0) and luminances below 2^-28 are raised to 2^-28
// (log2 = -28) with their chrominance kept. A format that needs true black uses eq. (3), see
// logyuv_luminance_from_code.
constexpr double kLogYuvLuminanceFloor = 0x1p-28;

// ---- logYuv (Practical HDR 2008, eq. 2 and eq. 3) ---------------------------------------------------------------
// Forward, eq. (2): Y = wr R + wg G + wb B; (Ybar, ubar, vbar) = (log2 Y, wb B / Y, wr R / Y).
// Edge cases: Y below kLogYuvLuminanceFloor (including black) is raised to the floor for the logarithm; the
// chrominance ratios use kChromaRegulariser (black gets grey chrominance (wb, wr)).
template <typename T>
LogYuv<T> rgb_to_logyuv(const Rgb<T>& rgb) {
  using std::log2;
  const T luminance = T(kRec601WeightR) * rgb.r + T(kRec601WeightG) * rgb.g + T(kRec601WeightB) * rgb.b;
  // No log of 0: black and near-black luminance is raised to the named floor (2^-28).
  const T floored_luminance = max(luminance, T(kLogYuvLuminanceFloor));
  // No 0/0 for black: tau added to numerator and (grey-weighted) denominator; the weights sum to 1, so the
  // denominator of a grey texel of value 1 is 1 and tau is added once.
  const T regularised_luminance = luminance + T(kChromaRegulariser);
  LogYuv<T> out{log2(floored_luminance),
                T(kRec601WeightB) * (rgb.b + T(kChromaRegulariser)) / regularised_luminance,
                T(kRec601WeightR) * (rgb.r + T(kChromaRegulariser)) / regularised_luminance};
  return out;
}

// Inverse, eq. (2): (R, G, B) = (vbar 2^Ybar / wr, (1 - ubar - vbar) 2^Ybar / wg, ubar 2^Ybar / wb).
// Luminance is always 2^Ybar here (never 0); apply eq. (3) to stored codes with logyuv_luminance_from_code and
// then logyuv_to_rgb_from_luminance.
template <typename T>
Rgb<T> logyuv_to_rgb_from_luminance(const T& luminance, const T& u, const T& v) {
  Rgb<T> out{v * luminance / T(kRec601WeightR), (T(1) - u - v) * luminance / T(kRec601WeightG),
             u * luminance / T(kRec601WeightB)};
  return out;
}

template <typename T>
Rgb<T> logyuv_to_rgb(const LogYuv<T>& yuv) {
  using std::exp2;
  return logyuv_to_rgb_from_luminance(exp2(yuv.log_luminance), yuv.u, yuv.v);
}

// Black-level rule, eq. (3): Y = 0 if Ybar = Ybar_min, else 2^Ybar. The comparison is made on the stored integer
// codes (a format quantises Ybar to codes; `minimum_code` is the code of Ybar_min), so the branch is on integers,
// never on T, and the function serves every scalar type. `log_luminance` is the dequantised Ybar of `code`.
template <typename T>
T logyuv_luminance_from_code(std::int64_t code, std::int64_t minimum_code, const T& log_luminance) {
  using std::exp2;
  // Eq. (3): the smallest code is true black, not 2^Ybar_min.
  if (code == minimum_code) return T(0);
  return exp2(log_luminance);
}

// ---- Roimela et al. Yuv (Practical HDR 2008, eq. 4) ------------------------------------------------------------
// Forward, eq. (4): Y~ = (R + 2G + B) / 4; (u, v) = (R / (4 Y~), B / (4 Y~)).
// Edge case Y~ = 0 (black): u = v = 1/4 (grey chrominance, via kChromaRegulariser); the inverse multiplies by
// Y~ = 0 and so returns exact black.
template <typename T>
RoimelaYuv<T> rgb_to_roimela_yuv(const Rgb<T>& rgb) {
  const T four_luminance = rgb.r + T(2) * rgb.g + rgb.b;
  // No 0/0 for black: tau added to R (or B) and 4 tau to 4 Y~ (4 Y~ of grey 1 is 4).
  const T regularised_divisor = four_luminance + T(4.0 * kChromaRegulariser);
  RoimelaYuv<T> out{four_luminance * T(0.25), (rgb.r + T(kChromaRegulariser)) / regularised_divisor,
                    (rgb.b + T(kChromaRegulariser)) / regularised_divisor};
  return out;
}

// Inverse, eq. (4): (R, G, B) = Y~ (4u, 2(1 - u - v), 4v).
template <typename T>
Rgb<T> roimela_yuv_to_rgb(const RoimelaYuv<T>& yuv) {
  Rgb<T> out{yuv.luminance * (T(4) * yuv.u), yuv.luminance * (T(2) * (T(1) - yuv.u - yuv.v)),
             yuv.luminance * (T(4) * yuv.v)};
  return out;
}

// Wang et al. LUVW: the length of the RGB vector and its direction (a unit vector, components in [0, 1]).
template <typename T>
struct Luvw {
  T l, u, v, w;
};

// ---- LUVW (Practical HDR 2008 eq. 5; Wang et al. 2007 eq. 1) ---------------------------------------------------
// Forward, eq. (5): L = sqrt(R^2 + G^2 + B^2); (U, V, W) = (R, G, B) / L.
// Edge case L = 0 (black): (U, V, W) = (1, 1, 1) / sqrt(3) (grey, via kChromaRegulariser); the inverse multiplies
// by L = 0 and so returns exact black.
template <typename T>
Luvw<T> rgb_to_luvw(const Rgb<T>& rgb) {
  using std::sqrt;
  const T length = sqrt(square(rgb.r) + square(rgb.g) + square(rgb.b));
  // No 0/0 for black: tau added to each channel and sqrt(3) tau to L (L of grey 1 is sqrt(3)).
  constexpr double kSqrt3 = 1.7320508075688772935;
  const T regularised_length = length + T(kSqrt3 * kChromaRegulariser);
  Luvw<T> out{length, (rgb.r + T(kChromaRegulariser)) / regularised_length,
              (rgb.g + T(kChromaRegulariser)) / regularised_length,
              (rgb.b + T(kChromaRegulariser)) / regularised_length};
  return out;
}

// Inverse (Wang et al. 2007, inverse of eq. 1): (R, G, B) = (U, V, W) L.
template <typename T>
Rgb<T> luvw_to_rgb(const Luvw<T>& luvw) {
  Rgb<T> out{luvw.u * luvw.l, luvw.v * luvw.l, luvw.w * luvw.l};
  return out;
}

}  // namespace blocklab
