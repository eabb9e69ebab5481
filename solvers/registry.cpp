// The explicit table of solvers (DESIGN.md: no self-registering statics). To add a solver, declare its accessor
// (`const Solver& <name>_solver();`) in solvers/<name>/<name>_solver.h and add one line to the table below; the
// registry test checks that names are unique and every solver's options resolve with their defaults.
#include "solvers/registry.h"

#include "core/error.h"
#include "solvers/exhaustive/exhaustive_solver.h"

namespace blocklab {

const std::vector<const Solver*>& all_solvers() {
  // Built on first use (thread-safe function-local static), in the order `blocklab list` shows them.
  static const std::vector<const Solver*> table = {
      &exhaustive_solver(),
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
