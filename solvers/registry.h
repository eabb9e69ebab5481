// The explicit table of solvers (DESIGN.md: no self-registering statics): solvers/registry.cpp lists them all.
#pragma once

#include <string>
#include <vector>

#include "solvers/solver.h"

namespace blocklab {

const std::vector<const Solver*>& all_solvers();
// Throws Error("unknown solver 'x'; valid solvers: a, b, c").
const Solver& find_solver(const std::string& name);

}  // namespace blocklab
