// `nlopt` solver (solvers/nlopt/nlopt_solver.h): any NLopt algorithm by name over a Problem, Jet gradients for
// the gradient-based ones, seeded and serialised stochastic algorithms.
#include "solvers/nlopt/nlopt_solver.h"

#include <nlopt.h>

#include <algorithm>
#include <cfloat>
#include <chrono>
#include <cmath>
#include <limits>
#include <memory>
#include <mutex>
#include <string>
#include <type_traits>
#include <vector>

#include "core/error.h"

namespace blocklab {

namespace {

constexpr const char* kName = "nlopt";

constexpr const char* kDescription =
    "any NLopt 2.7 algorithm by name (Jet gradients for LD/GD, seeded with nlopt_srand)";

// Every option of NloptOptions, declared once (core/options.h OptionTable): specs, is_valid and from_resolved.
const OptionTable<NloptOptions>& nlopt_option_table() {
  static const auto table = OptionTable<NloptOptions>()
      .choice("algorithm", &NloptOptions::algorithm, nlopt_algorithm_names(), "NLopt algorithm name")
      .choice("local_algorithm", &NloptOptions::local_algorithm, nlopt_algorithm_names(),
              "subsidiary local optimiser of AUGLAG and MLSL algorithms")
      .integer("max_evaluations", &NloptOptions::max_evaluations, 1, 2000000000, "maximum number of objective evaluations")
      .real("xtol_rel", &NloptOptions::xtol_rel, 0.0, 1.0, "relative parameter tolerance (0: off)")
      .real("ftol_rel", &NloptOptions::ftol_rel, 0.0, 1.0, "relative error tolerance (0: off)")
      .real("initial_step", &NloptOptions::initial_step, 0.0, 1.0,
            "initial step as a fraction of each parameter's box width (0: NLopt's default)")
      .integer("population", &NloptOptions::population, 0, 1000000000,
               "population of CRS / ISRES / ESCH / MLSL (0: NLopt's default)")
      .real("time_limit", &NloptOptions::time_limit, 0.0, DBL_MAX, kTimeLimitHelp, kLowerOpen);
  return table;
}

std::vector<OptionSpec> nlopt_option_specs() { return nlopt_option_table().specs(); }

bool contains(const std::string& text, const char* part) { return text.find(part) != std::string::npos; }

nlopt_algorithm algorithm_of(const std::string& name) {
  for (int a = 0; a < NLOPT_NUM_ALGORITHMS; ++a)
    if (name == nlopt_algorithm_to_string(static_cast<nlopt_algorithm>(a))) return static_cast<nlopt_algorithm>(a);
  fail(kName, "unknown algorithm '" + name + "'; valid algorithms: " + join_names(nlopt_algorithm_names()));
}

// The process-wide lock of NLopt's random generator (see the header).
std::mutex& nlopt_random_mutex() {
  static std::mutex mutex;
  return mutex;
}

// nlopt_optimize seeds the generator from the clock the first time unless nlopt_srand was called; seed it once
// up front (under the lock) so a deterministic solve never writes the generator while a stochastic one runs.
void ensure_nlopt_seeded_once() {
  static std::once_flag once;
  std::call_once(once, [] {
    std::lock_guard<std::mutex> lock(nlopt_random_mutex());
    nlopt_srand(0);
  });
}

struct OptDeleter {
  void operator()(nlopt_opt opt) const { nlopt_destroy(opt); }
};
using OptHandle = std::unique_ptr<std::remove_pointer_t<nlopt_opt>, OptDeleter>;

// The objective NLopt calls: counts evaluations, keeps the best valid point.
struct ObjectiveContext {
  const Problem* problem = nullptr;
  Summary* summary = nullptr;
  std::vector<double> best;
  double best_error = std::numeric_limits<double>::quiet_NaN();
  bool found = false;
};

double objective(unsigned n, const double* x, double* gradient, void* data) {
  ObjectiveContext& context = *static_cast<ObjectiveContext*>(data);
  double error;
  if (gradient != nullptr) {
    ++context.summary->gradient_evaluations;
    error = context.problem->eval_with_gradient(x, gradient);
  } else {
    ++context.summary->evaluations;
    error = context.problem->eval(x);
  }
  if (std::isnan(error)) {
    // Invalid point: a very bad but finite value, and no slope to follow.
    if (gradient != nullptr) std::fill(gradient, gradient + n, 0.0);
    return DBL_MAX;
  }
  if (!context.found || error < context.best_error) {   // strict: the earliest of equal errors stays
    context.best.assign(x, x + n);
    context.best_error = error;
    context.found = true;
  }
  return error;
}

Termination termination_of(nlopt_result code) {
  switch (code) {
    case NLOPT_SUCCESS:
    case NLOPT_STOPVAL_REACHED:
    case NLOPT_FTOL_REACHED:
    case NLOPT_XTOL_REACHED: return Termination::converged;
    case NLOPT_MAXEVAL_REACHED: return Termination::max_evaluations;
    case NLOPT_MAXTIME_REACHED: return Termination::max_seconds;
    case NLOPT_ROUNDOFF_LIMITED: return Termination::no_progress;
    default: return Termination::failed;
  }
}

void check(nlopt_result code, nlopt_opt opt, const char* what) {
  if (code >= 0) return;
  const char* message = opt != nullptr ? nlopt_get_errmsg(opt) : nullptr;
  fail(kName, std::string(what) + " failed: " + nlopt_result_to_string(code) +
                  (message != nullptr ? std::string(" (") + message + ")" : std::string()));
}

double start_value(const Problem& problem, int p, const double* start) {
  const double lo = problem.lower(p), hi = problem.upper(p);
  if (start != nullptr) {
    double value = start[p];
    if (!(value >= lo)) value = lo;   // below the box or NaN: the lower bound
    if (value > hi) value = hi;
    if (std::isfinite(value)) return value;   // NaN start with no finite lower bound: the centre rule below
  }
  if (std::isfinite(lo) && std::isfinite(hi)) return lo + 0.5 * (hi - lo);
  if (std::isfinite(lo)) return lo;
  if (std::isfinite(hi)) return hi;
  return 0.0;
}

}  // namespace

const std::vector<std::string>& nlopt_algorithm_names() {
  static const std::vector<std::string> names = [] {
    std::vector<std::string> list;
    for (int a = 0; a < NLOPT_NUM_ALGORITHMS; ++a) list.push_back(nlopt_algorithm_to_string(static_cast<nlopt_algorithm>(a)));
    return list;
  }();
  return names;
}

bool nlopt_algorithm_is_stochastic(const std::string& name) {
  // NLopt's algorithm reference: the randomised DIRECT-L and StoGO variants, CRS, ISRES, ESCH, MLSL (random or
  // low-discrepancy starting points, both reached through the shared generator) and PRAXIS draw random numbers.
  return contains(name, "RAND") || contains(name, "MLSL") || name == "GN_CRS2_LM" || name == "GN_ISRES" ||
         name == "GN_ESCH" || name == "LN_PRAXIS";
}

bool NloptOptions::is_valid(std::string* why) const { return nlopt_option_table().is_valid(*this, why); }

NloptOptions NloptOptions::from_resolved(const SolverOptions& resolved) {
  return nlopt_option_table().from_resolved(resolved);
}

SolveResult solve_nlopt(const Problem& problem, const NloptOptions& options, const double* start,
                        std::uint64_t seed) {
  const auto started = std::chrono::steady_clock::now();
  require_valid_options(kName, options);
  const nlopt_algorithm algorithm = algorithm_of(options.algorithm);
  const int dim = problem.dim();
  const unsigned n = static_cast<unsigned>(dim);
  const bool global = options.algorithm[0] == 'G';
  for (int p = 0; p < dim; ++p) {
    const bool finite = std::isfinite(problem.lower(p)) && std::isfinite(problem.upper(p));
    if (global && !finite)
      fail(kName, "global algorithm " + options.algorithm + " needs finite bounds; parameter " + std::to_string(p) +
                      " has an infinite bound");
    if (options.initial_step > 0.0 && !finite)
      fail(kName, "initial_step is a fraction of the box width, but parameter " + std::to_string(p) +
                      " has an infinite bound (use initial_step = 0)");
  }

  SolveResult result = begin_solve(kName, problem, start, seed);
  Summary& summary = result.summary;
  std::vector<double> x(n);
  for (int p = 0; p < dim; ++p) x[static_cast<std::size_t>(p)] = start_value(problem, p, start);

  OptHandle opt(nlopt_create(algorithm, n));
  if (!opt) fail(kName, "nlopt_create failed for " + options.algorithm + " in dimension " + std::to_string(dim));
  check(nlopt_set_lower_bounds(opt.get(), problem.bounds().lower.data()), opt.get(), "setting the lower bounds");
  check(nlopt_set_upper_bounds(opt.get(), problem.bounds().upper.data()), opt.get(), "setting the upper bounds");
  ObjectiveContext context;
  context.problem = &problem;
  context.summary = &summary;
  check(nlopt_set_min_objective(opt.get(), objective, &context), opt.get(), "setting the objective");
  check(nlopt_set_maxeval(opt.get(), static_cast<int>(options.max_evaluations)), opt.get(), "setting maxeval");
  check(nlopt_set_xtol_rel(opt.get(), options.xtol_rel), opt.get(), "setting xtol_rel");
  check(nlopt_set_ftol_rel(opt.get(), options.ftol_rel), opt.get(), "setting ftol_rel");
  // NLopt's clock starts in nlopt_optimize: it gets what the set-up left of the limit (a tiny positive rest, since
  // maxtime 0 means no limit to NLopt).
  check(nlopt_set_maxtime(opt.get(), std::max(options.time_limit - seconds_since(started), 1e-9)), opt.get(),
        "setting maxtime");
  if (options.initial_step > 0.0) {
    std::vector<double> step(n);
    for (int p = 0; p < dim; ++p) {
      const double width = problem.upper(p) - problem.lower(p);
      // A fixed parameter (zero width) still needs a non-zero step for NLopt's checks; it cannot move anyway.
      step[static_cast<std::size_t>(p)] = width > 0.0 ? options.initial_step * width : options.initial_step;
    }
    check(nlopt_set_initial_step(opt.get(), step.data()), opt.get(), "setting initial_step");
  }
  if (options.population > 0)
    check(nlopt_set_population(opt.get(), static_cast<unsigned>(options.population)), opt.get(),
          "setting population");
  const bool has_local = contains(options.algorithm, "AUGLAG") || contains(options.algorithm, "MLSL");
  if (has_local) {
    OptHandle local(nlopt_create(algorithm_of(options.local_algorithm), n));
    if (!local) fail(kName, "nlopt_create failed for local_algorithm " + options.local_algorithm);
    check(nlopt_set_xtol_rel(local.get(), options.xtol_rel), local.get(), "setting the local xtol_rel");
    check(nlopt_set_ftol_rel(local.get(), options.ftol_rel), local.get(), "setting the local ftol_rel");
    check(nlopt_set_local_optimizer(opt.get(), local.get()), opt.get(), "setting local_algorithm");   // copies it
  }

  ensure_nlopt_seeded_once();
  const bool stochastic = nlopt_algorithm_is_stochastic(options.algorithm) ||
                          (has_local && nlopt_algorithm_is_stochastic(options.local_algorithm));
  double final_value = 0.0;
  nlopt_result code;
  if (stochastic) {
    // Held from seeding to the end of the solve: NLopt's generator is shared (see the header).
    std::lock_guard<std::mutex> lock(nlopt_random_mutex());
    nlopt_srand(static_cast<unsigned long>(seed));
    code = nlopt_optimize(opt.get(), x.data(), &final_value);
  } else {
    code = nlopt_optimize(opt.get(), x.data(), &final_value);
  }
  if (code == NLOPT_INVALID_ARGS || code == NLOPT_OUT_OF_MEMORY) check(code, opt.get(), options.algorithm.c_str());

  summary.termination = termination_of(code);
  summary.message = options.algorithm + ": " + nlopt_result_to_string(code);
  if (code == NLOPT_MAXTIME_REACHED) summary.message += " (" + TimeLimit(started, options.time_limit).message() + ")";
  if (context.found) {
    result.parameters = context.best;
    summary.final_error = context.best_error;
    // NLopt can end with FAILURE/FORCED_STOP after valid evaluations; the best point is still an answer.
    if (summary.termination == Termination::failed) summary.termination = Termination::no_progress;
  } else {
    result.parameters = x;
    summary.termination = Termination::failed;
    summary.message += "; the error was NaN at every evaluated point";
  }
  summary.seconds = seconds_since(started);
  return result;
}

const Solver& nlopt_solver() {
  static const TypedSolver<NloptOptions> solver(kName, kDescription, nlopt_option_specs, solve_nlopt);
  return solver;
}

}  // namespace blocklab
