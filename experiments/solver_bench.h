// `blocklab bench solvers` as a library function: every solver of the library on the block problems the formats
// declare (formats/format.h BlockProblem, formats/registry.h registered_block_problems), drawn from the blocks of
// real images (experiments/block_samples.h), against the certified optimum. cli/command_bench.cpp parses the
// command line and calls it; tests call it directly (a registered test format's problems are benchmarked too).
// docs/solver-bench.md holds a measured table and the command.
#pragma once

#include <cstdint>
#include <map>
#include <ostream>
#include <string>
#include <vector>

#include "solvers/solver.h"

namespace blocklab {

struct SolverBenchSettings {
  std::string data_root;                // holds ldr/ and hdr/
  // "<format>.<problem>" or "<format>" (every problem of that format), in the order the tables are printed.
  std::vector<std::string> problems;
  // Registry names or chains "a+b"; empty = every solver and procrustes+lattice_polish.
  std::vector<std::string> solvers;
  std::vector<std::string> images;      // relative to data_root; empty = every image of the problem's kind folder
  std::map<std::string, SolverOptions> solver_options;   // given per solver name (unresolved)
  int blocks = 100;
  std::uint64_t seed = 1;
  long long certify_boxes = 2000000;    // interval_bb budget of the certification
  int threads = 0;
};

// The problem names a `problems` entry stands for: itself when it is "<format>.<problem>", every problem of the
// format for a format name. Throws Error("--problems: unknown problem 'x'; valid problems: ...").
std::vector<std::string> expand_bench_problem_names(const std::vector<std::string>& entries);

// Prints one markdown table (header, then per problem one row per solver and a certification row) to `out`.
// Throws Error on an unknown problem or solver, a bad solver option, or a data root without images.
void run_solver_bench(const SolverBenchSettings& settings, std::ostream& out);

}  // namespace blocklab
