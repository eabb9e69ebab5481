// Colour spaces used by the HDR block formats and metrics, each a forward and an inverse transform.
//
// Sources (equation numbers are those of the cited text):
//   log[RGB]    "Practical HDR Texture Compression" (Practical HDR 2008 below), CGF 27(6), 2008, section 3.4,
//               eq. (6) (Xu, Pattanaik, Hughes 2005).
//   YCoCg-R     Malvar & Sullivan, "YCoCg-R: A Color Space with RGB Reversibility and Low Dynamic Range",
//               JVT-I014, 2003 (lifting steps; inverse also quoted in Mavridis & Papaioannou 2012, section 3.2).
//   CIE L*a*b*  CIE 15:2004 (CIE 1976 L*a*b*, exact rational epsilon = 216/24389 and kappa = 24389/27), from
//               linear RGB with ITU-R BT.709 / sRGB primaries and D65 white through XYZ (IEC 61966-2-1).
//
// Scalar types. The continuous transforms (log[RGB]; the paper's other spaces, logYuv, Roimela Yuv and LUVW,
// live with the munkberg format in formats/munkberg/munkberg_color_spaces.h) are templates on T and work for double,
// float, ceres::Jet and blocklab::Interval (DESIGN.md rules: constants as T(k), unqualified maths calls after
// `using std::...`, no `if` on a T value; min/max/square come from core/scalar.h). CIE L*a*b* is piecewise and
// needs a cube root: it works for double, float and ceres::Jet (the derivative of the branch taken), not for
// Interval (Boost.Interval has no cbrt). YCoCg-R is integer lifting and works on int32.
//
// Input range. Forward transforms expect linear, finite, non-negative RGB (what the input policy guarantees,
// core/input_policy.h). Numeric edge cases (black texels, luminance below the log floor) are handled by the named
// constants below and documented at each function.
#pragma once

#include <cmath>
#include <cstdint>
#include <type_traits>

#include "core/scalar.h"

namespace blocklab {

// ---- value types -------------------------------------------------------------------------------------------------
template <typename T>
struct Rgb {
  T r, g, b;
};

// Xu et al. log[RGB]: per-channel log2.
template <typename T>
struct LogRgb {
  T log_r, log_g, log_b;
};

// YCoCg-R: for N-bit RGB, Y has N bits (unsigned) and Co, Cg have N + 1 bits (signed).
struct YCoCgR {
  std::int32_t y, co, cg;
};

// CIE 1976 L*a*b* (L* in [0, 100] for colours no brighter than the white point).
template <typename T>
struct Lab {
  T l, a, b;
};

// ---- named constants ---------------------------------------------------------------------------------------------
// Luminance weights of logYuv. "Practical HDR Texture Compression" (2008) section 3.1: "weights according to the Rec.
// 601 [Poy03] standard", i.e. the ITU-R BT.601 luma coefficients (Poynton, Digital Video and HDTV, 2003). They sum to
// 1, so grey (c, c, c) has Y = c and chrominance (u, v) = (wb, wr).
constexpr double kRec601WeightR = 0.299;
constexpr double kRec601WeightG = 0.587;
constexpr double kRec601WeightB = 0.114;

// Smallest channel value log[RGB] takes the log of: 2^-24, the smallest positive half (a subnormal). Every positive
// fp16 channel value is >= 2^-24 and round-trips; 0 (and anything below 2^-24) maps to log2 = -24.
constexpr double kLogRgbFloor = 0x1p-24;

// Chrominance regulariser tau for the ratio spaces (logYuv u/v, Roimela u/v, LUVW U/V/W): each ratio c / S is
// computed as (c + tau) / (S + tau * S(1, 1, 1)), where S(1,1,1) is the divisor of a grey texel of value 1.
//   * Black (S = 0): the ratio is the chrominance of grey instead of 0/0 (neutral, so a black texel never drags a
//     block's chroma endpoints; it decodes to black in Roimela and LUVW because Y~ = 0 / L = 0 multiply it).
//   * Grey (c, c, c): the ratio is exactly the grey chrominance for every c.
//   * Otherwise the change is at most tau / S relative: with tau = 2^-100 and S >= 2^-28 (any non-black fp16
//     texel) that is <= 2^-72, below double precision; in float, tau is below half an ulp of any S >= 2^-75 and
//     vanishes. 2^-100 is a normal float and double, so it behaves the same in both.
// For Interval arguments that contain S = 0 the divisor stays >= tau > 0 (wide but finite bounds, no division by
// an interval containing 0).
constexpr double kChromaRegulariser = 0x1p-100;

// ---- log[RGB] (Practical HDR 2008 eq. 6) -------------------------------------------------------------------------
// Forward, eq. (6): (R', G', B') = (log2 R, log2 G, log2 B). Edge case: channels below kLogRgbFloor (including 0)
// are raised to 2^-24 before the logarithm.
template <typename T>
LogRgb<T> rgb_to_log_rgb(const Rgb<T>& rgb) {
  using std::log2;
  // No log of 0: each channel is raised to the named floor (the smallest positive half).
  const T floor_value = T(kLogRgbFloor);
  LogRgb<T> out{log2(max(rgb.r, floor_value)), log2(max(rgb.g, floor_value)), log2(max(rgb.b, floor_value))};
  return out;
}

// Inverse of eq. (6): per-channel exp2 (a floored 0 comes back as 2^-24).
template <typename T>
Rgb<T> log_rgb_to_rgb(const LogRgb<T>& log_rgb) {
  using std::exp2;
  Rgb<T> out{exp2(log_rgb.log_r), exp2(log_rgb.log_g), exp2(log_rgb.log_b)};
  return out;
}

// ---- YCoCg-R (Malvar & Sullivan 2003) ----------------------------------------------------------------------------
// Lossless integer lifting; `>> 1` is floor(x / 2) (arithmetic shift, checked in color_spaces.cpp).
// For N-bit RGB (0 <= R, G, B < 2^N): 0 <= Y < 2^N and -(2^N - 1) <= Co, Cg <= 2^N - 1 (N + 1 bits signed).
// Exact for any int32 R, G, B with |R|, |G|, |B| < 2^29 (no intermediate overflows).
//   Forward: Co = R - B; t = B + (Co >> 1); Cg = G - t; Y = t + (Cg >> 1).
//   Inverse: t = Y - (Cg >> 1); G = Cg + t; B = t - (Co >> 1); R = B + Co.
YCoCgR rgb_to_ycocg_r(std::int32_t r, std::int32_t g, std::int32_t b);
Rgb<std::int32_t> ycocg_r_to_rgb(const YCoCgR& ycocg);

// Bits of each YCoCg-R channel for `rgb_bits`-bit RGB: Y rgb_bits (unsigned), Co and Cg rgb_bits + 1 (signed).
constexpr int ycocg_r_luma_bits(int rgb_bits) { return rgb_bits; }
constexpr int ycocg_r_chroma_bits(int rgb_bits) { return rgb_bits + 1; }

// ---- CIE 1976 L*a*b* from linear Rec.709/sRGB RGB (D65) ----------------------------------------------------------
// A 3x3 matrix, row-major.
struct ColorMatrix3 {
  double m[3][3];
};

namespace color_detail {

constexpr ColorMatrix3 multiply(const ColorMatrix3& a, const ColorMatrix3& b) {
  ColorMatrix3 out{};
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      double sum = 0.0;
      for (int k = 0; k < 3; ++k) sum += a.m[i][k] * b.m[k][j];
      out.m[i][j] = sum;
    }
  return out;
}

// Inverse through the adjugate (the matrices here are well conditioned: determinants ~0.2 to 5).
constexpr ColorMatrix3 inverse(const ColorMatrix3& a) {
  const auto& m = a.m;
  const double c00 = m[1][1] * m[2][2] - m[1][2] * m[2][1];
  const double c01 = m[1][2] * m[2][0] - m[1][0] * m[2][2];
  const double c02 = m[1][0] * m[2][1] - m[1][1] * m[2][0];
  const double determinant = m[0][0] * c00 + m[0][1] * c01 + m[0][2] * c02;
  ColorMatrix3 out{};
  out.m[0][0] = c00 / determinant;
  out.m[1][0] = c01 / determinant;
  out.m[2][0] = c02 / determinant;
  out.m[0][1] = (m[0][2] * m[2][1] - m[0][1] * m[2][2]) / determinant;
  out.m[1][1] = (m[0][0] * m[2][2] - m[0][2] * m[2][0]) / determinant;
  out.m[2][1] = (m[0][1] * m[2][0] - m[0][0] * m[2][1]) / determinant;
  out.m[0][2] = (m[0][1] * m[1][2] - m[0][2] * m[1][1]) / determinant;
  out.m[1][2] = (m[0][2] * m[1][0] - m[0][0] * m[1][2]) / determinant;
  out.m[2][2] = (m[0][0] * m[1][1] - m[0][1] * m[1][0]) / determinant;
  return out;
}

// RGB -> XYZ (Y of white = 1) from the chromaticities of the primaries and the white point (SMPTE RP 177-1993
// derivation): columns are the primaries' XYZ at Y = 1, scaled so that RGB (1, 1, 1) maps to the white point.
constexpr ColorMatrix3 rgb_to_xyz_from_chromaticities(double xr, double yr, double xg, double yg, double xb,
                                                      double yb, double xw, double yw) {
  const ColorMatrix3 primaries{{{xr / yr, xg / yg, xb / yb}, {1.0, 1.0, 1.0},
                                {(1 - xr - yr) / yr, (1 - xg - yg) / yg, (1 - xb - yb) / yb}}};
  const double white[3] = {xw / yw, 1.0, (1 - xw - yw) / yw};
  const ColorMatrix3 primaries_inverse = inverse(primaries);
  ColorMatrix3 scale{};
  for (int i = 0; i < 3; ++i) {
    double sum = 0.0;
    for (int k = 0; k < 3; ++k) sum += primaries_inverse.m[i][k] * white[k];
    scale.m[i][i] = sum;
  }
  return multiply(primaries, scale);
}

}  // namespace color_detail

// ITU-R BT.709 primaries (0.64, 0.33), (0.30, 0.60), (0.15, 0.06) and D65 white (0.3127, 0.3290) — the sRGB ones of
// IEC 61966-2-1. The derived matrix matches the standard's rounded 4-decimal table (0.4124 0.3576 0.1805 / ...).
inline constexpr ColorMatrix3 kRec709RgbToXyz =
    color_detail::rgb_to_xyz_from_chromaticities(0.64, 0.33, 0.30, 0.60, 0.15, 0.06, 0.3127, 0.3290);
// The exact inverse of kRec709RgbToXyz (not the standard's separately rounded inverse table, which would make the
// round trip lose ~1e-4).
inline constexpr ColorMatrix3 kXyzToRec709Rgb = color_detail::inverse(kRec709RgbToXyz);
// Reference white Xn, Yn, Zn = kRec709RgbToXyz * (1, 1, 1): D65 with Yn = 1, so RGB (1, 1, 1) is L* = 100,
// a* = b* = 0 up to rounding.
inline constexpr double kD65WhiteX = kRec709RgbToXyz.m[0][0] + kRec709RgbToXyz.m[0][1] + kRec709RgbToXyz.m[0][2];
inline constexpr double kD65WhiteY = kRec709RgbToXyz.m[1][0] + kRec709RgbToXyz.m[1][1] + kRec709RgbToXyz.m[1][2];
inline constexpr double kD65WhiteZ = kRec709RgbToXyz.m[2][0] + kRec709RgbToXyz.m[2][1] + kRec709RgbToXyz.m[2][2];

// CIE 15:2004 constants in their exact rational form (the decimal 0.008856 / 903.3 of older texts make the two
// pieces of f meet with a small jump; the rational ones make f continuous with a continuous slope at epsilon).
inline constexpr double kCieEpsilon = 216.0 / 24389.0;   // (6/29)^3
inline constexpr double kCieKappa = 24389.0 / 27.0;      // (29/3)^3

namespace color_detail {

// CIE 1976 f(t) = t^(1/3) for t > epsilon, (kappa t + 16) / 116 otherwise.
template <typename T>
T cie_f(const T& t) {
  using std::cbrt;
  // Piecewise at epsilon: below it the cube root is replaced by its tangent line (no infinite slope at 0).
  return select(greater(t, T(kCieEpsilon)), T(cbrt(t)), T((T(kCieKappa) * t + T(16)) / T(116)));
}

// Inverse of cie_f: f^3 for f^3 > epsilon (i.e. f > 6/29), (116 f - 16) / kappa otherwise.
template <typename T>
T cie_f_inverse(const T& f) {
  const T cube = f * f * f;
  return select(greater(cube, T(kCieEpsilon)), cube, T((T(116) * f - T(16)) / T(kCieKappa)));
}

}  // namespace color_detail

// Linear Rec.709 RGB -> XYZ (D65, Y of white = 1).
template <typename T>
Rgb<T> rec709_to_xyz(const Rgb<T>& rgb) {
  const auto& m = kRec709RgbToXyz.m;
  Rgb<T> out{T(m[0][0]) * rgb.r + T(m[0][1]) * rgb.g + T(m[0][2]) * rgb.b,
             T(m[1][0]) * rgb.r + T(m[1][1]) * rgb.g + T(m[1][2]) * rgb.b,
             T(m[2][0]) * rgb.r + T(m[2][1]) * rgb.g + T(m[2][2]) * rgb.b};
  return out;
}

// XYZ -> linear Rec.709 RGB (exact matrix inverse of rec709_to_xyz).
template <typename T>
Rgb<T> xyz_to_rec709(const Rgb<T>& xyz) {
  const auto& m = kXyzToRec709Rgb.m;
  Rgb<T> out{T(m[0][0]) * xyz.r + T(m[0][1]) * xyz.g + T(m[0][2]) * xyz.b,
             T(m[1][0]) * xyz.r + T(m[1][1]) * xyz.g + T(m[1][2]) * xyz.b,
             T(m[2][0]) * xyz.r + T(m[2][1]) * xyz.g + T(m[2][2]) * xyz.b};
  return out;
}

// CIE 1976: L* = 116 f(Y/Yn) - 16, a* = 500 (f(X/Xn) - f(Y/Yn)), b* = 200 (f(Y/Yn) - f(Z/Zn)), with Xn, Yn, Zn the
// D65 white above. Scale: RGB (1, 1, 1) is the white (L* = 100); HDR values above 1 give L* > 100 (the formula is
// applied as is, no clipping). Black is L* = 0 through the linear piece (no cube root of 0 needed).
template <typename T>
Lab<T> rec709_to_lab(const Rgb<T>& rgb) {
  const Rgb<T> xyz = rec709_to_xyz(rgb);
  const T fx = color_detail::cie_f(T(xyz.r / T(kD65WhiteX)));
  const T fy = color_detail::cie_f(T(xyz.g / T(kD65WhiteY)));
  const T fz = color_detail::cie_f(T(xyz.b / T(kD65WhiteZ)));
  Lab<T> out{T(116) * fy - T(16), T(500) * (fx - fy), T(200) * (fy - fz)};
  return out;
}

// Inverse CIE 1976: fy = (L* + 16) / 116, fx = fy + a*/500, fz = fy - b*/200; X/Xn = f^-1(fx) etc.
template <typename T>
Rgb<T> lab_to_rec709(const Lab<T>& lab) {
  const T fy = (lab.l + T(16)) / T(116);
  const T fx = fy + lab.a / T(500);
  const T fz = fy - lab.b / T(200);
  const Rgb<T> xyz{T(kD65WhiteX) * color_detail::cie_f_inverse(fx), T(kD65WhiteY) * color_detail::cie_f_inverse(fy),
                   T(kD65WhiteZ) * color_detail::cie_f_inverse(fz)};
  return xyz_to_rec709(xyz);
}

}  // namespace blocklab
