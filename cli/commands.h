// The subcommands of the `blocklab` executable. Each returns the process exit code and throws blocklab::Error on
// failure (main() prints the message on one line and exits non-zero).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "core/image.h"
#include "formats/format.h"

namespace blocklab::cli {

struct ListArgs { bool json = false, markdown = false; };
int run_list(const ListArgs& args);

struct EncodeArgs {
  std::string format, input, output, input_policy = "clamp";
  std::string mode_map;                // optional: PNG of the per-block modes (formats/common/mode_map.h)
  std::vector<std::string> settings;   // "key=value"
  int threads = 0;
};
int run_encode(const EncodeArgs& args);

// An image file (EXR, PNG, .hdr, PFM) as read, or a packed texture (DDS, .blk; told apart by magic bytes) decoded
// with its format: what `decode` writes and what `compare` compares.
EncodedTexture read_packed(const std::string& path);
Image read_image_or_decode(const std::string& path, int threads);

struct DecodeArgs { std::string input, output; int threads = 0; };
int run_decode(const DecodeArgs& args);

struct CompareArgs {
  std::string reference, test, metrics, error_map_dir;
  std::vector<std::string> settings;   // metric options "metric.key=value"
  bool json = false, details = false;
  int threads = 0;
};
int run_compare(const CompareArgs& args);

struct RunArgs {
  std::string config, out_dir, data_root;
  std::string shard;                   // "i/n" (experiments/shard.h), "" = every cell
  bool fresh = false, quiet = false;
  int threads = 0;
  std::uint64_t max_cells = 100000;    // experiments/config.h kDefaultMaxCells
};
int run_run(const RunArgs& args);

// `blocklab merge RUN_DIR... --out DIR` (experiments/run_merge.h).
struct MergeArgs {
  std::vector<std::string> run_dirs;
  std::string out_dir;
  int threads = 0;
};
int run_merge(const MergeArgs& args);

struct ConvertArgs {
  std::string input, output, crop;
  std::string input_policy = "clamp";
  bool float_exr = false, half_exr = false, raw = false;   // EXR pixel type: the input's unless one is forced
};
int run_convert(const ConvertArgs& args);

struct BenchArgs {
  std::string what;                                // "solvers", "formats" or "sweep"
  std::string data_root, problems = "bc1.four_color,bc4.eight_value,munkberg.kite_linear", solvers;
  std::string images;                              // comma-separated, relative to the data root ("" = all)
  std::vector<std::string> settings;               // "solver.key=value"
  int blocks = 100;
  std::uint64_t seed = 1;
  long long certify_boxes = 2000000;
  int threads = 0;
  // bench formats (experiments/format_bench.h)
  std::string formats, presets = "fast,medium,thorough", csv, reference = "astcenc-4x4-medium";
  int repeat = 1;
  bool no_peers = false, quiet = false;
  // bench sweep (cli/command_bench_sweep.cpp)
  std::string config = "configs/cluster/sweep_bench.yaml";
  int ranks = 2;
  std::size_t synthetic_cells = 100000;
};
int run_bench(const BenchArgs& args);
int run_bench_sweep(const BenchArgs& args);

struct ReportArgs {
  std::vector<std::string> run_dirs;
  std::string out_dir, papers_dir, readme_tables;
  int thumbnail_size = 128, thumbnail_images = 8;
  bool quiet = false;
};
int run_report(const ReportArgs& args);

struct TrainArgs {
  std::string what;                    // "munkberg-dct"
  std::string data_root, output;
  std::string held_out = "default";    // comma-separated relative paths, or "default" (the paper tables' images)
  bool quiet = false;
};
int run_train(const TrainArgs& args);

struct AnalyzeArgs { std::string config, out_dir, data_root; int threads = 0; };
int run_analyze(const AnalyzeArgs& args);

// "a,b,,c" -> {"a", "b", "c"} (empty items dropped).
std::vector<std::string> split_commas(const std::string& text);

// "key=value" -> (key, value); throws Error naming the malformed argument.
std::pair<std::string, std::string> split_setting(const std::string& setting, const std::string& flag);

}  // namespace blocklab::cli
