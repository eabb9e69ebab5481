// The BC7 subset endpoint search as a core/problem.h Problem, so the solver library (annealing, Levenberg-
// Marquardt, interval branch-and-bound, lattice polish) can replace the builtin closed-form fit (option `solver`).
//
// Discrete choices fixed for one solve (members): the subset's texels, the per-texel interpolation weights (the
// index assignment), the P-bits and the mode's stored bits per lane. Parameters x[0..7]: the stored endpoint codes
// (without P-bit) E0 R, G, B, A, then E1 R, G, B, A, each on its lattice {0, 1, ..., 2^bits - 1}; lanes the mode
// does not store are pinned to the single point 0.
// Error: sum over texels and lanes of weight * (value - texel)^2 with the CONTINUOUS relaxation of the decoder:
// expansion code -> (2 code + P) * 255 / (2^(bits+1) - 1) (or code * 255 / (2^bits - 1) without P-bit) instead of
// bit replication, and interpolation ((64 - w) E0 + w E1) / 64 without the +32 >> 6 rounding. At lattice points
// the relaxed value differs from the real decoder by less than one code value per channel, so a solver's lattice
// point must still be scored with decode<T> (the builtin path does exactly that). The least-squares form
// (kResiduals = 64: texel-major, lane-minor; members beyond `count` give 0) is the one Levenberg-Marquardt uses.
#pragma once

#include <cmath>
#include <cstdint>
#include <utility>
#include <vector>

#include "core/problem.h"
#include "formats/bc7/bc7_endpoint_fit.h"
#include "formats/bc7/bc7_tables.h"

namespace blocklab {
namespace bc7 {

struct SubsetEndpointError {
  static constexpr int kDim = 8;
  static constexpr bool kSmooth = true;
  static constexpr int kResiduals = 64;

  double texels[16][4] = {};
  double weight_sqrt[4] = {};        // sqrt of the lane weights (0 for lanes not stored)
  double fraction[16] = {};          // interpolation weight / 64 of each member texel (the fixed indices)
  double code_scale[2][4] = {};      // expanded = code * code_scale + code_offset (relaxed expansion)
  double code_offset[2][4] = {};
  int count = 0;

  template <typename T>
  void residuals(const T* x, T* r) const {
    for (int i = 0; i < 16; ++i)
      for (int lane = 0; lane < 4; ++lane) {
        if (i >= count) {   // unused residual slots (fewer than 16 members)
          r[i * 4 + lane] = T(0.0);
          continue;
        }
        const T e0 = x[lane] * T(code_scale[0][lane]) + T(code_offset[0][lane]);
        const T e1 = x[4 + lane] * T(code_scale[1][lane]) + T(code_offset[1][lane]);
        const T value = e0 * T(1.0 - fraction[i]) + e1 * T(fraction[i]);
        r[i * 4 + lane] = (value - T(texels[i][lane])) * T(weight_sqrt[lane]);
      }
  }

  template <typename T>
  T operator()(const T* x) const {
    T r[kResiduals];
    residuals(x, r);
    T sum = T(0.0);
    for (int k = 0; k < kResiduals; ++k) sum = sum + square(r[k]);
    return sum;
  }
};

// Builds the problem for `count` member texels with fixed `indices` (member order) and P-bits, from the same
// settings the builtin fit uses.
inline ErrorProblem<SubsetEndpointError> make_subset_endpoint_problem(const float (*texels)[4], int count,
                                                                      const SubsetFitSettings& settings,
                                                                      const std::uint8_t* indices,
                                                                      const std::uint8_t (&pbits)[2]) {
  SubsetEndpointError error;
  error.count = count;
  const int* weights = index_weights(settings.index_bits);
  for (int i = 0; i < count; ++i) {
    for (int lane = 0; lane < 4; ++lane) error.texels[i][lane] = texels[i][lane];
    error.fraction[i] = weights[indices[i]] / 64.0;
  }
  Bounds bounds;
  std::vector<Lattice> lattices;
  const bool has_pbit = settings.lattice.pbit != PbitKind::none;
  for (int endpoint = 0; endpoint < 2; ++endpoint)
    for (int lane = 0; lane < 4; ++lane) {
      const int bits = settings.lattice.lane_bits[lane];
      if (bits == 0) {   // lane not stored: pinned (decodes to 255 whatever x is), weight 0
        error.code_scale[endpoint][lane] = 0.0;
        error.code_offset[endpoint][lane] = 255.0;
        bounds.lower.push_back(0.0);
        bounds.upper.push_back(0.0);
        lattices.push_back(Lattice::uniform(0.0, 0.0, 1));
        continue;
      }
      const int max_code = (1 << bits) - 1;
      if (has_pbit) {
        const double full = static_cast<double>((2 << bits) - 1);
        error.code_scale[endpoint][lane] = 2.0 * 255.0 / full;
        error.code_offset[endpoint][lane] = pbits[endpoint] * 255.0 / full;
      } else {
        error.code_scale[endpoint][lane] = 255.0 / max_code;
        error.code_offset[endpoint][lane] = 0.0;
      }
      bounds.lower.push_back(0.0);
      bounds.upper.push_back(max_code);
      lattices.push_back(Lattice::uniform(0.0, max_code, max_code + 1));
    }
  for (int lane = 0; lane < 4; ++lane)
    error.weight_sqrt[lane] = settings.lattice.lane_bits[lane] == 0 ? 0.0 : std::sqrt(settings.weights[lane]);
  return make_problem(error, std::move(bounds), std::move(lattices));
}

}  // namespace bc7
}  // namespace blocklab
