// blocklab: command-line front end. Subcommands: list, encode, decode, compare, run, merge, convert, bench, analyze,
// train, report.
// Results go to stdout, progress and errors to stderr; every failure exits non-zero with a one-line reason.
#include <CLI/CLI.hpp>
#include <tbb/global_control.h>

#include <cstdio>
#include <exception>
#include <memory>

#include "cli/commands.h"
#include "core/error.h"
#include "experiments/analysis.h"

int main(int argc, char** argv) {
  using namespace blocklab::cli;
  CLI::App app{"blocklab: encoder search for fixed-rate block texture compression (HDR first)"};
  app.require_subcommand(1);
  app.set_version_flag("--version", std::string("blocklab ") + BLOCKLAB_VERSION);

  int threads = 0;
  auto add_threads = [&threads](CLI::App* sub) {
    sub->add_option("--threads,-j", threads, "worker threads (0 = all hardware threads)")->check(CLI::NonNegativeNumber);
  };

  ListArgs list_args;
  CLI::App* list = app.add_subcommand("list", "list formats (with modes and options), solvers and metrics");
  list->add_flag("--json", list_args.json, "machine-readable output");
  list->add_flag("--markdown", list_args.markdown, "the README option tables of every format and solver");
  add_threads(list);

  EncodeArgs encode_args;
  CLI::App* encode = app.add_subcommand("encode", "encode an image into a format's packed blocks (.blk container, or .dds: the GPU textures of bc1, bc3, bc4, bc7, bc6h, bc6h_sf, wang)");
  encode->add_option("--format,-f", encode_args.format, "format registry name (see `blocklab list`)")->required();
  encode->add_option("--set,-s", encode_args.settings, "format option key=value (same keys as in YAML)");
  encode->add_option("--input-policy", encode_args.input_policy, "NaN/Inf/negative values: error, clamp or zero");
  encode->add_option("input", encode_args.input, "input image (.exr .hdr .pfm .png)")->required();
  encode->add_option("output", encode_args.output, "output file (.blk; or .dds: OUT.dds for one texture, OUT.<name>.dds for each of several plus OUT.blk)")->required();
  encode->add_option("--mode-map", encode_args.mode_map,
                     "also write the colour-coded per-block mode map (PNG over the image) and print mode shares");
  add_threads(encode);

  DecodeArgs decode_args;
  CLI::App* decode = app.add_subcommand("decode", "decode a packed file back to an image");
  decode->add_option("input", decode_args.input, "packed file (.blk or .dds)")->required();
  decode->add_option("output", decode_args.output, "output image (.exr .hdr .pfm .png)")->required();
  add_threads(decode);

  CompareArgs compare_args;
  CLI::App* compare = app.add_subcommand("compare", "compare a test image against a reference image");
  compare->add_option("reference", compare_args.reference, "reference image")->required();
  compare->add_option("test", compare_args.test, "test image, or a packed texture (.blk, .dds) decoded first")->required();
  compare->add_option("--metrics,-m", compare_args.metrics, "comma-separated metric names (default: all)");
  compare->add_option("--set,-s", compare_args.settings, "metric option metric.key=value, e.g. mpsnr.start=-4");
  compare->add_option("--error-maps", compare_args.error_map_dir, "write one per-pixel error map (EXR) per metric here");
  compare->add_flag("--json", compare_args.json, "print {metric name: value} as JSON");
  compare->add_flag("--details", compare_args.details, "with --json: {metric: {value, details}}");
  add_threads(compare);

  RunArgs run_args;
  CLI::App* run = app.add_subcommand("run", "run an experiment (YAML config) and write a run folder");
  run->add_option("config", run_args.config, "experiment YAML")->required();
  run->add_option("--out,-o", run_args.out_dir, "run folder (default runs/<experiment name>)");
  run->add_option("--data-root", run_args.data_root, "image root (overrides BLOCKLAB_DATA_ROOT and the config)");
  run->add_flag("--fresh", run_args.fresh, "recompute cells even when cached");
  run->add_flag("--quiet,-q", run_args.quiet, "no plan size or progress output");
  run->add_option("--max-cells", run_args.max_cells,
                  "refuse an experiment of more cells (images x format variants x (baseline + ablations)); "
                  "default 100000")
      ->check(CLI::PositiveNumber);
  run->add_option("--shard", run_args.shard,
                  "compute only shard i of n (i/n, 0-based): the cells in key order dealt round-robin; join the "
                  "shards' folders with `blocklab merge` (docs/cluster.md)");
  add_threads(run);

  MergeArgs merge_args;
  CLI::App* merge = app.add_subcommand(
      "merge", "merge the run folders of one experiment (e.g. the shards of run --shard i/n) into one run folder");
  merge->add_option("run_dirs", merge_args.run_dirs, "run folders of the same config")->required();
  merge->add_option("--out,-o", merge_args.out_dir, "merged run folder (may be one of the inputs)")->required();
  add_threads(merge);

  ConvertArgs convert_args;
  CLI::App* convert = app.add_subcommand(
      "convert",
      "convert (and optionally crop) an image between file types. EXR output keeps the input's precision (half-float "
      "EXR stays half; float EXR, PFM, .hdr and PNG become 32-bit float) unless --float or --half; 16-bit PNG stays "
      "16-bit. An alpha channel is kept when the target format has one (EXR, PNG) and dropped otherwise (PFM, .hdr). "
      "A half output warns on stderr about values it turns to infinity or zero");
  convert->add_option("input", convert_args.input, "input image")->required();
  convert->add_option("output", convert_args.output, "output image (.exr .hdr .pfm .png)")->required();
  convert->add_option("--crop", convert_args.crop, "x,y,width,height");
  convert->add_option("--input-policy", convert_args.input_policy, "NaN/Inf/negative values: error, clamp or zero");
  convert->add_flag("--float", convert_args.float_exr, "write 32-bit float EXR whatever the input");
  convert->add_flag("--half", convert_args.half_exr, "write half-float EXR whatever the input (warns about lost values)");
  convert->add_flag("--raw", convert_args.raw, "skip the input policy: keep NaN/Inf/negative values as read");

  BenchArgs bench_args;
  CLI::App* bench = app.add_subcommand("bench", "benchmark the solver library on blocks of real images (solvers), "
                                       "every format at its presets against astcenc, libsquish and NVTT (formats), or "
                                       "MPI sweeps (sweep)");
  bench->add_option("what", bench_args.what, "what to benchmark: solvers, formats or sweep")->required();
  bench->add_option("--data-root", bench_args.data_root,
                    "image root with hdr/ and ldr/ (default: BLOCKLAB_DATA_ROOT, else samples/)");
  bench->add_option("--blocks", bench_args.blocks, "4x4 blocks per problem");
  bench->add_option("--problems", bench_args.problems,
                    "comma-separated block problems <format>.<problem> (e.g. bc4.eight_value, munkberg.shape_i) or "
                    "format names (all of its problems); the formats declare them (blocklab list --json)");
  bench->add_option("--images", bench_args.images,
                    "comma-separated images relative to the data root to sample from (default: every image of "
                    "<root>/ldr or <root>/hdr)");
  bench->add_option("--solvers", bench_args.solvers, "comma-separated solver names or chains a+b (default: all)");
  bench->add_option("--set,-s", bench_args.settings, "solver option solver.key=value");
  bench->add_option("--seed", bench_args.seed, "seed of the block sampling and of the solves");
  bench->add_option("--certify-boxes", bench_args.certify_boxes, "interval_bb box budget of the certification");
  bench->add_option("--formats", bench_args.formats, "formats: comma-separated format and peer names (default: all)");
  bench->add_option("--presets", bench_args.presets, "formats: comma-separated presets (default fast,medium,thorough)");
  bench->add_option("--csv", bench_args.csv, "formats: write the table as CSV here");
  bench->add_option("--reference", bench_args.reference,
                    "formats: the run the speed ratios are taken against (<format>-<preset>, e.g. astcenc-4x4-medium)");
  bench->add_option("--repeat", bench_args.repeat, "formats: rounds per image (times are medians)")
      ->check(CLI::PositiveNumber);
  bench->add_flag("--no-peers", bench_args.no_peers, "formats: run only blocklab's formats");
  bench->add_flag("--quiet,-q", bench_args.quiet, "formats: no progress output");
  bench->add_option("--config", bench_args.config, "sweep: the experiment timed (default configs/cluster/sweep_bench.yaml)");
  bench->add_option("--ranks", bench_args.ranks, "sweep: MPI ranks of the parallel run (each with --threads 1)")
      ->check(CLI::Range(2, 1024));
  bench->add_option("--synthetic-cells", bench_args.synthetic_cells,
                    "sweep: cells of the synthetic run whose merge rank 0's cost per cell is measured on")
      ->check(CLI::Range(1, 10000000));
  add_threads(bench);

  AnalyzeArgs analyze_args;
  CLI::App* analyze = app.add_subcommand(
      "analyze", "run an analysis (YAML config; kinds: " + blocklab::analysis_names() + ") into a folder");
  analyze->add_option("config", analyze_args.config, "analysis YAML")->required();
  analyze->add_option("--out,-o", analyze_args.out_dir, "output folder (default: the config's output, else runs/<name>)");
  analyze->add_option("--data-root", analyze_args.data_root, "image root (overrides BLOCKLAB_DATA_ROOT and the config)");
  add_threads(analyze);

  TrainArgs train_args;
  CLI::App* train = app.add_subcommand("train", "train a format's tables on images (munkberg-dct: the DCT mode's bit allocation and quantisers)");
  train->add_option("what", train_args.what, "what to train: munkberg-dct")->required();
  train->add_option("--data-root", train_args.data_root, "image root with hdr/ (default: BLOCKLAB_DATA_ROOT)");
  train->add_option("--out,-o", train_args.output, "tables YAML to write (the format's: formats/munkberg/dct_tables.yaml)")->required();
  train->add_option("--hold-out", train_args.held_out,
                    "comma-separated images (relative to the root) left out of training; default: the paper tables' "
                    "hdr/Desk.exr, hdr/dani_cathedral_oBBC.hdr, hdr/memorial.hdr");
  train->add_flag("--quiet,-q", train_args.quiet, "no progress output");

  ReportArgs report_args;
  CLI::App* report = app.add_subcommand("report", "a static HTML page and its Markdown twin from run folders: paper tables "
                                        "with published values, error-vs-time plots, thumbnails, provenance");
  report->add_option("runs", report_args.run_dirs, "run folders (written by `blocklab run`)");
  report->add_option("--out,-o", report_args.out_dir, "output folder (index.html, report.md, img/)");
  report->add_option("--papers", report_args.papers_dir, "folder of <paper>/published.yaml (default configs/papers)");
  report->add_option("--readme-tables", report_args.readme_tables,
                     "print the generated README tables of one paper folder (its published.yaml and measured/*.jsonl)");
  report->add_option("--thumbnail-size", report_args.thumbnail_size, "side of the re-encoded thumbnail crop")
      ->check(CLI::Range(16, 1024));
  report->add_option("--thumbnail-images", report_args.thumbnail_images, "images per run that get thumbnails")
      ->check(CLI::NonNegativeNumber);
  report->add_flag("--quiet,-q", report_args.quiet, "no progress output");

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e);
  }

  // --threads bounds every parallel loop of the process (block loops and metric row loops alike).
  std::unique_ptr<tbb::global_control> thread_limit;
  if (threads > 0)
    thread_limit = std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism,
                                                         static_cast<std::size_t>(threads));
  try {
    if (*list) return run_list(list_args);
    if (*encode) { encode_args.threads = threads; return run_encode(encode_args); }
    if (*decode) { decode_args.threads = threads; return run_decode(decode_args); }
    if (*compare) { compare_args.threads = threads; return run_compare(compare_args); }
    if (*run) { run_args.threads = threads; return run_run(run_args); }
    if (*merge) { merge_args.threads = threads; return run_merge(merge_args); }
    if (*convert) return run_convert(convert_args);
    if (*bench) { bench_args.threads = threads; return run_bench(bench_args); }
    if (*analyze) { analyze_args.threads = threads; return run_analyze(analyze_args); }
    if (*train) return run_train(train_args);
    if (*report) return run_report(report_args);
  } catch (const blocklab::Error& e) {
    std::fprintf(stderr, "blocklab: error: %s\n", e.what());
    return 1;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "blocklab: internal error: %s\n", e.what());
    return 2;
  }
  return 1;
}
