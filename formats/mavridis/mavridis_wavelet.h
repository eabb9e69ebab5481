// The wavelet stage of `mavridis` (Mavridis & Papaioannou 2012, ../shared/papers/mavridis2012_wavelet_texture_
// compression.txt, section 3.1 and 3.3), templated on the scalar (double, ceres::Jet):
//   eq. 1  Haar of a 2x2 group a b / c d:  LL = (a+b+c+d)/2, HL = (a-b+c-d)/2, LH = (a+b-c-d)/2, HH = (a-b-c+d)/2;
//   eq. 2  PI-Haar: HL' = HL + LH + w HH, LH' = -HL + LH - w HH, HH' = HL - LH - w HH (0 < w <= 1: the matrix has
//          determinant -4w, so w = 0 cannot be inverted and the option refuses it);
//   eq. 3  branch-free reconstruction of texel (u, v) of its group from the Haar coefficients:
//          C(u, v) = 1/2 [LL - f((u&1)^(v&1)) HH - f(v&1) LH - f(u&1) HL],  f(x) = 2x - 1.
//          The paper prints eq. 3 without the 1/2; with eq. 1 normalised by 1/2 (its own inverse) the bracket is
//          2C, so the 1/2 is restored here (README.md, "Decisions").
// Section 3.2's coefficient mapping (dequantise): a stored value s in [0, 1] of a band with centre c, half range r
// and gamma g decodes to x = c + r sign(n) |n|^(1/g), n = 2s - 1 (wavelet bands; LL has g = 1).
#pragma once

#include <array>
#include <cmath>

namespace blocklab {
namespace mavridis {

enum class Transform { haar, pi_haar, s_transform, plhaar };

// Section 3.1's BC7 packing: HH dropped (w = 0 in eq. 2), LL with HL' = HL + LH and LH' = HL - LH (PI-Haar) or with
// HL and LH (Haar) in R, G, B; band 3 is 0. The inverse restores HL = (HL' + LH') / 2, LH = (HL' - LH') / 2, HH = 0.
template <typename T>
std::array<T, 4> bc7_bands_from_haar(const std::array<T, 4>& h, bool partially_inverted) {
  if (!partially_inverted) return {h[0], h[1], h[2], T(0.0)};
  return {h[0], h[1] + h[2], h[1] - h[2], T(0.0)};
}

template <typename T>
std::array<T, 4> haar_from_bc7_bands(const std::array<T, 4>& b, bool partially_inverted) {
  if (!partially_inverted) return {b[0], b[1], b[2], T(0.0)};
  return {b[0], (b[1] + b[2]) * 0.5, (b[1] - b[2]) * 0.5, T(0.0)};
}

// The S-transform (Calderbank, Daubechies, Sweldens, Yeo 1997; the paper's Table 3 / section 4.2), an integer Haar:
// per pair l = floor((x + y) / 2), h = x - y, inverted by x = l + floor((h + 1) / 2), y = x - h; applied to the rows
// of the group (a b, c d) and then to the two lows and the two highs:
//   LL = floor((l1 + l2) / 2), LH = l1 - l2, HL = floor((h1 + h2) / 2), HH = h1 - h2,
//   l1 = floor((a + b) / 2), h1 = a - b, l2 = floor((c + d) / 2), h2 = c - d.
// Exact on integers (|values| < 2^29); the decoder rounds the dequantised coefficients to integers first.
inline long long floor_half(long long x) { return (x - (x & 1)) / 2; }

inline std::array<long long, 4> s_transform_forward(long long a, long long b, long long c, long long d) {
  const long long l1 = floor_half(a + b), h1 = a - b, l2 = floor_half(c + d), h2 = c - d;
  return {floor_half(l1 + l2), floor_half(h1 + h2), l1 - l2, h1 - h2};
}

// Returns the group's texels a, b, c, d.
inline std::array<long long, 4> s_transform_inverse(const std::array<long long, 4>& s) {
  const long long l1 = s[0] + floor_half(s[2] + 1), l2 = l1 - s[2];
  const long long h1 = s[1] + floor_half(s[3] + 1), h2 = h1 - s[3];
  const long long a = l1 + floor_half(h1 + 1), c = l2 + floor_half(h2 + 1);
  return {a, a - h1, c, c - h2};
}

// Band order everywhere: LL, HL, LH, HH (or LL, HL', LH', HH' for PI-Haar).
template <typename T>
std::array<T, 4> haar_forward(const T& a, const T& b, const T& c, const T& d) {
  return {(a + b + c + d) * 0.5, (a - b + c - d) * 0.5, (a + b - c - d) * 0.5, (a - b - c + d) * 0.5};
}

// Eq. 2 applied to the three Haar wavelet bands (LL unchanged).
template <typename T>
std::array<T, 4> pi_haar_from_haar(const std::array<T, 4>& h, double w) {
  return {h[0], h[1] + h[2] + h[3] * w, h[2] - h[1] - h[3] * w, h[1] - h[2] - h[3] * w};
}

// The inverse of eq. 2: LH = (HL' + LH') / 2, HH = -(LH' + HH') / (2w), HL = HL' - LH - w HH.
template <typename T>
std::array<T, 4> haar_from_pi_haar(const std::array<T, 4>& p, double w) {
  const T lh = (p[1] + p[2]) * 0.5;
  const T hh = (p[2] + p[3]) * (-0.5 / w);
  const T hl = p[1] - lh - hh * w;
  return {p[0], hl, lh, hh};
}

// Eq. 3 (with the 1/2, see above): texel (u, v) of the 2x2 group, integer decisions on the integer coordinates only.
template <typename T>
T reconstruct_texel(const std::array<T, 4>& haar, int u, int v) {
  const int f_hh = 2 * ((u & 1) ^ (v & 1)) - 1;
  const int f_lh = 2 * (v & 1) - 1;
  const int f_hl = 2 * (u & 1) - 1;
  return (haar[0] - haar[3] * double(f_hh) - haar[2] * double(f_lh) - haar[1] * double(f_hl)) * 0.5;
}

// Section 3.2 dequantisation of one stored value (s in [0, 1]).
template <typename T>
T dequantise(const T& s, double centre, double half_range, double gamma) {
  using std::abs;
  using std::pow;
  const T n = s * 2.0 - 1.0;
  if (gamma == 1.0) return n * half_range + centre;
  // sign(n) |n|^(1/g); the sign test is a comparison of T (double and ceres::Jet define it).
  const T magnitude = pow(abs(n), 1.0 / gamma);
  return centre + half_range * (n < T(0.0) ? -magnitude : magnitude);
}

}  // namespace mavridis
}  // namespace blocklab
