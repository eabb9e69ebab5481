// `blocklab bench solvers`: the command line of experiments/solver_bench.h (run_solver_bench), which holds the
// benchmark, its problems (the registered formats' block-problem tables, named "<format>.<problem>") and what each
// column means. docs/solver-bench.md holds a measured table and the command.
// Data root: --data-root, else BLOCKLAB_DATA_ROOT, else the bundled samples (the same relative names). --images a,b
// restricts the sampling to those files (paths relative to the data root), e.g. one image at a time for per-image
// rows. Solver options: --set solver.key=value (applies to that solver wherever it appears in a chain).
#include <cstdlib>
#include <iostream>
#include <string>
#include <vector>

#include "cli/commands.h"
#include "core/error.h"
#include "experiments/solver_bench.h"

namespace blocklab::cli {

namespace {

std::vector<std::string> split_list(const std::string& text, const char* flag) {
  std::vector<std::string> items;
  std::size_t begin = 0;
  while (begin <= text.size()) {
    std::size_t end = text.find(',', begin);
    if (end == std::string::npos) end = text.size();
    std::string item = text.substr(begin, end - begin);
    item.erase(0, item.find_first_not_of(" \t"));
    item.erase(item.find_last_not_of(" \t") + 1);
    if (item.empty()) fail(flag, "empty entry in '" + text + "'");
    items.push_back(item);
    begin = end + 1;
  }
  return items;
}

}  // namespace

int run_bench(const BenchArgs& args) {
  if (args.what == "sweep") return run_bench_sweep(args);
  if (args.what != "solvers") fail("bench", "unknown benchmark '" + args.what + "'; valid: solvers, sweep");
  SolverBenchSettings settings;
  settings.problems = split_list(args.problems, "--problems");
  if (!args.solvers.empty()) settings.solvers = split_list(args.solvers, "--solvers");
  if (!args.images.empty()) settings.images = split_list(args.images, "--images");
  settings.data_root = args.data_root;
  if (settings.data_root.empty()) {
    const char* env = std::getenv("BLOCKLAB_DATA_ROOT");
    settings.data_root = env != nullptr && *env != '\0' ? env : std::string(BLOCKLAB_SOURCE_DIR) + "/samples";
  }
  for (const std::string& setting : args.settings) {
    const auto [key, value] = split_setting(setting, "--set");
    const auto dot = key.find('.');
    if (dot == std::string::npos || dot == 0 || dot + 1 == key.size())
      fail("--set", "expected solver.key=value, got '" + setting + "'");
    settings.solver_options[key.substr(0, dot)][key.substr(dot + 1)] = value;
  }
  settings.blocks = args.blocks;
  settings.seed = args.seed;
  settings.certify_boxes = args.certify_boxes;
  settings.threads = args.threads;
  run_solver_bench(settings, std::cout);
  return 0;
}

}  // namespace blocklab::cli
