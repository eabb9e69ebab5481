// `blocklab merge RUN_DIR... --out DIR`: joins the run folders of one experiment computed apart (the shards of
// `run --shard i/n`, experiments/shard.h, or runs on different machines) into one run folder.
//
// The folders must hold one plan: their resolved.json must agree on everything but the locations config_path and
// data_root (same experiment, images and their digests, formats, variants, metrics, cells and keys); otherwise the
// merge is refused naming both folders and what differs. Every cell of the plan is taken from the first folder,
// in argument order, holding a valid record of it with status "ok", else the first holding any valid record (a
// failed cell stays failed); a cell in none of them is an Error naming how many are missing and the first.
// DIR becomes a complete run folder: config.yaml and resolved.json of the first folder, every cell file, and
// results.jsonl / results.csv in cell order, byte-identical to what one process computing every cell writes apart
// from the execution fields (timings, host, rank; experiments/results_writer.h). provenance.json records the
// folders merged and keeps the provenance files found in each. A later `blocklab run CONFIG --out DIR` finds every
// cell cached. DIR may be one of the inputs (shards that wrote into one shared folder).
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace blocklab {

struct MergeSummary {
  std::string out_dir;
  std::size_t cells = 0, ok = 0, failed = 0;
  std::vector<nlohmann::json> records;     // in cell order
  std::vector<std::string> metric_names;   // results columns, from resolved.json
};

MergeSummary merge_run_folders(const std::vector<std::string>& run_dirs, const std::string& out_dir, int threads);

}  // namespace blocklab
