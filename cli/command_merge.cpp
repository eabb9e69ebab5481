// `blocklab merge RUN_DIR... --out DIR`: joins run folders of one experiment (the shards of `run --shard i/n`)
// into one run folder with results.jsonl / results.csv (experiments/run_merge.h). Prints the results table and a
// summary on stdout; refuses folders of different configs, or cells no folder holds, with one line on stderr; exits
// 1 (after writing everything) when cells failed, like `run`.
#include <cstdio>

#include "cli/commands.h"
#include "experiments/run_merge.h"
#include "experiments/runner.h"

namespace blocklab::cli {

int run_merge(const MergeArgs& args) {
  const MergeSummary merged = merge_run_folders(args.run_dirs, args.out_dir, args.threads);
  RunSummary table;
  table.records = merged.records;
  table.metric_names = merged.metric_names;
  std::printf("%s", format_results_table(table).c_str());
  std::printf("\n%zu cells from %zu run folders: %zu ok, %zu failed\nrun folder: %s\n", merged.cells,
              args.run_dirs.size(), merged.ok, merged.failed, merged.out_dir.c_str());
  if (merged.failed == 0) return 0;
  std::fprintf(stderr, "blocklab: error: %zu of %zu merged cells failed (status \"error\" in %s/results.jsonl)\n",
               merged.failed, merged.cells, merged.out_dir.c_str());
  return 1;
}

}  // namespace blocklab::cli
