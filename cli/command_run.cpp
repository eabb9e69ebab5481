// `blocklab run CONFIG`: runs an experiment, prints the results table on stdout, progress on stderr.
#include <cstdio>

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
  return summary.failed == 0 ? 0 : 1;
}

}  // namespace blocklab::cli
