// ProblemCostFunction: a blocklab Problem's least-squares form (Problem::eval_residuals) as one ceres::CostFunction
// with a single parameter block of dim() values; used by `ceres_lm` and by its gradient-check test
// (ceres::GradientChecker compares this analytic Jacobian with Ceres' numeric differentiation).
#pragma once

#include <ceres/cost_function.h>

#include <cstdint>

#include "core/problem.h"

namespace blocklab {

class ProblemCostFunction final : public ceres::CostFunction {
 public:
  // Throws Error("<who>: ...") when the problem has no residuals.
  ProblemCostFunction(const Problem& problem, const char* who);

  // residuals[0..residual_count()) and, when requested, jacobians[0] (row-major, residual_count() x dim(), the
  // layout Ceres expects for one parameter block). Returns false (an invalid point for Ceres) when a value is not
  // finite.
  bool Evaluate(double const* const* parameters, double* residuals, double** jacobians) const override;

  std::uint64_t residual_evaluations() const { return residual_evaluations_; }
  std::uint64_t jacobian_evaluations() const { return jacobian_evaluations_; }

 private:
  const Problem& problem_;
  // Counts of one solve (the cost function belongs to one solve on one thread, so plain counters suffice).
  mutable std::uint64_t residual_evaluations_ = 0;
  mutable std::uint64_t jacobian_evaluations_ = 0;
};

}  // namespace blocklab
