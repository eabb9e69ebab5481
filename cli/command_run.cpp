// `blocklab run CONFIG`: runs an experiment, prints the results table on stdout; the plan's size, progress and,
// when cells failed, one line naming the first failure on stderr (exit 1).
// `--shard i/n` computes one static share of the cells (experiments/shard.h); started by mpirun, the ranks share
// the cells (experiments/cell_dispatch.h) and only rank 0 prints. docs/cluster.md has the batch recipes.
#include <cstdio>
#include <memory>
#include <string>

#include "cli/commands.h"
#include "cli/progress.h"
#include "experiments/runner.h"

namespace blocklab::cli {

namespace {

int report(const RunSummary& summary) {
  std::printf("%s", format_results_table(summary).c_str());
  // Say which variant each metric column is (e.g. mPSNR's stop range), so a table is never ambiguous on its own.
  std::printf("\n");
  for (std::size_t m = 0; m < summary.metric_names.size(); ++m)
    std::printf("  %-11s %s\n", summary.metric_names[m].c_str(), summary.metric_legend[m].c_str());
  std::printf("\n%zu cells: %zu computed, %zu cached, %zu failed\n", summary.total, summary.computed, summary.cached,
              summary.failed);
  if (!summary.shard.whole()) {
    std::printf("shard %s of %zu cells: results%s.jsonl / .csv; join the shards with blocklab merge\n",
                summary.shard.text().c_str(), summary.experiment_cells, summary.shard.file_suffix().c_str());
  }
  std::printf("run folder: %s\n", summary.run_dir.c_str());
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

}  // namespace

int run_run(const RunArgs& args) {
  RunOptions options;
  options.config_path = args.config;
  options.out_dir = args.out_dir;
  options.data_root = args.data_root;
  options.threads = args.threads;
  options.fresh = args.fresh;
  options.max_cells = args.max_cells;
  if (!args.shard.empty()) options.shard = parse_shard(args.shard);
  // The one seam to MPI: a dispatcher over the ranks when mpirun started this process (and the build has MPI).
  const std::unique_ptr<CellDispatcher> dispatcher = make_cell_dispatcher();
  options.dispatcher = dispatcher.get();
  const bool speaks = dispatcher->rank() == 0 && !args.quiet;
  ProgressDisplay progress(speaks);
  // The size of the plan, before any image is hashed or cell keyed (a long run says how long it will be).
  options.on_plan = [&](const PlanEvent& plan) {
    if (!speaks) return;
    std::string share;
    if (!options.shard.whole()) {
      const std::size_t n = options.shard.count, mine = (plan.cells + n - 1 - options.shard.index) / n;
      share = "; shard " + options.shard.text() + " computes " + std::to_string(mine) + " of them";
    }
    if (dispatcher->is_mpi()) share += "; spread over " + dispatcher->description();
    std::fprintf(stderr, "blocklab: run: %zu cells (%zu format variants and ablations x %zu images)%s\n", plan.cells,
                 plan.treatments, plan.images, share.c_str());
  };
  options.on_progress = [&progress](const ProgressEvent& e) { progress.update(e.done, e.total, e.cached, e.current); };
  RunSummary summary;
  try {
    summary = run_experiment(options);
  } catch (const RankZeroFailed&) {
    return 1;   // rank 0 prints why
  } catch (const std::exception& e) {
    dispatcher->abort_job_for(e.what());   // a rank other than 0 ends the job; rank 0 and single processes go on
    throw;
  }
  progress.finish();
  if (dispatcher->rank() != 0) return 0;
  return report(summary);
}

}  // namespace blocklab::cli
