// `blocklab analyze CONFIG`: the command line of the analysis registry (experiments/analysis.h), which holds the
// config schema, the analyses (experiments/analysis_<name>.cpp, one per file) and what each writes.
#include "cli/commands.h"
#include "experiments/analysis.h"

namespace blocklab::cli {

int run_analyze(const AnalyzeArgs& args) {
  AnalyzeOptions options;
  options.out_dir = args.out_dir;
  options.data_root = args.data_root;
  run_analysis_config(args.config, options);
  return 0;
}

}  // namespace blocklab::cli
