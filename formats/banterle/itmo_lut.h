// The decoder of Banterle et al. 2008: the 256-entry half-float inverse-TMO lookup table of section 4.4 and the
// per-texel expansion of Listing 1 (tex2DITMO), defined to the bit so that decoding is deterministic.
//
// LUT (section 4.4: "we pre-compute, for each texture, Equation 2 into a 1D texture with 256 half floating point
// values"):
//   peak = g(1) = Lwhite * L_H / alpha (double);  frexp(peak) = m * 2^e, m in [0.5, 1);  s = e - 15
//   entry[k] = half(float(ldexp(g(k / 255), -s)))  for k = 0..255, g = eq. 2 in double (reinhard_operator.h),
//   float -> half rounding to nearest even (Imath::half). The power-of-two scale 2^s is blocklab's addition: the
//   paper's LUT holds g itself, which overflows half (65504) for any texture brighter than that; scaling by an
//   exact power of two puts the peak in [2^14, 2^15) and is undone exactly in float (std::ldexp), so for textures
//   whose peak already lies in that binade (s = 0) this is the paper's table. s is derived from the side data, so
//   it is not stored.
// Lookup of a tone-mapped luminance l (the 1D texture's linear filter, entry k at l = k / 255):
//   t = clamp(l * 255, 0, 255) (float);  i = min(floor(t), 254);  w = t - i;
//   v = entry[i] + (entry[i + 1] - entry[i]) * w   (float);   result = ldexp(v, s).
// Texel (Listing 1, lines 7-10), decoded LDR colour c = (r, g, b) and residual d (0 at 4 bpp):
//   l = 0.21 r + 0.72 g + 0.07 b (float, in this order);  total = lookup(l) + d;  total < 0 -> 0;
//   l > 0:  out_c = (c_c * total) / l        (the shader's rgb * (Lw + a) / L, multiply first)
//   l == 0: out = (total, total, total)       (the grey limit of c * total / l as c -> 0: Listing 1 divides by 0)
// All arithmetic is IEEE float with -ffp-contract=off, so every machine decodes the same bits.
#pragma once

#include <array>
#include <cstdint>
#include <string>

namespace blocklab {

struct ItmoLut {
  std::array<std::uint16_t, 256> half_bits{};   // the 512-byte table of the paper (half-float bit patterns)
  std::array<float, 256> values{};              // the same entries as float (half -> float is exact)
  int exponent = 0;                             // s: a table value v stands for v * 2^s
};

// Largest peak luminance g(1) the decoder accepts: texel values stay far from float overflow (out <= total / 0.07).
constexpr double kMaxItmoPeak = 1e30;

// Builds the table; throws Error("<who>: ...") when a parameter is not finite and > 0, or the peak g(1) is not a
// normal double or exceeds kMaxItmoPeak.
ItmoLut build_itmo_lut(double alpha, double l_white, double mean, const std::string& who);

// The filtered lookup (see above); `tone_mapped` is any finite float (clamped to [0, 1] through t).
float itmo_lookup(const ItmoLut& lut, float tone_mapped);

// Listing 1 for one texel: `ldr` the decoded colour in [0, 1], `residual` the decoded additive luminance residual.
void itmo_decode_texel(const ItmoLut& lut, const float ldr[3], float residual, float out[3]);

}  // namespace blocklab
