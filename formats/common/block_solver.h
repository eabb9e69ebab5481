// A block format's parameter search routed through the solver library (solvers/): the format options `solver` and
// `solver_options`, shared by every format whose blocks are searched as a Problem (core/problem.h).
//
//   solver          `builtin` (the format's own specialised search pipeline) or the name of any registered solver
//                   (solvers/registry.h: exhaustive, anneal, nlopt, interval_bb, ...). Solvers that need something
//                   the block Problem does not have (ceres_lm needs a least-squares form; exhaustive refuses lattices
//                   that are too large) fail with an Error naming the solver and the reason.
//   solver_options  "key=value, key=value" for the chosen solver (its own option keys, `blocklab list` shows them);
//                   resolved with the solver's option specs when encoding starts, so an unknown key or a bad value is
//                   an Error naming the solver, the key and the valid keys before any block is encoded.
//   seed            the formats' common option: block b's solve gets derive_stream_seed(seed, b) (solvers/seeding.h),
//                   so the bytes depend only on (image, options), never on the thread count or block order.
//
// Every solve starts from the builtin search's `fast` answer (the start point); the solver's answer is used as it
// is, snapped to the storage lattice when the solver returns a continuous point, so an experiment measures the
// solver and not a min() with the builtin encoder.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "core/options.h"
#include "core/problem.h"
#include "solvers/solver.h"

namespace blocklab {

// "key=value, key=value" -> {key: value} for a solver-options text option named `option_name` (blanks around keys
// and values dropped; an empty text is no options). Throws Error("<who>: option '<option_name>': ...") on an empty
// item ("a=1,,b=2", a trailing comma), an item without '=' or with an empty key, and a key given twice.
SolverOptions parse_solver_option_list(const std::string& text, const std::string& option_name, const std::string& who);

// The two option specs (`solver`, `solver_options`); `what` names the searched parameters in the help text.
std::vector<OptionSpec> block_solver_option_specs(const std::string& what);

struct BlockSolverSetup {
  const Solver* solver = nullptr;   // null: the format's builtin search
  SolverOptions solver_options;     // resolved with the solver's specs
  std::uint64_t seed = 1;           // the format's `seed` option

  bool builtin() const { return solver == nullptr; }
};

// Reads `solver`, `solver_options` and `seed` from resolved format options; throws Error("<format>: ...") on an
// unknown solver, a malformed "key=value" list or options the solver rejects.
BlockSolverSetup parse_block_solver(const Options& format_options, const std::string& format_name);

// Solves `problem` for block `block_index` from `start` (dim() values) and returns the answer as lattice indices,
// one per parameter (the problem must have a full lattice): the solver's lattice_indices when it returned them,
// otherwise each parameter's nearest lattice point. A solver that fails (Termination::failed) leaves the start.
std::vector<std::int64_t> solve_block_on_lattice(const BlockSolverSetup& setup, const Problem& problem,
                                                 const std::vector<double>& start, std::size_t block_index);

}  // namespace blocklab
