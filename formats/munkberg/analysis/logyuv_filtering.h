// Texture filtering before the colour transform, Munkberg, Clarberg, Hasselgren, Akenine-Moeller, "Practical HDR
// Texture Compression", CGF 27(6), 2008, section 4, eqs. (7)-(10) and the luminance normalisation trick.
//
// A texel of the logYuv colour space (section 3.1, eq. 2) decodes to linear luminance Y (2^Ybar, or 0 for the
// eq. 3 black level) and chrominance (u, v); the colour transform is
//     R = v Y / wr,   G = (1 - u - v) Y / wg,   B = u Y / wb.
// Correct filtering interpolates R, G, B after the transform (eq. 7, eq. 8). Filtering before the transform
// interpolates Y, u, v and transforms once (eq. 9); in 1D with weights (1 - alpha, alpha) the red error is
//     eps = (1 / wr) alpha (alpha - 1) (v2 - v1) (Y2 - Y1)                                              (eq. 10)
// Normalisation (section 4): every texel i is rescaled by c_i = 2^k_i, Y_i' = Y_i / c_i, u_i' = c_i u_i,
// v_i' = c_i v_i (so v_i' Y_i' = v_i Y_i, the products stay exact), with k_i chosen by comparing the magnitude of Y_i
// with that of a reference texel, so all Y_i' are within a factor of about 2 of each other and the Y difference in
// eq. 10 shrinks. Green uses the interpolated shift, G = (c - u' - v') Y' / wg with c = sum w_i c_i (section 4,
// "replace the constant 1 with the bit shift factor"). The same weights serve 1D (two texels), bilinear (four) and
// trilinear (eight) filtering.
//
// Choices the paper leaves open (documented in configs/papers/munkberg2008/README.md):
//   * k rule: `nearest`  k = round(log2 Y_i - log2 Y_ref) (Y_i' / Y_ref within [2^-1/2, 2^1/2]);
//             `exponent` k = e(Y_i) - e(Y_ref), e the binary exponent of the float (what comparing the exponent
//             bits in hardware gives; Y_i' / Y_ref within (1/2, 2));
//             `truncate` k = trunc(log2 Y_i - log2 Y_ref) (shift only by whole octaves of difference: texels within
//             a factor 2 of the reference are left alone, so neighbours of similar chroma keep v2 - v1 small;
//             blocklab's variant, measured beside the others in the README).
//   * reference texel: `first` (Y1 in the paper's 1D example; texel 0 of a footprint) or `brightest`.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "core/color_spaces.h"

namespace blocklab::munkberg {

// A decoded logYuv texel: linear luminance (>= 0; 0 is the eq. 3 black) and the chrominance of eq. 2.
struct FilterTexel {
  double luminance = 0.0;
  double u = 0.0;
  double v = 0.0;
};

enum class ShiftRule { nearest, exponent, truncate };
enum class ShiftReference { first, brightest };

ShiftRule shift_rule_from_string(const std::string& text);   // nearest | exponent | truncate; throws Error
ShiftReference shift_reference_from_string(const std::string& text);   // first | brightest; throws Error
const char* to_string(ShiftRule rule);
const char* to_string(ShiftReference reference);

// Largest |k| used: 2^512 keeps Y / c and c v finite and normal in double for every float luminance (|log2| < 150);
// only absurd double inputs hit the clamp, and they then get a partial normalisation, never an Inf or a 0/0.
constexpr int kMaxShift = 512;

// Texel of linear RGB (>= 0): Y = wr R + wg G + wb B, (u, v) of eq. 2 (core/color_spaces.h; black gets the grey
// chrominance (wb, wr) and luminance 0, the eq. 3 black level, so it decodes to exact black).
FilterTexel filter_texel_from_rgb(const Rgb<double>& rgb);
// The colour transform of eq. 2 (inverse), R = v Y / wr etc.
Rgb<double> rgb_from_filter_texel(const FilterTexel& texel);

// k for a texel of luminance `luminance` against the reference luminance. 0 when either is 0 (a black texel has
// nothing to normalise: Y' = 0 contributes 0 whatever its chroma). Clamped to [-kMaxShift, kMaxShift].
int normalisation_shift(double luminance, double reference_luminance, ShiftRule rule);

// The reference texel of a footprint of n >= 1 texels: `first` is texel 0 unless it is black (then `brightest`,
// since shifts against a black reference are all 0); `brightest` is the largest luminance (lowest index on ties).
std::size_t normalisation_reference(const FilterTexel* texels, std::size_t n, ShiftReference reference);

// Eq. 7 / eq. 8: sum_i w_i RGB_i, each texel transformed first (the correct result), evaluated in eq. 8's form
// (1 / wr) sum_i w_i v_i Y_i (likewise for G and B).
Rgb<double> filter_after_transform(const FilterTexel* texels, const double* weights, std::size_t n);
// Eq. 9: Y, u, v interpolated, then one transform.
Rgb<double> filter_before_transform(const FilterTexel* texels, const double* weights, std::size_t n);
// Section 4's trick: shifts k_i against the reference texel, then Y', u', v', c interpolated and
// (R, G, B) = (v' Y' / wr, (c - u' - v') Y' / wg, u' Y' / wb). `shifts_out` (optional, n entries) receives k_i.
Rgb<double> filter_before_transform_normalised(const FilterTexel* texels, const double* weights, std::size_t n,
                                               ShiftRule rule, ShiftReference reference, int* shifts_out = nullptr);

// Eq. 10, the red error of the un-normalised filter in 1D. With each texel's (v, Y) replaced by (c v, Y / c) it is
// also the error of the normalised filter: eq. 8 depends only on the products v Y, which the shift keeps.
double red_error_closed_form(double v1, double v2, double y1, double y2, double alpha);

// Figure 1: the red error of the 1D filter between texel 1 (v1, Y1) and texel 2 (v2, Y2), weights (1 - alpha,
// alpha), for `samples` >= 2 values of Y2 from y2_first to y2_last (linear or geometric spacing).
struct Figure1Point {
  double y2 = 0.0;
  double correct_red = 0.0;             // eq. 8
  double plain_red = 0.0;               // eq. 9
  double plain_error = 0.0;             // eq. 9 - eq. 8
  double plain_closed_form = 0.0;       // eq. 10
  int shift1 = 0, shift2 = 0;           // k of texel 1 and texel 2 (the reference texel has k = 0)
  double normalised_red = 0.0;
  double normalised_error = 0.0;        // normalised - eq. 8
  double normalised_closed_form = 0.0;  // eq. 10 with (c_i v_i, Y_i / c_i)
};
struct Figure1Setup {
  double v1 = 0.25, v2 = 0.1, y1 = 1.0, y2_first = 0.1, y2_last = 10.0, alpha = 0.5;
  int samples = 991;
  bool geometric = false;               // geometric spacing of Y2 (else linear)
  ShiftRule rule = ShiftRule::nearest;
  ShiftReference reference = ShiftReference::first;
};
// Throws Error for samples < 2, non-finite or negative inputs, alpha outside [0, 1], a geometric range with Y2 <= 0.
std::vector<Figure1Point> figure1_curve(const Figure1Setup& setup);

}  // namespace blocklab::munkberg
