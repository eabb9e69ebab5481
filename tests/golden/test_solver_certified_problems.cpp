// Certified problems for every solver (the habit of Ceres' NIST tests: problems whose optimum is known exactly).
//
// Each problem has a closed-form optimum:
//   constant block      16 equal texels c: the BC4-like palette (SPECS.md 2.2 four-entry lerp, the PaletteFit of
//                       tests/contract/example_problems.h) reaches error 0 with an endpoint at c;
//   two-value block     texels a and b: error 0 with endpoints (a, b) (palette entries 0 and 3);
//   exact ramp          texels = the four palette entries of endpoints (e0, e1), computed by the same expression the
//                       error uses: error 0 at (e0, e1);
//   fp16-max block      texels 0 and 65504 (the largest finite binary16 value, IEEE 754-2008): error 0 with the
//                       optimum on the upper bound, at magnitudes where absolute tolerances break;
//   one outlier         least-squares constant fit to 15 texels at 0.25 and one at 0.9: the optimum is the mean
//                       0.290625 (exact in binary); on the lattice k/1024 the optimum is the nearest point, 298/1024
//                       (the error is a convex parabola).
// Lattice versions check the lattice solvers (exhaustive confirms the certified lattice optimum, anneal and
// coeff_search reach it); continuous versions with residuals check ceres_lm and nlopt from a reasonable start.
// Then: the same seed gives the same answer, and answers do not change when 4 threads solve different problems
// at once.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <functional>
#include <memory>
#include <string>
#include <thread>
#include <vector>

#include "core/problem.h"
#include "solvers/registry.h"
#include "solvers/solver.h"
#include "tests/contract/problem_contract.h"

namespace blocklab {
namespace {

// BC4-like 1-D block with a least-squares form: residual_i = texel_i - nearest palette entry (first on ties), so
// error = sum of residual_i^2 = the palette error of examples::PaletteFitError.
struct PaletteResidualError {
  static constexpr int kDim = 2;
  static constexpr int kResiduals = 16;
  std::array<double, kResiduals> texels{};

  template <typename T>
  static T palette_entry(const T* x, int k) {
    return x[0] * T((3.0 - k) / 3.0) + x[1] * T(k / 3.0);
  }
  template <typename T>
  void residuals(const T* x, T* r) const {
    for (int i = 0; i < kResiduals; ++i) {
      const T value = T(texels[static_cast<std::size_t>(i)]);
      T best = value - palette_entry(x, 0);
      for (int k = 1; k < 4; ++k) {
        const T difference = value - palette_entry(x, k);
        best = select(less(square(difference), square(best)), difference, best);
      }
      r[i] = best;
    }
  }
  template <typename T>
  T operator()(const T* x) const {
    return sum_of_squared_residuals<kResiduals>(*this, x);
  }
};

// Least-squares constant: residual_i = m - texel_i.
struct ConstantFitError {
  static constexpr int kDim = 1;
  static constexpr int kResiduals = 16;
  static constexpr bool kSmooth = true;
  std::array<double, kResiduals> texels{};
  template <typename T>
  void residuals(const T* x, T* r) const {
    for (int i = 0; i < kResiduals; ++i) r[i] = x[0] - T(texels[static_cast<std::size_t>(i)]);
  }
  template <typename T>
  T operator()(const T* x) const {
    return sum_of_squared_residuals<kResiduals>(*this, x);
  }
};

constexpr double kFp16Max = 65504.0;
const Lattice kUnitLattice = Lattice::uniform(0.0, 1.0, 64);   // k / 63
// 0, 736, ..., 65504: 65504 = 89 * 736, so the last point is exactly the fp16 maximum.
const Lattice kFp16Lattice{0.0, 736.0, 90};

struct CertifiedPaletteProblem {
  std::string name;
  PaletteResidualError error;
  double lower, upper;
  Lattice lattice;
  std::array<double, 2> reasonable_start;   // for local solvers: near the optimum, same texel assignment
  double energy;                            // sum of texel^2: the scale of "zero" for continuous solvers
};

std::vector<CertifiedPaletteProblem> certified_palette_problems() {
  std::vector<CertifiedPaletteProblem> problems;
  const auto add = [&](std::string name, const std::array<double, 16>& texels, double lower, double upper,
                       Lattice lattice, std::array<double, 2> start) {
    CertifiedPaletteProblem problem{std::move(name), {}, lower, upper, lattice, start, 0.0};
    problem.error.texels = texels;
    for (double t : texels) problem.energy += t * t;
    problems.push_back(problem);
  };
  std::array<double, 16> texels{};
  texels.fill(kUnitLattice.point(23));
  add("constant", texels, 0.0, 1.0, kUnitLattice, {0.30, 0.55});
  for (int i = 0; i < 16; ++i) texels[static_cast<std::size_t>(i)] = kUnitLattice.point(i % 3 == 0 ? 40 : 12);
  add("two_value", texels, 0.0, 1.0, kUnitLattice, {0.15, 0.60});
  const double ramp_ends[2] = {kUnitLattice.point(10), kUnitLattice.point(50)};
  for (int i = 0; i < 16; ++i)
    texels[static_cast<std::size_t>(i)] = PaletteResidualError::palette_entry(ramp_ends, i % 4);
  add("exact_ramp", texels, 0.0, 1.0, kUnitLattice, {0.20, 0.75});
  for (int i = 0; i < 16; ++i) texels[static_cast<std::size_t>(i)] = i % 2 == 0 ? 0.0 : kFp16Max;
  add("fp16_max", texels, 0.0, kFp16Max, kFp16Lattice, {5000.0, 60000.0});
  return problems;
}

ErrorProblem<PaletteResidualError> lattice_version(const CertifiedPaletteProblem& p) {
  return make_problem(p.error, Bounds{{p.lower, p.lower}, {p.upper, p.upper}}, {p.lattice, p.lattice});
}
ErrorProblem<PaletteResidualError> continuous_version(const CertifiedPaletteProblem& p) {
  return make_problem(p.error, Bounds{{p.lower, p.lower}, {p.upper, p.upper}});
}

ConstantFitError outlier_error() {
  ConstantFitError error;
  error.texels.fill(0.25);
  error.texels[7] = 0.9;
  return error;
}
constexpr double kOutlierMean = (15 * 0.25 + 0.9) / 16;   // 0.290625
const Lattice kOutlierLattice = Lattice::uniform(0.0, 1.0, 1025);   // k / 1024
constexpr std::int64_t kOutlierLatticeOptimum = 298;                // nearest k / 1024 to 0.290625 (297.6)

// Local continuous solvers reach "zero" to this fraction of the data energy (double rounding of the residuals
// leaves ~1e-32; tolerances of 1e-10 on parameters leave ~1e-20).
constexpr double kZeroRelativeToEnergy = 1e-16;

SolveResult solve_with(const std::string& solver, const Problem& problem, const SolverOptions& options,
                       const double* start, std::uint64_t seed) {
  return find_solver(solver).solve(problem, options, start, seed);
}

// The residual functors written for this file obey the Problem contract (error == sum of squared residuals,
// Jet/Interval agreement, Jacobians against finite differences).
TEST(CertifiedProblems, ProblemsObeyTheProblemContract) {
  for (const CertifiedPaletteProblem& p : certified_palette_problems()) {
    SCOPED_TRACE(p.name);
    contract::ContractOptions options;
    options.error_scale = p.energy;
    options.point_count = 100;
    options.box_count = 50;
    contract::check_problem_contract(continuous_version(p), options);
  }
  contract::check_problem_contract(make_problem(outlier_error(), Bounds{{0.0}, {1.0}}));
}

TEST(CertifiedProblems, ExhaustiveConfirmsTheLatticeOptimum) {
  for (const CertifiedPaletteProblem& p : certified_palette_problems()) {
    const auto problem = lattice_version(p);
    const SolveResult result = solve_with("exhaustive", problem, {}, nullptr, 0);
    EXPECT_EQ(result.summary.final_error, 0.0) << p.name << ": " << result.summary.brief_report();
    EXPECT_EQ(result.summary.termination, Termination::optimal) << p.name;
  }
  const auto outlier = make_problem(outlier_error(), Bounds{{0.0}, {1.0}}, {kOutlierLattice});
  const SolveResult result = solve_with("exhaustive", outlier, {}, nullptr, 0);
  EXPECT_EQ(result.lattice_indices, std::vector<std::int64_t>{kOutlierLatticeOptimum});
}

TEST(CertifiedProblems, AnnealReachesTheLatticeOptimum) {
  for (const CertifiedPaletteProblem& p : certified_palette_problems()) {
    const auto problem = lattice_version(p);
    const SolveResult result = solve_with("anneal", problem, {}, nullptr, 7);
    EXPECT_EQ(result.summary.final_error, 0.0) << p.name << ": " << result.summary.brief_report();
  }
  const auto outlier = make_problem(outlier_error(), Bounds{{0.0}, {1.0}}, {kOutlierLattice});
  EXPECT_EQ(solve_with("anneal", outlier, {}, nullptr, 7).lattice_indices,
            std::vector<std::int64_t>{kOutlierLatticeOptimum});
}

// coeff_search is grid-then-local: on the palette's multimodal error it needs a grid fine enough to land in the
// optimum's basin. With the default 9 points on the 64-level lattice, the two-value block's best grid point is
// (0, 39) (entries 0, 13, 26, 39 against texels 12 and 40) and coordinate hill climbing stops there, at the
// lattice-local optimum 16/63^2; 16 points (one per ~4 lattice steps) reach the certified zero.
TEST(CertifiedProblems, CoeffSearchReachesTheLatticeOptimum) {
  for (const CertifiedPaletteProblem& p : certified_palette_problems()) {
    const auto problem = lattice_version(p);
    const SolveResult result = solve_with("coeff_search", problem, {{"grid_points", "16"}}, nullptr, 0);
    EXPECT_EQ(result.summary.final_error, 0.0) << p.name << ": " << result.summary.brief_report();
  }
  const auto outlier = make_problem(outlier_error(), Bounds{{0.0}, {1.0}}, {kOutlierLattice});
  EXPECT_EQ(solve_with("coeff_search", outlier, {}, nullptr, 0).lattice_indices,
            std::vector<std::int64_t>{kOutlierLatticeOptimum});
}

TEST(CertifiedProblems, CeresLmReachesZeroFromAReasonableStart) {
  for (const CertifiedPaletteProblem& p : certified_palette_problems()) {
    const auto problem = continuous_version(p);
    const SolveResult result = solve_with("ceres_lm", problem, {}, p.reasonable_start.data(), 0);
    EXPECT_LE(result.summary.final_error, kZeroRelativeToEnergy * p.energy)
        << p.name << ": " << result.summary.brief_report();
  }
  const auto outlier = make_problem(outlier_error(), Bounds{{0.0}, {1.0}});
  const double start = 0.5;
  const SolveResult result = solve_with("ceres_lm", outlier, {}, &start, 0);
  // parameter_tolerance 1e-12 (the default) ends the iterations within ~1e-13 relative of the exact mean.
  EXPECT_NEAR(result.parameters[0], kOutlierMean, 1e-12 * kOutlierMean) << result.summary.brief_report();
}

TEST(CertifiedProblems, NloptLocalAndGlobalAlgorithmsReachTheOptimum) {
  for (const char* algorithm : {"LN_NELDERMEAD", "LN_SBPLX"}) {
    for (const CertifiedPaletteProblem& p : certified_palette_problems()) {
      const auto problem = continuous_version(p);
      const SolveResult result = solve_with("nlopt", problem, {{"algorithm", algorithm}, {"initial_step", "0.05"}},
                                            p.reasonable_start.data(), 0);
      EXPECT_LE(result.summary.final_error, kZeroRelativeToEnergy * p.energy)
          << algorithm << " " << p.name << ": " << result.summary.brief_report();
    }
  }
  const auto outlier = make_problem(outlier_error(), Bounds{{0.0}, {1.0}});
  for (const char* algorithm : {"LN_NELDERMEAD", "LN_BOBYQA", "LD_LBFGS", "GN_DIRECT_L"}) {
    const SolveResult result = solve_with("nlopt", outlier, {{"algorithm", algorithm}}, nullptr, 0);
    EXPECT_NEAR(result.parameters[0], kOutlierMean, 1e-8) << algorithm << ": " << result.summary.brief_report();
  }
}

// Every solver that takes a problem of this kind, with options for a quick but complete solve.
struct SolverRun {
  std::string solver;
  SolverOptions options;
  bool continuous;   // solves the continuous version (ceres_lm, nlopt) instead of the lattice one
};

std::vector<SolverRun> solver_runs() {
  return {{"exhaustive", {}, false},
          {"anneal", {{"iterations", "1500"}}, false},
          {"coeff_search", {{"grid_points", "16"}}, false},
          {"ceres_lm", {}, true},
          {"nlopt", {{"algorithm", "LN_SBPLX"}}, true},
          {"nlopt", {{"algorithm", "GN_CRS2_LM"}, {"max_evaluations", "600"}}, true}};
}

// One solve of problem `index` (a certified palette problem) by `run`, seeded with `seed`.
SolveResult solve_certified(const SolverRun& run, const CertifiedPaletteProblem& p, std::uint64_t seed) {
  if (run.continuous) {
    const auto problem = continuous_version(p);
    return solve_with(run.solver, problem, run.options, p.reasonable_start.data(), seed);
  }
  const auto problem = lattice_version(p);
  return solve_with(run.solver, problem, run.options, p.reasonable_start.data(), seed);
}

TEST(CertifiedProblems, SameSeedGivesTheSameAnswer) {
  const auto problems = certified_palette_problems();
  for (const SolverRun& run : solver_runs())
    for (const CertifiedPaletteProblem& p : problems) {
      const SolveResult a = solve_certified(run, p, 31);
      const SolveResult b = solve_certified(run, p, 31);
      EXPECT_EQ(a.parameters, b.parameters) << run.solver << " " << p.name;
      EXPECT_EQ(a.lattice_indices, b.lattice_indices) << run.solver << " " << p.name;
      EXPECT_EQ(a.summary.final_error, b.summary.final_error) << run.solver << " " << p.name;
    }
}

TEST(CertifiedProblems, AnswersDoNotChangeWhenFourThreadsSolveDifferentProblemsAtOnce) {
  const auto problems = certified_palette_problems();
  const auto runs = solver_runs();
  // Every (run, problem) pair, each with its own seed; solved sequentially, then spread over 4 threads.
  struct Job {
    std::size_t run, problem;
    std::uint64_t seed;
  };
  std::vector<Job> jobs;
  for (std::size_t r = 0; r < runs.size(); ++r)
    for (std::size_t p = 0; p < problems.size(); ++p) jobs.push_back({r, p, 1000 + 17 * r + p});
  std::vector<SolveResult> sequential, threaded(jobs.size());
  for (const Job& job : jobs) sequential.push_back(solve_certified(runs[job.run], problems[job.problem], job.seed));
  std::vector<std::thread> threads;
  for (std::size_t t = 0; t < 4; ++t)
    threads.emplace_back([&, t] {
      // Interleaved so that different solvers and problems run at the same time.
      for (std::size_t j = t; j < jobs.size(); j += 4)
        threaded[j] = solve_certified(runs[jobs[j].run], problems[jobs[j].problem], jobs[j].seed);
    });
  for (std::thread& thread : threads) thread.join();
  for (std::size_t j = 0; j < jobs.size(); ++j) {
    const std::string what = runs[jobs[j].run].solver + " " + problems[jobs[j].problem].name;
    EXPECT_EQ(sequential[j].parameters, threaded[j].parameters) << what;
    EXPECT_EQ(sequential[j].lattice_indices, threaded[j].lattice_indices) << what;
    EXPECT_EQ(sequential[j].summary.final_error, threaded[j].summary.final_error) << what;
    EXPECT_EQ(sequential[j].summary.evaluations, threaded[j].summary.evaluations) << what;
  }
}

}  // namespace
}  // namespace blocklab
