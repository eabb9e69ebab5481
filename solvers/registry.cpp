// The explicit table of solvers (DESIGN.md: no self-registering statics). To add a solver, declare its accessor
// (`const Solver& <name>_solver();`) in solvers/<name>/<name>_solver.h and add one line to the table below; the
// registry test checks that names are unique and every solver's options resolve with their defaults.
#include "solvers/registry.h"

#include "core/error.h"
#include "solvers/exhaustive/exhaustive_solver.h"
#include "solvers/anneal/anneal_solver.h"
#include "solvers/ceres_lm/ceres_lm_solver.h"
#include "solvers/coeff_search/coeff_search_solver.h"
#include "solvers/nlopt/nlopt_solver.h"
#include "solvers/interval_bb/interval_bb_solver.h"
#include "solvers/lattice_polish/lattice_polish_solver.h"
#include "solvers/procrustes/procrustes_solver.h"

namespace blocklab {

const std::vector<const Solver*>& all_solvers() {
  // Built on first use (thread-safe function-local static), in the order `blocklab list` shows them.
  static const std::vector<const Solver*> table = {
      &exhaustive_solver(),
      &anneal_solver(),
      &ceres_lm_solver(),
      &nlopt_solver(),
      &coeff_search_solver(),
      &procrustes_solver(),
      &interval_bb_solver(),
      &lattice_polish_solver(),
  };
  return table;
}

const Solver& find_solver(const std::string& name) {
  std::string valid;
  for (const Solver* solver : all_solvers()) {
    if (solver->name() == name) return *solver;
    valid += (valid.empty() ? "" : ", ") + solver->name();
  }
  // Never fall back silently on an unknown name: list the valid ones.
  throw Error("unknown solver '" + name + "'; valid solvers: " + valid);
}

}  // namespace blocklab
