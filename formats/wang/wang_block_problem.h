// The 1D codec of Wang et al. 2007 section 3.5 as block Problems on the endpoint lattice (core/problem.h), with the
// log-domain error of eq. 9, E = |L - L'| / (L + c), summed over the block's texels, each texel taking its best
// codes. Templated on the scalar type (double, ceres::Jet, Interval), like formats/common/s3tc_endpoint_problem.h.
//
//   LuminanceBlockError  4 parameters: the alpha endpoints (alpha0, alpha1) of tex0 and of tex1 on [0, 255], each
//                        half in a FIXED mode (8- or 6-value palette). L' = eq. 4 of the fetched values (wang_shader.h
//                        with residual none); a texel picks its best pair of codes (8 x 8), which is what makes the
//                        two alpha channels one 1D quantity.
//   ResidualBlockError   6 parameters: the RGB565 endpoints of tex1's colour block (R5, G6, B5 twice). The residual
//                        palette entry k is the 1D value dot(fetched colour k, r_ranges) + smin; L' = L_a + s' (S) or
//                        L_a + L_a s' (ratio T), L_a the texel's decoded eq. 4 luminance; a texel picks its best of
//                        the 4 entries. The texel's error is measured on what the shader shows, D = max(L', 0), as
//                        |L - D| / (min(L, D) + c): eq. 9 where D >= L, and where D < L the same ratio taken the other
//                        way, so that the error is (larger + c) / (smaller + c) - 1 = exp|ln((L + c) / (D + c))| - 1,
//                        a monotone function of the log-domain distance eq. 9 linearises. Eq. 9 alone charges a
//                        texel decoded black (L' <= 0) at most 1 whatever its L, so the code nearest in linear terms
//                        could be black; this error charges it L / c.
// `texture_unit` = true (default) rounds every fetched value to 8 bits as the decoder does (so the error at a lattice
// point is the decoded block's error, up to float vs double); false leaves the exact fractions, a continuous
// extension with useful Jet gradients.
#pragma once

#include <array>

#include "core/problem.h"
#include "core/scalar.h"
#include "formats/common/s3tc_common.h"
#include "formats/wang/wang_shader.h"

namespace blocklab {
namespace wang {

template <typename T>
T fetched_value(const T& exact, bool texture_unit) {
  return texture_unit ? texture_unit_value(exact) : exact;
}

struct LuminanceBlockError {
  static constexpr int kDim = 4;
  std::array<double, 16> luminance{};   // L of each texel
  std::array<double, 16> weight{};      // 1 / (L + c)
  double high = 0.0, low = 0.0, tmin = 0.0;   // the eq. 4 constants (ShaderConstants l_high, l_low, tmin)
  std::array<Bc4Mode, 2> modes{{Bc4Mode::eight_value, Bc4Mode::eight_value}};
  bool texture_unit = true;

  template <typename T>
  T operator()(const T* x) const {
    T palette0[8], palette1[8];
    bc4_palette(x[0], x[1], modes[0], palette0);
    bc4_palette(x[2], x[3], modes[1], palette1);
    T part0[8], part1[8];
    for (int k = 0; k < 8; ++k) {
      part0[k] = fetched_value(palette0[k], texture_unit) * T(high);
      part1[k] = fetched_value(palette1[k], texture_unit) * T(low) + T(tmin);
    }
    T total = T(0.0);
    for (int texel = 0; texel < 16; ++texel) {
      const T target = T(luminance[texel]);
      T best = abs(target - (part0[0] + part1[0]));
      for (int i = 0; i < 8; ++i)
        for (int j = 0; j < 8; ++j) best = min(best, abs(target - (part0[i] + part1[j])));
      total += T(weight[texel]) * best;
    }
    return total;
  }
};

struct ResidualBlockError {
  static constexpr int kDim = 6;
  std::array<double, 16> luminance{};   // L of each texel
  std::array<double, 16> decoded{};     // L_a: the decoded eq. 4 luminance
  std::array<double, 16> weight{};      // 1 / (L + c): the Lloyd rounds' weights
  double c = 1.0 / 16384.0;             // c of eq. 9 (option error_c)
  std::array<double, 3> ranges{};       // r_ranges (ShaderConstants)
  double rmin = 0.0;                    // smin
  bool ratio = false;                   // residual T (eq. 11) instead of S
  bool texture_unit = true;

  template <typename T>
  T operator()(const T* x) const {
    T palette[4][3];
    bc1_palette(x, x + 3, Bc1Mode::four_color, palette);
    T entry[4];
    for (int k = 0; k < 4; ++k) {
      T fetched[3];
      for (int channel = 0; channel < 3; ++channel) fetched[channel] = fetched_value(palette[k][channel], texture_unit);
      entry[k] = (fetched[0] * T(ranges[0]) + fetched[1] * T(ranges[1])) + fetched[2] * T(ranges[2]) + T(rmin);
    }
    T total = T(0.0);
    for (int texel = 0; texel < 16; ++texel) {
      const T base = T(decoded[texel]);
      const T target = T(luminance[texel]);
      T best = texel_error(target, reconstruct(base, entry[0]));
      for (int k = 1; k < 4; ++k) best = min(best, texel_error(target, reconstruct(base, entry[k])));
      total += best;
    }
    return total;
  }

  // The error of a texel of luminance L >= 0 decoded (before the shader's clamp) as `decoded` (see above).
  template <typename T>
  T texel_error(const T& target, const T& decoded) const {
    const T shown = max(decoded, T(0.0));
    return abs(target - shown) / (min(target, shown) + T(c));
  }

  template <typename T>
  T reconstruct(const T& base, const T& residual) const {
    return ratio ? base + base * residual : base + residual;
  }
};

inline ErrorProblem<LuminanceBlockError> make_luminance_block_problem(const LuminanceBlockError& error) {
  Bounds bounds{{0, 0, 0, 0}, {255, 255, 255, 255}};
  return make_problem(error, std::move(bounds), std::vector<Lattice>(4, Lattice::uniform(0, 255, 256)));
}

inline ErrorProblem<ResidualBlockError> make_residual_block_problem(const ResidualBlockError& error) {
  Bounds bounds{{0, 0, 0, 0, 0, 0}, {31, 63, 31, 31, 63, 31}};
  std::vector<Lattice> lattices;
  for (int k = 0; k < 6; ++k)
    lattices.push_back(Lattice::uniform(0, rgb565_channel_max(k % 3), rgb565_channel_max(k % 3) + 1));
  return make_problem(error, std::move(bounds), std::move(lattices));
}

}  // namespace wang
}  // namespace blocklab
