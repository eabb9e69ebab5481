// `blocklab bench solvers`: every solver of the library on the block problems of real images (issue 4, "blocklab
// bench prints, for each solver on BC1 endpoints, BC4 endpoints and the shape fit over the blocks of real images:
// mean error, the certified optimum's mean error where interval_bb can finish, the share of blocks where the solver
// found the optimum, blocks per second"). docs/solver-bench.md holds a measured table and the command.
//
// Problems (one per sampled 4x4 block):
//   bc1             BC1 colour endpoints, four-colour mode (formats/common/s3tc_endpoint_problem.h), texels = the RGB
//                   code values in [0, 1] of an LDR image (<data root>/ldr, every PNG below it);
//   bc4             BC4 endpoints, eight-value mode, texels = the red channel of an LDR image;
//   shape           the 2D chroma shape fit of Munkberg et al. 2008 section 7.1 (eq. 11, linear error) on an HDR
//                   image (<data root>/hdr): points = the chroma (u, v) of eq. 2 (core/color_spaces.h rgb_to_logyuv,
//                   clamped to [0, 1]) of the block's texels, weight 0 for black texels (no chroma) and 1 otherwise,
//                   as the munkberg encoder builds them; an 8-bit lattice per base coordinate; the template is the
//                   "kite" (0,0), (1,0), (0.6,0.5), (0.2,-0.4) (a shape with no symmetry, so no correspondence is
//                   free);
//   shape_stretched the same with the stretched error of section 7.2.
//   munkberg_shape_i, munkberg_shape_ii
//                   the `munkberg` format's own shape-fit problems (issue 5 item 7, "the optimality gap of each
//                   heuristic against the certified optimum"): exactly what its encoder hands the solver
//                   (formats/munkberg/munkberg_chroma.h chroma_fit_data with the default settings): the stretched
//                   error (alpha = 0.455), the 7-bit base-colour lattice, one of the 8 template shapes of the
//                   built-in set (drawn per block from the block's stream), per-texel points (shape I) or the
//                   weighted means of the 2x1 pairs (shape II).
// --images a,b restricts the sampling to those files (paths relative to the data root), e.g. one image at a time
// for per-image rows.
// Blocks: image i and block (x, y) are drawn from a SplitMix64 stream seeded with derive_stream_seed(seed, problem
// number) (solvers/seeding.h), so a (seed, data root) pair always benchmarks the same blocks.
//
// Solvers: registry names, or chains "a+b" where each solver starts from the previous one's answer (the Munkberg
// recipe procrustes+lattice_polish). Each block's solve gets seed derive_stream_seed(seed, block). Options:
// --set solver.key=value. A solver's answer is snapped to the storage lattice (nearest point) when it is
// continuous (nlopt, coeff_search on continuous parameters): stored parameters are lattice points.
// A solver that cannot take a problem (procrustes without a point set, ceres_lm without residuals, exhaustive on a
// lattice too large) is listed with the reason instead of numbers.
//
// Certified optimum per block: `exhaustive` when the lattice has at most 2^16 points (BC4), otherwise interval_bb
// started from the best answer any benchmarked solver found (a start only seeds the incumbent; the certificate is
// interval_bb's), with a box budget (--certify-boxes); blocks where the budget runs out are not certified and only
// count in "mean error". "optimum found" = error <= optimum * (1 + 1e-9) + 1e-18 (the absolute floor only matters
// for an optimum of 0, where rounding leaves ~1e-33).
// blocks/s = blocks / the sum of the solver's own solve times (per core; blocks run in parallel with --threads,
// each solve timed on its own thread, so the figure does not grow with the thread count).
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "cli/commands.h"
#include "core/color_spaces.h"
#include "core/error.h"
#include "core/image_io.h"
#include "core/input_policy.h"
#include "core/parallel.h"
#include "formats/munkberg/shape_fit/shape_fit_problem.h"
#include "formats/common/s3tc_endpoint_problem.h"
#include "formats/munkberg/munkberg_encoder.h"
#include "formats/munkberg/munkberg_shapes.h"
#include "solvers/exhaustive/exhaustive_solver.h"
#include "solvers/interval_bb/interval_bb_solver.h"
#include "solvers/registry.h"
#include "solvers/seeding.h"

namespace blocklab::cli {

namespace {

constexpr const char* kWhere = "bench solvers";
constexpr double kOptimumRelative = 1e-9;
constexpr double kOptimumAbsolute = 1e-18;
// Lattices up to this many points are certified by exhaustive enumeration instead of interval_bb.
constexpr std::uint64_t kExhaustiveLimit = std::uint64_t{1} << 16;

const std::vector<std::string> kProblemNames = {"bc1", "bc4", "shape", "shape_stretched", "munkberg_shape_i",
                                                "munkberg_shape_ii"};

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

bool is_image_file(const std::filesystem::path& path) {
  std::string ext = path.extension().string();
  for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return ext == ".png" || ext == ".exr" || ext == ".hdr" || ext == ".pfm";
}

// Every image file below `folder`, sorted by path (the order the seeded sampling indexes).
std::vector<std::string> image_files(const std::string& folder) {
  std::error_code error;
  if (!std::filesystem::is_directory(folder, error)) fail(folder, "not a folder (check --data-root)");
  std::vector<std::string> files;
  for (const auto& entry : std::filesystem::recursive_directory_iterator(folder))
    if (entry.is_regular_file() && is_image_file(entry.path())) files.push_back(entry.path().string());
  std::sort(files.begin(), files.end());
  if (files.empty()) fail(folder, "holds no image (.png .exr .hdr .pfm)");
  return files;
}

// A 4x4 block of RGB texels (after the clamp input policy: finite, >= 0).
struct BlockTexels {
  std::string source;   // "file (x, y)"
  float rgb[16][3];
};

// Draws `count` blocks from the images of `folder`: image uniformly, then a whole 4x4 block uniformly. Images are
// loaded on first use and kept (the data sets are small).
std::vector<BlockTexels> sample_blocks(const std::vector<std::string>& files, int count, std::uint64_t stream_seed) {
  std::map<std::size_t, Image> loaded;
  RandomStream random(stream_seed);
  std::vector<BlockTexels> blocks;
  for (int b = 0; b < count; ++b) {
    const std::size_t which = static_cast<std::size_t>(random.uniform_index(files.size()));
    auto found = loaded.find(which);
    if (found == loaded.end()) {
      Image image = read_image(files[which]);
      apply_input_policy(image, InputPolicy::clamp, files[which]);
      found = loaded.emplace(which, std::move(image)).first;
    }
    const Image& image = found->second;
    const int blocks_x = image.width / 4, blocks_y = image.height / 4;
    // Images smaller than one block cannot give a whole block.
    if (blocks_x == 0 || blocks_y == 0) fail(files[which], "is smaller than one 4x4 block");
    const int bx = static_cast<int>(random.uniform_index(static_cast<std::uint64_t>(blocks_x)));
    const int by = static_cast<int>(random.uniform_index(static_cast<std::uint64_t>(blocks_y)));
    BlockTexels block;
    block.source = files[which] + " (" + std::to_string(4 * bx) + ", " + std::to_string(4 * by) + ")";
    for (int t = 0; t < 16; ++t) {
      const float* texel = image.texel(4 * bx + t % 4, 4 * by + t / 4);
      for (int c = 0; c < 3; ++c) block.rgb[t][c] = texel[c];
    }
    blocks.push_back(block);
  }
  return blocks;
}

ShapeTemplate kite_template() {
  return ShapeTemplate::from_landmarks({Point2{0, 0}, Point2{1, 0}, Point2{0.6, 0.5}, Point2{0.2, -0.4}});
}

// The munkberg encoder's shape-fit problem of `block` for `mode` and template `shape_index` (default settings).
std::unique_ptr<Problem> make_munkberg_problem(munkberg::Mode mode, const BlockTexels& block, int shape_index) {
  ::blocklab::BlockTexels texels;
  for (int t = 0; t < 16; ++t)
    for (int c = 0; c < 3; ++c) texels.rgba[t][c] = block.rgb[t][c];
  double log_luminance[munkberg::kTexels];
  munkberg::ChromaPoints points;
  munkberg::block_targets(texels, log_luminance, &points);
  const munkberg::ChromaSettings settings;   // the format's defaults: stretched error, alpha 0.455
  const ShapeTemplate& shape = munkberg::default_shape_set().shapes[static_cast<std::size_t>(shape_index)];
  return std::make_unique<ShapeFitProblem>(munkberg::chroma_fit_data(points, mode, shape, settings, nullptr));
}

std::unique_ptr<Problem> make_block_problem(const std::string& kind, const BlockTexels& block, int shape_index) {
  if (kind == "munkberg_shape_i") return make_munkberg_problem(munkberg::Mode::shape_i, block, shape_index);
  if (kind == "munkberg_shape_ii") return make_munkberg_problem(munkberg::Mode::shape_ii, block, shape_index);
  if (kind == "bc1") {
    Bc1EndpointError error;
    for (int t = 0; t < 16; ++t)
      for (int c = 0; c < 3; ++c)   // PNG code values are in [0, 1]; the clamp only guards other inputs
        error.targets[static_cast<std::size_t>(t)][static_cast<std::size_t>(c)] =
            std::min(1.0, static_cast<double>(block.rgb[t][c]));
    return std::make_unique<ErrorProblem<Bc1EndpointError>>(make_bc1_endpoint_problem(error));
  }
  if (kind == "bc4") {
    Bc4EndpointError error;
    for (int t = 0; t < 16; ++t)
      error.targets[static_cast<std::size_t>(t)] = std::min(1.0, static_cast<double>(block.rgb[t][0]));
    return std::make_unique<ErrorProblem<Bc4EndpointError>>(make_bc4_endpoint_problem(error));
  }
  ShapeFitData data;
  data.shape = kite_template();
  data.error_kind = kind == "shape" ? ShapeErrorKind::linear : ShapeErrorKind::stretched;
  for (int t = 0; t < 16; ++t) {
    const Rgb<double> rgb{block.rgb[t][0], block.rgb[t][1], block.rgb[t][2]};
    const LogYuv<double> yuv = rgb_to_logyuv(rgb);
    // u, v are in [0, 1] for non-negative RGB; the clamp removes rounding overshoot.
    data.points.push_back({std::min(1.0, std::max(0.0, yuv.u)), std::min(1.0, std::max(0.0, yuv.v))});
    // A black texel has no chroma (eq. 2 would divide 0 by 0): weight 0, as the munkberg encoder does.
    data.weights.push_back(rgb.r == 0.0 && rgb.g == 0.0 && rgb.b == 0.0 ? 0.0 : 1.0);
  }
  return std::make_unique<ShapeFitProblem>(std::move(data));
}

// The error of `result` on the lattice: its lattice indices, or its parameters snapped to the nearest point.
double lattice_error(const Problem& problem, const SolveResult& result, std::vector<double>& snapped) {
  const int dim = problem.dim();
  snapped.assign(static_cast<std::size_t>(dim), 0.0);
  for (int p = 0; p < dim; ++p) {
    const std::size_t pp = static_cast<std::size_t>(p);
    const Lattice& lattice = problem.lattice(p);
    snapped[pp] = result.lattice_indices.size() == static_cast<std::size_t>(dim)
                      ? lattice.point(result.lattice_indices[pp])
                      : lattice.point(lattice.nearest_index(result.parameters[pp]));
  }
  return problem.eval(snapped.data());
}

struct SolverRow {
  std::string name;                       // "a" or "a+b"
  std::vector<const Solver*> chain;
  std::vector<SolverOptions> options;     // per chain element, resolved
  std::string unavailable;                // reason when the solver failed on this problem
  std::vector<double> error;              // per block, on the lattice
  std::vector<std::vector<double>> answer;
  std::vector<double> seconds;            // per block
};

struct CertifiedOptimum {
  bool certified = false;
  double error = 0.0;
  double seconds = 0.0;
  std::uint64_t boxes = 0;
};

std::string number(double value, const char* format = "%.6g") {
  char buffer[48];
  std::snprintf(buffer, sizeof buffer, format, value);
  return buffer;
}

}  // namespace

int run_bench(const BenchArgs& args) {
  if (args.what != "solvers") fail("bench", "unknown benchmark '" + args.what + "'; valid: solvers");
  if (args.blocks < 1) fail("--blocks", "must be >= 1, got " + std::to_string(args.blocks));
  const std::vector<std::string> problems = split_list(args.problems, "--problems");
  for (const std::string& kind : problems)
    if (std::find(kProblemNames.begin(), kProblemNames.end(), kind) == kProblemNames.end())
      fail("--problems", "unknown problem '" + kind + "'; valid problems: " + join_names(kProblemNames));

  // Data root: --data-root, else BLOCKLAB_DATA_ROOT, else the bundled samples (the same relative names).
  std::string root = args.data_root;
  if (root.empty()) {
    const char* env = std::getenv("BLOCKLAB_DATA_ROOT");
    root = env != nullptr && *env != '\0' ? env : std::string(BLOCKLAB_SOURCE_DIR) + "/samples";
  }

  // Solver rows and their options (--set solver.key=value applies to that solver wherever it appears).
  std::vector<std::string> solver_names;
  if (args.solvers.empty()) {
    for (const Solver* solver : all_solvers()) solver_names.push_back(solver->name());
    solver_names.push_back("procrustes+lattice_polish");
  } else {
    solver_names = split_list(args.solvers, "--solvers");
  }
  std::map<std::string, SolverOptions> given;
  for (const std::string& setting : args.settings) {
    const auto [key, value] = split_setting(setting, "--set");
    const auto dot = key.find('.');
    if (dot == std::string::npos || dot == 0 || dot + 1 == key.size())
      fail("--set", "expected solver.key=value, got '" + setting + "'");
    const std::string solver = key.substr(0, dot);
    find_solver(solver);   // throws on an unknown solver name
    given[solver][key.substr(dot + 1)] = value;
  }
  // interval_bb as a benchmarked solver gets the certification budget unless told otherwise (its default, 2^30
  // boxes, can take hours on a 6-parameter BC1 block).
  if (given["interval_bb"].count("max_boxes") == 0)
    given["interval_bb"]["max_boxes"] = std::to_string(args.certify_boxes);
  std::vector<SolverRow> prototype;
  for (const std::string& name : solver_names) {
    SolverRow row;
    row.name = name;
    std::size_t begin = 0;
    while (begin <= name.size()) {
      std::size_t end = name.find('+', begin);
      if (end == std::string::npos) end = name.size();
      const Solver& solver = find_solver(name.substr(begin, end - begin));
      row.chain.push_back(&solver);
      // Resolved once here (errors before any work), again (idempotently) by solve().
      row.options.push_back(resolve_solver_options(solver, given[solver.name()]));
      begin = end + 1;
    }
    prototype.push_back(row);
  }

  std::printf("blocklab bench solvers: data root %s, %d blocks per problem, seed %llu, interval_bb budget %lld boxes\n",
              root.c_str(), args.blocks, static_cast<unsigned long long>(args.seed),
              static_cast<long long>(args.certify_boxes));
  std::printf("| problem | solver | mean error | certified optimum (mean) | solver on certified blocks | ratio | "
              "optimum found | blocks/s |\n|---|---|---|---|---|---|---|---|\n");
  for (std::size_t k = 0; k < problems.size(); ++k) {
    const std::string& kind = problems[k];
    const std::size_t problem_number = static_cast<std::size_t>(
        std::find(kProblemNames.begin(), kProblemNames.end(), kind) - kProblemNames.begin());
    const bool hdr = kind.find("shape") != std::string::npos;
    std::vector<std::string> files;
    if (args.images.empty()) {
      files = image_files(root + (hdr ? "/hdr" : "/ldr"));
    } else {
      for (const std::string& image : split_list(args.images, "--images")) files.push_back(root + "/" + image);
    }
    const std::vector<BlockTexels> blocks =
        sample_blocks(files, args.blocks, derive_stream_seed(args.seed, problem_number));
    std::vector<std::unique_ptr<Problem>> block_problems;
    for (std::size_t b = 0; b < blocks.size(); ++b) {
      // The template of a munkberg problem: from the block's own stream, so it does not depend on the solvers.
      const int shape_index = static_cast<int>(
          RandomStream(derive_stream_seed(derive_stream_seed(args.seed, problem_number), b)).uniform_index(munkberg::kShapeCount));
      block_problems.push_back(make_block_problem(kind, blocks[b], shape_index));
    }
    const std::size_t n = block_problems.size();

    std::vector<SolverRow> rows = prototype;
    for (SolverRow& row : rows) {
      row.error.assign(n, 0.0);
      row.answer.assign(n, {});
      row.seconds.assign(n, 0.0);
      std::vector<std::string> failures(n);
      parallel_for_index(n, args.threads, [&](std::size_t b) {
        const Problem& problem = *block_problems[b];
        const std::uint64_t seed = derive_stream_seed(args.seed, b);
        try {
          SolveResult result;
          const double* start = nullptr;
          const auto started = std::chrono::steady_clock::now();
          for (std::size_t c = 0; c < row.chain.size(); ++c) {
            result = row.chain[c]->solve(problem, row.options[c], start, seed);
            start = result.parameters.data();   // the next solver of the chain starts here
          }
          row.seconds[b] = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
          row.error[b] = lattice_error(problem, result, row.answer[b]);
        } catch (const Error& e) {
          failures[b] = e.what();
        }
      });
      for (const std::string& failure : failures)
        if (!failure.empty()) {
          row.unavailable = failure;
          break;
        }
    }

    // Certification, started from the best answer of any solver.
    std::vector<CertifiedOptimum> optimum(n);
    parallel_for_index(n, args.threads, [&](std::size_t b) {
      const Problem& problem = *block_problems[b];
      const std::vector<double>* best = nullptr;
      double best_error = 0.0;
      for (const SolverRow& row : rows)
        if (row.unavailable.empty() && !std::isnan(row.error[b]) && (best == nullptr || row.error[b] < best_error)) {
          best = &row.answer[b];
          best_error = row.error[b];
        }
      const auto started = std::chrono::steady_clock::now();
      SolveResult result;
      if (problem.lattice_point_count() <= kExhaustiveLimit) {
        result = solve_exhaustive(problem, ExhaustiveOptions{}, nullptr, 0);
      } else {
        IntervalBbOptions options;
        options.max_boxes = args.certify_boxes;
        result = solve_interval_bb(problem, options, best != nullptr ? best->data() : nullptr, 0);
      }
      optimum[b].seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
      optimum[b].certified = result.summary.termination == Termination::optimal;
      optimum[b].error = result.summary.final_error;
      optimum[b].boxes = result.summary.interval_evaluations;
    });
    std::size_t certified = 0;
    double certified_sum = 0.0, certify_seconds = 0.0;
    for (const CertifiedOptimum& o : optimum) {
      certify_seconds += o.seconds;
      if (!o.certified) continue;
      ++certified;
      certified_sum += o.error;
    }

    for (const SolverRow& row : rows) {
      if (!row.unavailable.empty()) {
        std::printf("| %s | %s | n/a: %s | | | | | |\n", kind.c_str(), row.name.c_str(), row.unavailable.c_str());
        continue;
      }
      double sum = 0.0, on_certified = 0.0, seconds = 0.0;
      std::size_t found = 0;
      for (std::size_t b = 0; b < n; ++b) {
        sum += row.error[b];
        seconds += row.seconds[b];
        if (!optimum[b].certified) continue;
        on_certified += row.error[b];
        const double opt = optimum[b].error;
        if (row.error[b] <= opt + kOptimumRelative * std::abs(opt) + kOptimumAbsolute) ++found;
      }
      const double mean_certified = certified > 0 ? certified_sum / certified : std::nan("");
      const double mean_on_certified = certified > 0 ? on_certified / certified : std::nan("");
      std::printf("| %s | %s | %s | %s (%zu/%zu blocks) | %s | %s | %s | %s |\n", kind.c_str(), row.name.c_str(),
                  number(sum / n).c_str(), number(mean_certified).c_str(), certified, n,
                  number(mean_on_certified).c_str(), number(mean_on_certified / mean_certified, "%.4f").c_str(),
                  certified > 0 ? (number(100.0 * found / certified, "%.1f") + "%").c_str() : "n/a",
                  number(seconds > 0.0 ? n / seconds : 0.0, "%.0f").c_str());
    }
    std::printf("| %s | (certification: %s) | | %s (%zu/%zu blocks) | | | | %s |\n", kind.c_str(),
                block_problems.front()->lattice_point_count() <= kExhaustiveLimit ? "exhaustive"
                                                                                  : "interval_bb from the best answer",
                number(certified > 0 ? certified_sum / certified : std::nan("")).c_str(), certified, n,
                number(certify_seconds > 0.0 ? n / certify_seconds : 0.0, "%.1f").c_str());
    std::fflush(stdout);
  }
  return 0;
}

}  // namespace blocklab::cli
