// `blocklab run CONFIG`: runs an experiment, prints the results table on stdout; the plan's size, progress and,
// when cells failed, one line naming the first failure on stderr (exit 1).
#include <cstdio>
#include <string>

#include "cli/commands.h"
#include "cli/progress.h"
#include "experiments/runner.h"

namespace blocklab::cli {

int run_run(const RunArgs& args) {
  ProgressDisplay progress(!args.quiet);
  RunOptions options;
  options.config_path = args.config;
  options.out_dir = args.out_dir;
  options.data_root = args.data_root;
  options.threads = args.threads;
  options.fresh = args.fresh;
  options.max_cells = args.max_cells;
  // The size of the plan, before any image is hashed or cell keyed (a long run says how long it will be).
  options.on_plan = [&args](const PlanEvent& plan) {
    if (!args.quiet)
      std::fprintf(stderr, "blocklab: run: %zu cells (%zu format variants and ablations x %zu images)\n", plan.cells,
                   plan.treatments, plan.images);
  };
  options.on_progress = [&progress](const ProgressEvent& e) { progress.update(e.done, e.total, e.cached, e.current); };
  const RunSummary summary = run_experiment(options);
  progress.finish();
  std::printf("%s", format_results_table(summary).c_str());
  // Say which variant each metric column is (e.g. mPSNR's stop range), so a table is never ambiguous on its own.
  std::printf("\n");
  for (std::size_t m = 0; m < summary.metric_names.size(); ++m)
    std::printf("  %-11s %s\n", summary.metric_names[m].c_str(), summary.metric_legend[m].c_str());
  std::printf("\n%zu cells: %zu computed, %zu cached, %zu failed\nrun folder: %s\n", summary.total, summary.computed,
              summary.cached, summary.failed, summary.run_dir.c_str());
  if (summary.failed == 0) return 0;
  // The failures are in the table on stdout; stderr gets the one line every failure of the tool prints.
  std::string first_error;
  for (const nlohmann::json& record : summary.records) {
    if (record.value("status", std::string()) != "error") continue;
    first_error = record.value("image", std::string()) + " " + record.value("label", std::string()) + ": " +
                  record.value("error", std::string());
    break;
  }
  for (char& c : first_error)
    if (c == '\n' || c == '\r') c = ' ';
  std::fprintf(stderr, "blocklab: error: %zu of %zu cells failed (first: %s); run folder %s\n", summary.failed,
               summary.total, first_error.c_str(), summary.run_dir.c_str());
  return 1;
}

}  // namespace blocklab::cli
