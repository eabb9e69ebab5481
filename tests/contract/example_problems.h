// Small real problems written the blocklab way (one templated error, DESIGN.md "The one idea"), shared by the
// Problem contract test and the solver tests:
//   ExponentialFitError  least-squares fit y = a exp(b t) (smooth, with residuals);
//   PaletteFitError      BC4-like 1-D block: two endpoints, palette lerp(e0, e1, k/3), error = sum over 16 texels
//                        of the min over the 4 palette entries of the squared distance (SPECS.md 2.2 with the
//                        4-entry interpolation of BC1 colour; non-smooth);
//   LogYuvFitError       logYuv-like: shared chroma (u, v) and a log2 luminance with per-texel offsets, decoded
//                        through exp2 and compared in log2 RGB (smooth on its bounds);
//   GammaFitError        v = s t^g with a real exponent (pow through exp(g log t)), with residuals.
#pragma once

#include <array>
#include <cmath>

#include "core/problem.h"
#include "core/scalar.h"

namespace blocklab::examples {

struct ExponentialFitError {
  static constexpr int kDim = 2;          // a, b
  static constexpr int kResiduals = 8;
  static constexpr bool kSmooth = true;
  std::array<double, kResiduals> t{};
  std::array<double, kResiduals> y{};

  template <typename T>
  void residuals(const T* x, T* r) const {
    using std::exp;
    for (int i = 0; i < kResiduals; ++i) r[i] = x[0] * exp(x[1] * T(t[i])) - T(y[i]);
  }
  template <typename T>
  T operator()(const T* x) const {
    return sum_of_squared_residuals<kResiduals>(*this, x);
  }
};

// Samples of y = 1.5 exp(-0.7 t) with a small deterministic perturbation, t = 0, 0.5, ..., 3.5.
inline ExponentialFitError exponential_fit_example() {
  ExponentialFitError error;
  for (int i = 0; i < ExponentialFitError::kResiduals; ++i) {
    error.t[static_cast<std::size_t>(i)] = 0.5 * i;
    error.y[static_cast<std::size_t>(i)] = 1.5 * std::exp(-0.7 * 0.5 * i) + 0.01 * ((i % 3) - 1);
  }
  return error;
}

struct PaletteFitError {
  static constexpr int kDim = 2;          // endpoints e0, e1
  static constexpr int kTexels = 16;
  static constexpr int kPaletteSize = 4;
  std::array<double, kTexels> texels{};

  // Palette entry k = lerp(e0, e1, k / 3) = e0 (3 - k)/3 + e1 k/3.
  template <typename T>
  static T palette_entry(const T* x, int k) {
    return x[0] * T((3.0 - k) / 3.0) + x[1] * T(k / 3.0);
  }
  template <typename T>
  T operator()(const T* x) const {
    T palette[kPaletteSize];
    for (int k = 0; k < kPaletteSize; ++k) palette[k] = palette_entry(x, k);
    T sum = T(0.0);
    for (int i = 0; i < kTexels; ++i) {
      const T value = T(texels[static_cast<std::size_t>(i)]);
      T best = square(value - palette[0]);
      for (int k = 1; k < kPaletteSize; ++k) best = min(best, square(value - palette[k]));
      sum += best;
    }
    return sum;
  }
};

// A block with two clusters and a ramp, values in [0, 1].
inline PaletteFitError palette_fit_example() {
  PaletteFitError error;
  const double values[PaletteFitError::kTexels] = {0.10, 0.12, 0.11, 0.35, 0.36, 0.40, 0.62, 0.60,
                                                   0.65, 0.88, 0.90, 0.91, 0.13, 0.37, 0.63, 0.89};
  for (int i = 0; i < PaletteFitError::kTexels; ++i) error.texels[static_cast<std::size_t>(i)] = values[i];
  return error;
}

struct LogYuvFitError {
  static constexpr int kDim = 3;          // log2 luminance L, chroma u, v
  static constexpr int kTexels = 4;
  static constexpr bool kSmooth = true;   // the floor below is never active inside the bounds (see bounds)
  // Named floor before log2 (no log of 0): 2^-24, below any decodable value inside the bounds.
  static constexpr double kLogFloor = 5.9604644775390625e-08;
  std::array<double, kTexels> luminance_offset{};                 // per-texel log2 luminance offsets
  std::array<std::array<double, 3>, kTexels> target_log2_rgb{};   // log2 of the target RGB

  template <typename T>
  T operator()(const T* x) const {
    using std::exp2;   // std for double; ADL finds ceres' (Jet) and blocklab's (Interval) overloads
    using std::log2;
    T sum = T(0.0);
    for (int i = 0; i < kTexels; ++i) {
      const T luminance = exp2(x[0] + T(luminance_offset[static_cast<std::size_t>(i)]));
      const T rgb[3] = {T(3.0) * luminance * x[1], T(3.0) * luminance * (T(1.0) - x[1] - x[2]),
                        T(3.0) * luminance * x[2]};
      for (int c = 0; c < 3; ++c) {
        // select on a comparison (not max) to exercise select: floor the channel before log2.
        const T floored = select(less(rgb[c], T(kLogFloor)), T(kLogFloor), rgb[c]);
        sum += square(log2(floored) - T(target_log2_rgb[static_cast<std::size_t>(i)][static_cast<std::size_t>(c)]));
      }
    }
    return sum;
  }
};

inline LogYuvFitError log_yuv_fit_example() {
  LogYuvFitError error;
  error.luminance_offset = {-1.0, -0.25, 0.5, 1.5};
  const double rgb[LogYuvFitError::kTexels][3] = {
      {0.20, 0.35, 0.10}, {0.45, 0.50, 0.20}, {0.70, 1.10, 0.35}, {2.20, 2.60, 0.90}};
  for (int i = 0; i < LogYuvFitError::kTexels; ++i)
    for (int c = 0; c < 3; ++c)
      error.target_log2_rgb[static_cast<std::size_t>(i)][static_cast<std::size_t>(c)] = std::log2(rgb[i][c]);
  return error;
}

struct GammaFitError {
  static constexpr int kDim = 2;          // scale s, exponent g
  static constexpr int kResiduals = 6;
  static constexpr bool kSmooth = true;
  std::array<double, kResiduals> t{};     // in (0, 1]
  std::array<double, kResiduals> v{};

  template <typename T>
  void residuals(const T* x, T* r) const {
    using std::pow;
    for (int i = 0; i < kResiduals; ++i) r[i] = x[0] * pow(T(t[i]), x[1]) - T(v[i]);
  }
  template <typename T>
  T operator()(const T* x) const {
    return sum_of_squared_residuals<kResiduals>(*this, x);
  }
};

inline GammaFitError gamma_fit_example() {
  GammaFitError error;
  for (int i = 0; i < GammaFitError::kResiduals; ++i) {
    const double t = 0.05 + 0.19 * i;   // 0.05 .. 1.0
    error.t[static_cast<std::size_t>(i)] = t;
    error.v[static_cast<std::size_t>(i)] = 0.9 * std::pow(t, 2.2);
  }
  return error;
}

}  // namespace blocklab::examples
