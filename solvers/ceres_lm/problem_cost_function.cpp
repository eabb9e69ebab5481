// ProblemCostFunction (solvers/ceres_lm/problem_cost_function.h): Problem residuals + Jet Jacobian for Ceres.
#include "solvers/ceres_lm/problem_cost_function.h"

#include <cmath>
#include <string>

#include "core/error.h"

namespace blocklab {

ProblemCostFunction::ProblemCostFunction(const Problem& problem, const char* who) : problem_(problem) {
  if (problem.residual_count() <= 0)
    fail(who, "the problem has no least-squares form (its error functor declares no kResiduals / residuals); "
              "Levenberg-Marquardt needs residuals: use a scalar-error solver such as nlopt or anneal");
  set_num_residuals(problem.residual_count());
  mutable_parameter_block_sizes()->push_back(problem.dim());
}

bool ProblemCostFunction::Evaluate(double const* const* parameters, double* residuals, double** jacobians) const {
  double* jacobian = jacobians != nullptr ? jacobians[0] : nullptr;
  problem_.eval_residuals(parameters[0], residuals, jacobian);
  if (jacobian != nullptr) ++jacobian_evaluations_; else ++residual_evaluations_;
  const int count = problem_.residual_count();
  for (int r = 0; r < count; ++r)
    if (!std::isfinite(residuals[r])) return false;   // NaN/inf residual: an invalid point for Ceres
  if (jacobian != nullptr)
    for (int k = 0; k < count * problem_.dim(); ++k)
      if (!std::isfinite(jacobian[k])) return false;   // a non-finite derivative would poison the LM step
  return true;
}

}  // namespace blocklab
