// PLHaar, the piecewise-linear Haar of Table 3 (Mavridis & Papaioannou 2012, section 4.2: "PLHaar [SLDJ05]
// provides a lossless Haar-like transform which operates only with 8-bits of fixed-point precision"):
// G. Senecal, P. Lindstrom, M. Duchaineau, K. Joy, "Investigating lossy image coding using the PLHaar transform",
// DCC 2005 (the transform itself: Senecal, Duchaineau, Joy, "An improved N-bit to N-bit reversible Haar-like
// transform", Pacific Graphics 2004).
//
// The 1D step maps a pair (a, b) of the signed range [-Z, Z - 1] onto a pair (L, H) of the same range, bijectively:
// the square is cut along its diagonals into four triangles and each is mapped linearly (determinant +-1) onto a
// triangle of the (L, H) square, so no bit of range is added (Haar adds one per step). With p = a + [a < 0],
// q = b + [b < 0] (negative values move one step towards zero, so both signs have magnitudes 0 .. Z - 1):
//   a, b of one sign:        L = the one of p, q of larger magnitude - [b < 0],           H = p - q - [a < 0]
//   a, b of opposite signs:  L = p + q - [b < 0],   H = (p if |p| >= |q| else -q) - [a < 0]
// (the tie |p| = |q| in the opposite-sign case is decided by the sign of p + q: p + q >= 0 picks p when a >= 0,
// p + q < 0 picks p when a < 0). The four regions of the (L, H) square are disjoint (plhaar_inverse reads them
// back); the unit test checks the bijection on every pair for Z = 128 and Z = 256.
//
// 2D, one level, on a 2x2 group a b / c d: the rows (a, b) -> (l1, h1), (c, d) -> (l2, h2), then the columns
// (l1, l2) -> (LL, LH), (h1, h2) -> (HL, HH) (the S-transform's order, mavridis_wavelet.h). The plane is offset to
// the signed range first: luma (0..255) by -128 with Z = 128 (8 bits), the signed chroma planes (-255..255) by 0
// with Z = 256 (9 bits, YCoCg-R's extra chroma bit).
#pragma once

#include <array>

namespace blocklab {
namespace mavridis {

// The signed range a plane is transformed in: values v become v - offset in [-half, half - 1].
struct PlhaarDomain {
  int offset = 128;
  int half = 128;
};
inline PlhaarDomain plhaar_luma_domain() { return {128, 128}; }
inline PlhaarDomain plhaar_chroma_domain() { return {0, 256}; }

struct PlhaarPair {
  int low = 0, high = 0;
};

inline int magnitude(int v) { return v < 0 ? -v : v; }

inline PlhaarPair plhaar_forward(int a, int b) {
  const int sa = a < 0 ? 1 : 0, sb = b < 0 ? 1 : 0;
  const int p = a + sa, q = b + sb;
  if (sa == sb) return {(magnitude(p) >= magnitude(q) ? p : q) - sb, p - q - sa};
  const int sum = p + q;
  const bool pick_p = sa == 0 ? sum >= 0 : sum < 0;
  return {sum - sb, (pick_p ? p : -q) - sa};
}

// The inverse, region by region (the regions of the (L, H) square: same sign non-negative L >= |H|; same sign
// negative; a >= 0 > b with H >= 0; a < 0 <= b with H < 0).
inline PlhaarPair plhaar_inverse(int low, int high) {
  if (high >= 0) {
    if (low >= high) return {low, low - high};                     // a >= b >= 0
    if (low >= -high - 1) {                                         // a >= 0 > b
      const int sum = low + 1;                                      // p + q
      const int p = sum >= 0 ? high : sum + high, q = sum - p;
      return {p, q - 1};
    }
    const int q = low + 1, p = q + high + 1;                        // both negative, p > q
    return {p - 1, q - 1};
  }
  if (low >= -high) return {low + high, low};                       // 0 <= a < b
  if (low >= high + 1) {                                            // a < 0 <= b
    const int p = low < 0 ? high + 1 : low + high + 1, q = low - p;
    return {p - 1, q};
  }
  const int p = low + 1, q = low - high;                            // both negative, p <= q
  return {p - 1, q - 1};
}

// One 2x2 group (already offset to the signed range): returns LL, HL, LH, HH.
inline std::array<int, 4> plhaar_group_forward(int a, int b, int c, int d) {
  const PlhaarPair row1 = plhaar_forward(a, b), row2 = plhaar_forward(c, d);
  const PlhaarPair low = plhaar_forward(row1.low, row2.low), high = plhaar_forward(row1.high, row2.high);
  return {low.low, high.low, low.high, high.high};
}

// Returns the group's texels a, b, c, d (signed range).
inline std::array<int, 4> plhaar_group_inverse(const std::array<int, 4>& bands) {
  const PlhaarPair low = plhaar_inverse(bands[0], bands[2]), high = plhaar_inverse(bands[1], bands[3]);
  const PlhaarPair row1 = plhaar_inverse(low.low, high.low), row2 = plhaar_inverse(low.high, high.high);
  return {row1.low, row1.high, row2.low, row2.high};
}

}  // namespace mavridis
}  // namespace blocklab
