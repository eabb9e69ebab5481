// The S3TC endpoint searches as Problems (core/problem.h), for the solver library and for tests.
//
//   BC1 / BC3 colour: 6 parameters (R5, G6, B5 of endpoint 0, then of endpoint 1) on the RGB565 lattice
//     ([0, 31] x [0, 63] x [0, 31], twice). Error = sum over texels of min over the palette entries of the
//     channel-weighted squared difference, in [0, 1] code units, the palette being the reference decoding
//     (formats/common/s3tc_common.h) of the endpoints in a FIXED mode. Since each code is chosen per texel, the
//     error does not depend on the endpoint order: a solution is stored with canonicalise_bc1 /
//     canonicalise_bc3_color (which reorder endpoints, or use equal endpoints with code 0) without changing it.
//   BC4 / BC3 alpha: 2 parameters (red0, red1) on [0, 255] in a FIXED mode, error as above with 8 entries.
//
// Between lattice points the error is a continuous extension: bit replication is written 8 v + floor(v / 4)
// (resp. 4 v + floor(v / 16)), exact at lattice points; the interval version encloses it over boxes (floor is
// monotone), the Jet version differentiates it piecewise (floor has derivative 0). The builtin encoders
// (s3tc_color_fit.h, bc4_encoder.h) search the same error with specialised float code; tests check that the
// Problem error at their result equals the error of the decoded block.
#pragma once

#include <array>

#include "core/problem.h"
#include "core/scalar.h"
#include "formats/common/s3tc_common.h"

namespace blocklab {

struct Bc1EndpointError {
  static constexpr int kDim = 6;
  std::array<std::array<double, 3>, 16> targets{};   // texel RGB in [0, 1]
  std::array<double, 3> weights{{1.0, 1.0, 1.0}};
  Bc1Mode mode = Bc1Mode::four_color;

  template <typename T>
  T operator()(const T* x) const {
    T palette[4][3];
    bc1_palette(x, x + 3, mode, palette);
    T total = T(0.0);
    for (int texel = 0; texel < 16; ++texel) {
      T best = entry_error(palette[0], texel);
      for (int index = 1; index < 4; ++index) best = min(best, entry_error(palette[index], texel));
      total += best;
    }
    return total;
  }

  template <typename T>
  T entry_error(const T* entry, int texel) const {
    T error = T(0.0);
    for (int channel = 0; channel < 3; ++channel)
      error += T(weights[channel]) * square(entry[channel] - T(targets[texel][channel]));
    return error;
  }
};

struct Bc4EndpointError {
  static constexpr int kDim = 2;
  std::array<double, 16> targets{};   // values in [0, 1]
  Bc4Mode mode = Bc4Mode::eight_value;

  template <typename T>
  T operator()(const T* x) const {
    T palette[8];
    bc4_palette(x[0], x[1], mode, palette);
    T total = T(0.0);
    for (int texel = 0; texel < 16; ++texel) {
      T best = square(palette[0] - T(targets[texel]));
      for (int index = 1; index < 8; ++index) best = min(best, square(palette[index] - T(targets[texel])));
      total += best;
    }
    return total;
  }
};

inline ErrorProblem<Bc1EndpointError> make_bc1_endpoint_problem(const Bc1EndpointError& error) {
  Bounds bounds{{0, 0, 0, 0, 0, 0}, {31, 63, 31, 31, 63, 31}};
  std::vector<Lattice> lattices;
  for (int k = 0; k < 6; ++k) lattices.push_back(Lattice::uniform(0, rgb565_channel_max(k % 3), rgb565_channel_max(k % 3) + 1));
  return make_problem(error, std::move(bounds), std::move(lattices));
}

inline ErrorProblem<Bc4EndpointError> make_bc4_endpoint_problem(const Bc4EndpointError& error) {
  return make_problem(error, Bounds{{0, 0}, {255, 255}}, {Lattice::uniform(0, 255, 256), Lattice::uniform(0, 255, 256)});
}

}  // namespace blocklab
