// `blocklab bench solvers`: the command line of experiments/solver_bench.h (run_solver_bench), which holds the
// benchmark, its problems (the registered formats' block-problem tables, named "<format>.<problem>") and what each
// column means. docs/solver-bench.md holds a measured table and the command.
// Data root: --data-root, else BLOCKLAB_DATA_ROOT, else the bundled samples (the same relative names). --images a,b
// restricts the sampling to those files (paths relative to the data root), e.g. one image at a time for per-image
// rows. Solver options: --set solver.key=value (applies to that solver wherever it appears in a chain).
// `blocklab bench formats`: the command line of experiments/format_bench.h (run_format_bench): every format at its
// presets against the peer encoders on one core; prints the per-row table summary and the Pareto front (Markdown) on
// stdout, writes the CSV to --csv, and shows progress with an ETA on stderr.
#include <cstdlib>
#include <iostream>
#include <string>
#include <vector>

#include "cli/commands.h"
#include "cli/progress.h"
#include "core/atomic_write.h"
#include "core/error.h"
#include "experiments/format_bench.h"
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

std::string default_data_root(const std::string& given) {
  if (!given.empty()) return given;
  const char* env = std::getenv("BLOCKLAB_DATA_ROOT");
  return env != nullptr && *env != '\0' ? env : std::string(BLOCKLAB_SOURCE_DIR) + "/samples";
}

int run_format_bench_command(const BenchArgs& args) {
  FormatBenchSettings settings;
  settings.data_root = default_data_root(args.data_root);
  if (!args.images.empty()) settings.images = split_list(args.images, "--images");
  if (!args.formats.empty()) settings.formats = split_list(args.formats, "--formats");
  settings.presets = split_list(args.presets, "--presets");
  settings.reference = args.reference;
  settings.repeat = args.repeat;
  settings.peers = !args.no_peers;
  ProgressDisplay display(!args.quiet, "runs");
  std::vector<std::string> warnings;
  const std::vector<FormatBenchRow> rows = run_format_bench(
      settings, [&](std::size_t done, std::size_t total, const std::string& current) {
        display.update(done, total, 0, current);
      }, &warnings);
  display.finish();
  for (const std::string& warning : warnings) std::cerr << "blocklab: bench formats: " << warning << "\n";
  if (!args.csv.empty()) write_file_atomically(args.csv, format_bench_csv(rows));
  std::cout << "One core; " << settings.repeat << " round(s) per image, encoders alternating; speed ratio against "
            << settings.reference << ".\n\n| format | preset | image | bpp | error | encode s | decode s | ratio |\n"
            << "|---|---|---|---|---|---|---|---|\n";
  for (const FormatBenchRow& row : rows) {
    char line[512];
    const bool hdr = row.kind == "hdr";
    std::snprintf(line, sizeof line, "| %s | %s | %s | %.3g | %s %.4g | %.3f | %.3f | %s |\n", row.format.c_str(),
                  row.preset.c_str(), row.image.c_str(), row.bpp, hdr ? "log2[RGB]" : "PSNR",
                  row.metrics.at(hdr ? "log2rgb" : "psnr"), row.encode_seconds, row.decode_seconds,
                  row.speed_ratio ? std::to_string(*row.speed_ratio).substr(0, 6).c_str() : "");
    std::cout << line;
  }
  std::cout << "\nPareto front (error against encode time at each bit rate):\n\n"
            << pareto_markdown(pareto_points(rows));
  return 0;
}

}  // namespace

int run_bench(const BenchArgs& args) {
  if (args.what == "formats") return run_format_bench_command(args);
  if (args.what == "sweep") return run_bench_sweep(args);
  if (args.what != "solvers") fail("bench", "unknown benchmark '" + args.what + "'; valid: solvers, formats, sweep");
  SolverBenchSettings settings;
  settings.problems = split_list(args.problems, "--problems");
  if (!args.solvers.empty()) settings.solvers = split_list(args.solvers, "--solvers");
  if (!args.images.empty()) settings.images = split_list(args.images, "--images");
  settings.data_root = default_data_root(args.data_root);
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
