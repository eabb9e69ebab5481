// Section 3.2's coefficient optimisation of one `mavridis` plane as a blocklab Problem (core/problem.h), so any
// solver of the library (`coeff_search` first) can search it: x[0] = the clamped outlier fraction in [0, 0.6],
// x[1] = the gamma of the wavelet bands in [0.5, 1.2]; error = the sum of squared errors of the plane decoded after
// a `fast` BC3 encode of its coefficients at (x[0], x[1]) (what the brute-force grid of mavridis_presets.h
// evaluates per point). The error is a black box (a BC3 encoder inside), so:
//   interval enclosures are [0, +inf) (sound, uninformative: branch-and-bound solvers cannot prune),
//   gradients are central differences with step 1e-3 (not exact; the error is piecewise constant at fine scale),
//   no least-squares residuals.
#pragma once

#include <cmath>
#include <limits>

#include "core/problem.h"
#include "formats/mavridis/mavridis_plane_codec.h"

namespace blocklab {
namespace mavridis {

constexpr double kClampUpper = 0.6;
constexpr double kGammaLower = 0.5, kGammaUpper = 1.2;

class CoefficientProblem final : public Problem {
 public:
  CoefficientProblem(const Plane& plane, const WaveletSettings& settings)
      : Problem(2, Bounds{{0.0, kGammaLower}, {kClampUpper, kGammaUpper}}, {}), plane_(plane), settings_(settings) {}

  double eval(const double* x) const override {
    if (!(x[0] >= 0.0 && x[0] <= kClampUpper && x[1] >= kGammaLower && x[1] <= kGammaUpper))
      return std::numeric_limits<double>::quiet_NaN();
    return wavelet_plane_error(plane_, settings_, x[0], x[1]);
  }
  Interval eval(const Interval*) const override { return Interval(0.0, std::numeric_limits<double>::infinity()); }
  double eval_with_gradient(const double* x, double* gradient) const override {
    constexpr double kStep = 1e-3;
    for (int p = 0; p < 2; ++p) {
      double plus[2] = {x[0], x[1]}, minus[2] = {x[0], x[1]};
      plus[p] = std::fmin(plus[p] + kStep, upper(p));
      minus[p] = std::fmax(minus[p] - kStep, lower(p));
      gradient[p] = (eval(plus) - eval(minus)) / (plus[p] - minus[p]);
    }
    return eval(x);
  }
  bool is_smooth() const override { return false; }
  int residual_count() const override { return 0; }
  void eval_residuals(const double*, double*, double*) const override { fail_no_residuals(); }

 private:
  const Plane& plane_;
  WaveletSettings settings_;
};

}  // namespace mavridis
}  // namespace blocklab
