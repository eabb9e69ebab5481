// The `solver` / `solver_options` format options (formats/common/block_solver.h).
#include "formats/common/block_solver.h"

#include <cmath>

#include "core/error.h"
#include "solvers/registry.h"
#include "solvers/seeding.h"

namespace blocklab {

namespace {

std::string trimmed(const std::string& text) {
  const auto first = text.find_first_not_of(" \t");
  if (first == std::string::npos) return "";
  const auto last = text.find_last_not_of(" \t");
  return text.substr(first, last - first + 1);
}

}  // namespace

SolverOptions parse_solver_option_list(const std::string& text, const std::string& option_name, const std::string& who) {
  SolverOptions options;
  if (trimmed(text).empty()) return options;   // no options
  const std::string where = "option '" + option_name + "': ";
  std::size_t begin = 0;
  while (begin <= text.size()) {
    const std::size_t comma = text.find(',', begin);
    const std::string item = trimmed(text.substr(begin, comma == std::string::npos ? std::string::npos : comma - begin));
    begin = comma == std::string::npos ? text.size() + 1 : comma + 1;
    // "a=1,,b=2" or a trailing comma: an empty item is a typo, not "no option".
    if (item.empty()) fail(who, where + "empty item in '" + text + "' (expected key=value, key=value)");
    const std::size_t equals = item.find('=');
    if (equals == std::string::npos || equals == 0) fail(who, where + "'" + item + "' is not key=value");
    const std::string key = trimmed(item.substr(0, equals));
    if (options.count(key)) fail(who, where + "key '" + key + "' given twice");
    options[key] = trimmed(item.substr(equals + 1));
  }
  return options;
}

std::vector<OptionSpec> block_solver_option_specs(const std::string& what) {
  std::vector<std::string> choices = {"builtin"};
  for (const Solver* solver : all_solvers()) choices.push_back(solver->name());
  return {
      {"solver", OptionType::choice, "builtin", choices,
       "search of the " + what + ": builtin (the format's own pipeline) or a solver of the library"},
      {"solver_options", OptionType::text, "", {},
       "options of the chosen solver as 'key=value, key=value' (see `blocklab list` for each solver's keys)"},
  };
}

BlockSolverSetup parse_block_solver(const Options& format_options, const std::string& format_name) {
  BlockSolverSetup setup;
  setup.seed = static_cast<std::uint64_t>(option_int(format_options, "seed"));
  const std::string& name = option_text(format_options, "solver");
  const std::string& given = option_text(format_options, "solver_options");
  if (name == "builtin") {
    if (!trimmed(given).empty())
      fail(format_name, "option 'solver_options' is set ('" + given + "') but solver is 'builtin', which has none");
    return setup;
  }
  setup.solver = &find_solver(name);
  try {
    setup.solver_options = resolve_solver_options(*setup.solver, parse_solver_option_list(given, "solver_options", format_name));
  } catch (const Error& error) {
    fail(format_name, std::string("option 'solver_options': ") + error.what());
  }
  return setup;
}

std::vector<std::int64_t> solve_block_on_lattice(const BlockSolverSetup& setup, const Problem& problem,
                                                 const std::vector<double>& start, std::size_t block_index) {
  if (setup.builtin()) fail("block solver", "solve_block_on_lattice called with the builtin search");
  if (!problem.has_full_lattice()) fail(setup.solver->name(), "the block problem has no full storage lattice");
  const SolveResult result = setup.solver->solve(problem, setup.solver_options, start.data(),
                                                 derive_stream_seed(setup.seed, block_index));
  const int dim = problem.dim();
  const std::size_t size = static_cast<std::size_t>(dim);
  if (result.lattice_indices.size() == size) return result.lattice_indices;
  // A failed solve (no valid point found) or a malformed answer keeps the start point.
  const bool usable = result.summary.termination != Termination::failed && result.parameters.size() == size;
  std::vector<std::int64_t> indices(size);
  for (int p = 0; p < dim; ++p) {
    const double value = usable ? result.parameters[static_cast<std::size_t>(p)] : start[static_cast<std::size_t>(p)];
    // NaN cannot come from a solver that respects bounds; treat it like a failed solve for that parameter.
    const double safe = std::isnan(value) ? start[static_cast<std::size_t>(p)] : value;
    indices[static_cast<std::size_t>(p)] = problem.lattice(p).nearest_index(safe);
  }
  return indices;
}

}  // namespace blocklab
