// The BC6H one-region endpoint fit as a core/problem.h Problem, so the solver library (annealing, Levenberg-Marquardt,
// interval branch-and-bound, lattice polish) can search what bc6h_mode_search.cpp fits in closed form.
//
// Mode 3 (KDFS "BC6H": one subset, endpoints stored untransformed in 10 bits, 4-bit indices), the indices fixed (one
// interpolation weight per texel). Parameters x[0..5]: the stored codes E0 R, G, B, E1 R, G, B on their lattice
// {0..1023} (UF16) or {-511..511} (SF16).
// Error: sum over texels and channels of (decoded half bits - source half bits)^2 (the encoder's log_domain for normal
// halves, bc6h_endpoint_fit.h; kept polynomial here so every solver can evaluate it), with the CONTINUOUS relaxation of the decoder: unquantisation 64 x + 32 (exact for unsigned
// codes 1..1022 and signed codes 1..510; the unsigned codes 0 and 1023, the saturated signed code 511 and negative
// signed codes, which the encoder never needs for non-negative images, differ), interpolation
// ((64 - w) E0 + w E1) / 64 without rounding, final unquantisation i * 31 / 64 (unsigned) or i * 31 / 32 (signed)
// without truncation. At lattice points the relaxed value is within about one half-bit step of the real decoder, so
// a solver's point must still be scored with the real decoder. Least-squares form: kResiduals = 48 (texel-major).
#pragma once

#include <cstdint>
#include <utility>
#include <vector>

#include "core/problem.h"

namespace blocklab {
namespace bc6h {

struct OneRegionEndpointError {
  static constexpr int kDim = 6;
  static constexpr bool kSmooth = true;
  static constexpr int kResiduals = 48;

  double source_half[16][3] = {};   // source half bits as signed magnitudes
  double fraction[16] = {};         // interpolation weight / 64 of each texel (the fixed indices)
  double code_scale = 64.0;         // relaxed unquantisation: code * code_scale + code_offset
  double code_offset = 32.0;
  double finish_scale = 31.0 / 64.0;

  template <typename T>
  void residuals(const T* x, T* r) const {
    for (int i = 0; i < 16; ++i)
      for (int c = 0; c < 3; ++c) {
        const T e0 = x[c] * T(code_scale) + T(code_offset);
        const T e1 = x[3 + c] * T(code_scale) + T(code_offset);
        const T interpolated = e0 * T(1.0 - fraction[i]) + e1 * T(fraction[i]);
        r[i * 3 + c] = interpolated * T(finish_scale) - T(source_half[i][c]);
      }
  }

  template <typename T>
  T operator()(const T* x) const {
    return sum_of_squared_residuals<kResiduals>(*this, x);
  }
};

// The problem for source half bits (signed magnitudes) and fixed 4-bit indices.
inline ErrorProblem<OneRegionEndpointError> make_one_region_endpoint_problem(const int (&source_half)[16][3],
                                                                             const std::uint8_t (&indices)[16],
                                                                             bool is_signed) {
  static constexpr int kWeights4[16] = {0, 4, 9, 13, 17, 21, 26, 30, 34, 38, 43, 47, 51, 55, 60, 64};
  OneRegionEndpointError error;
  for (int i = 0; i < 16; ++i) {
    for (int c = 0; c < 3; ++c) error.source_half[i][c] = source_half[i][c];
    error.fraction[i] = kWeights4[indices[i]] / 64.0;
  }
  error.finish_scale = is_signed ? 31.0 / 32.0 : 31.0 / 64.0;
  const double low = is_signed ? -511.0 : 0.0;
  const double high = is_signed ? 511.0 : 1023.0;
  Bounds bounds;
  std::vector<Lattice> lattices;
  for (int p = 0; p < OneRegionEndpointError::kDim; ++p) {
    bounds.lower.push_back(low);
    bounds.upper.push_back(high);
    lattices.push_back(Lattice::uniform(low, high, static_cast<std::int64_t>(high - low) + 1));
  }
  return make_problem(error, std::move(bounds), std::move(lattices));
}

}  // namespace bc6h
}  // namespace blocklab
