// Static shards of an experiment: `blocklab run CONFIG --shard i/n` computes one n-th of the expanded cells, so that
// n independent batch jobs (a Slurm job array, srun tasks) split a sweep between them; `blocklab merge` joins their
// run folders (experiments/run_merge.h). docs/cluster.md has the recipes.
//
// The split: the cells sorted by their key (a SHA-256, experiments/cell_key.h) and dealt round-robin, the j-th cell
// in key order going to shard j mod n. It depends only on the plan, so every machine computes the same split; the
// shards differ in size by at most one cell; and since key order is a pseudo-random permutation of the expansion
// order it is uncorrelated with the sweep's structure (a shard never gets "every thorough preset" or "every cell of
// the largest image", which a split by index would when the treatment count is a multiple of n). Costs that differ
// 1000x between cells still balance only on average: for those, many more shards than machines, or MPI's dynamic
// dispatch (experiments/cell_dispatch.h), do better.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

namespace blocklab {

struct ShardSpec {
  std::size_t index = 0, count = 1;   // shard `index` of `count` (0-based); count 1 = the whole experiment
  bool whole() const { return count == 1; }
  std::string text() const;          // "i/n"
  std::string file_suffix() const;   // ".shard-i-of-n", e.g. results.shard-0-of-4.jsonl
};

// Parses "i/n" (0 <= i < n, n >= 1, plain decimal); throws Error naming `flag` and the text otherwise.
ShardSpec parse_shard(const std::string& text, const std::string& flag = "--shard");

// The indices (into `cell_keys`, in increasing order, i.e. expansion order) of the cells of `shard`.
std::vector<std::size_t> shard_cells(const std::vector<std::string>& cell_keys, const ShardSpec& shard);

}  // namespace blocklab
