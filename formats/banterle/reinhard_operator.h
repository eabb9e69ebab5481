// Reinhard's global photographic operator and its closed-form inverse, as used by Banterle et al. 2008
// ("A GPU-friendly Method for High Dynamic Range Texture Compression using Inverse Tone Mapping", GI 2008), eqs. 1-2;
// SPECS.md section 3.
//
// With the scaled luminance x = alpha * L / L_H (L_H the image mean, see reinhard_estimate.h):
//   eq. 1 (forward)  f(L) = x * (1 + x / Lwhite^2) / (1 + x)            (Lwhite lives in the scaled domain)
//   eq. 2 (inverse)  g(L') = (Lwhite^2 L_H / (2 alpha)) * (L' - 1 + sqrt((1 - L')^2 + 4 L' / Lwhite^2))
// Eq. 2 is evaluated in the algebraically identical rationalised form
//   g(L') = (2 L' L_H / alpha) / (sqrt((1 - L')^2 + 4 L' / Lwhite^2) + 1 - L'),
// because the literal form cancels catastrophically for small L' and large Lwhite (L' - 1 + sqrt(...) is the
// difference of two numbers close to 1 - L'; at Lwhite = 1e6 it loses about 12 of 16 digits). The denominator is
// >= 2 / Lwhite > 0 on [0, 1], so the form never divides by zero; g(0) = 0 and g(1) = Lwhite * L_H / alpha.
//
// Both are templates on the scalar type (double, ceres::Jet, blocklab::Interval; core/scalar.h rules) so the same
// code serves the encoder, the decoder's LUT and the parameter-fit Problems (tmo_fit_problem.h).
//
// Luminance: the weights of the paper's decoding shader (Listing 1), (0.21, 0.72, 0.07), which sum to 1, are used
// by the encoder AND the decoder. (Eq. 1's text gives 0.213, 0.72, 0.072, summing to 1.005; the decoder must use the
// weights the encoder used or the inverse is not an inverse, and the shader is the normative decoder.)
#pragma once

#include <cmath>

#include "core/scalar.h"

namespace blocklab {

// Listing 1: const float3 LUMINANCE = float3(0.21, 0.72, 0.07).
constexpr float kBanterleLumaWeights[3] = {0.21f, 0.72f, 0.07f};

// Luminance of an RGB triple in float, in the fixed order R, G, B (what the decoder computes; -ffp-contract=off
// keeps it one multiply and one add per term on every machine).
inline float banterle_luminance(const float rgb[3]) {
  return kBanterleLumaWeights[0] * rgb[0] + kBanterleLumaWeights[1] * rgb[1] + kBanterleLumaWeights[2] * rgb[2];
}

// Eq. 1 on the scaled luminance x = alpha * L / L_H (x >= 0): the tone-mapped luminance L' (in [0, 1] for
// x <= Lwhite, above 1 beyond, where the quantiser clips it).
template <typename T>
T reinhard_forward_scaled(const T& x, const T& l_white) {
  return x * (T(1.0) + x / square(l_white)) / (T(1.0) + x);
}

// Eq. 2 without the 1 / scale factor: G(L') = g(L') * alpha / L_H = x, the scaled luminance of the tone-mapped
// value L' in [0, 1] (rationalised form, see the file comment).
template <typename T>
T reinhard_inverse_scaled(const T& tone_mapped, const T& l_white) {
  using std::sqrt;
  const T one_minus = T(1.0) - tone_mapped;
  const T discriminant = square(one_minus) + T(4.0) * tone_mapped / square(l_white);
  return T(2.0) * tone_mapped / (sqrt(discriminant) + one_minus);
}

// Eq. 2 in full: the HDR luminance of tone-mapped luminance L' for parameters (alpha, Lwhite, L_H).
template <typename T>
T reinhard_inverse(const T& tone_mapped, const T& alpha, const T& l_white, const T& mean) {
  return reinhard_inverse_scaled(tone_mapped, l_white) * mean / alpha;
}

}  // namespace blocklab
