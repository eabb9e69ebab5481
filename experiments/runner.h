// Running an experiment: config -> cells -> run folder (experiments/run_folder.h) -> results.jsonl / results.csv.
//
// Cells are images x treatments, IMAGE-MAJOR: for each image (config order, globs sorted), for each format variant
// (entry order, sweeps first-option-outermost), baseline then each applicable ablation (file order). Everything is
// validated, every image found and hashed, and config.yaml / resolved.json / provenance.json written before the
// first cell runs. The number of cells is checked against RunOptions.max_cells from the list lengths before the
// config is expanded, and again with the real image count before any image is hashed. A cell whose record file
// exists with status "ok" is served from the cache (the store is scanned before any cell runs, so the progress
// knows how many cells remain); a failed cell (blocklab::Error from reading, the input policy, encode, decode or a
// metric) is recorded with status "error" and retried by the next run, and the other cells continue. Library code
// never prints: progress goes to on_progress.
//
// Beyond one process: RunOptions.shard computes one static share of the cells (experiments/shard.h) and writes
// results.shard-i-of-n.jsonl / .csv and provenance.shard-i-of-n.json instead of the whole-run names (blocklab merge
// joins shards, experiments/run_merge.h); RunOptions.dispatcher spreads the cells over the ranks of an MPI job
// (experiments/cell_dispatch.h). Each record names the host, and the MPI rank, that computed it.
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "experiments/cell_dispatch.h"
#include "experiments/config.h"
#include "experiments/shard.h"

namespace blocklab {

// Sent before each cell that is computed (cells served from the cache send none) and once at the end.
struct ProgressEvent {
  std::size_t done = 0, total = 0, cached = 0;   // done includes the cached cells; total is this run's (shard's) cells
  std::string current;           // the cell about to run, e.g. "Desk.exr fp16" ("... on rank 2" under MPI); "" on
                                 // the final event
};

// The size of the plan, known once the images are found and before any image is hashed or cell keyed.
struct PlanEvent {
  std::size_t cells = 0, treatments = 0, images = 0;   // cells = treatments x images
};

struct RunOptions {
  std::string config_path, out_dir, data_root;   // out_dir "" -> runs/<name> under the current directory
  int threads = 0;                               // 0 = all hardware threads (not part of cell keys)
  bool fresh = false;                            // recompute cells even when cached
  std::uint64_t max_cells = kDefaultMaxCells;    // a larger plan is refused before it is built (experiments/sweep.h)
  ShardSpec shard;                               // the share of the cells this run computes (default: all)
  CellDispatcher* dispatcher = nullptr;          // nullptr: this process computes every cell (the local dispatcher)
  std::function<void(const PlanEvent&)> on_plan;
  std::function<void(const ProgressEvent&)> on_progress;
};

struct RunSummary {
  std::string run_dir;
  int rank = 0;                                  // under MPI only rank 0's summary holds counts and records
  ShardSpec shard;
  std::size_t experiment_cells = 0;              // all cells of the experiment, whatever the shard
  std::size_t total = 0, cached = 0, computed = 0, failed = 0;   // of this run's (shard's) cells
  std::vector<nlohmann::json> records;           // this run's cells in cell order, as stored in the cell files
  std::vector<std::string> metric_names;         // the config's metrics, in config order (CSV / table columns)
  std::vector<std::string> metric_legend;        // per column: the metric's description and its options as written
};

RunSummary run_experiment(const RunOptions& options);
// Same with another catalog of formats and metrics (tests).
RunSummary run_experiment(const RunOptions& options, const Catalog& catalog);

// Aligned text table, one row per record: format (label, + ablation), image, bpp, each metric, encode s, decode s,
// status. Empty `metric_columns` means summary.metric_names.
std::string format_results_table(const RunSummary& summary, const std::vector<std::string>& metric_columns = {});

}  // namespace blocklab
