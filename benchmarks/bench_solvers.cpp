// Speed goals of the solver library (docs/solver-bench.md), measured on 4x4 blocks of real HDR images:
//   * procrustes: blocks per second on one core (goal >= 100,000) and mean error relative to the certified optimum
//     (goal within 5%), with its default options, with refined_candidates=0 (no clamp-aware refinement), with
//     svd=eigen (and the number of blocks where it ends on another lattice point than the closed form), and for
//     the chain procrustes + lattice_polish timed as one solver (Munkberg 2008 sec. 7.1: "search in a small radius
//     of quantized values around each base point");
//   * interval_bb: milliseconds per block to certify the 4-parameter shape fit at 8 bits per coordinate, started
//     from the procrustes + lattice_polish answer (goal < 20 ms on average), on CERTIFIED_BLOCKS blocks spread
//     evenly over each set.
// The blocks are posed as the `munkberg` format's registered block problems munkberg.kite_linear and
// munkberg.kite_stretched (formats/munkberg/munkberg_problems.cpp), the ones `blocklab bench solvers` benchmarks: the
// chroma (u, v) of Munkberg 2008 eq. 2 of each texel, weight 0 for black texels, the "kite" template.
// Times are thread CPU times (one core); each rate is the median of three 1-second windows. Prints one markdown
// table row per image and error kind; asserts nothing.
// Usage: bench_solvers [DATA_ROOT] [BLOCKS_PER_IMAGE] [CERTIFIED_BLOCKS] [PROCRUSTES_OPTIONS]
//   PROCRUSTES_OPTIONS (optional, e.g. "refined_candidates=4,evaluated_candidates=4"): one more pair of columns, the
//   blocks/s and error ratio of procrustes with these options (the rest at their defaults).
#include <algorithm>
#include <ctime>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <string>
#include <vector>

#include "benchmarks/bench_args.h"
#include "core/image_io.h"
#include "core/input_policy.h"
#include "formats/munkberg/shape_fit/shape_fit_problem.h"
#include "formats/common/block_solver.h"
#include "formats/registry.h"
#include "solvers/interval_bb/interval_bb_solver.h"
#include "solvers/lattice_polish/lattice_polish_solver.h"
#include "solvers/procrustes/procrustes_solver.h"

namespace {

using namespace blocklab;

// CPU time of this thread: the machine is shared (other builds), and the goals are per core, so time spent
// descheduled must not count. clock_gettime(CLOCK_THREAD_CPUTIME_ID) is POSIX.
struct CpuClock {
  using time_point = double;
  static double now() {
    timespec t{};
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
    return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
  }
};

double seconds_since(double t) { return CpuClock::now() - t; }

// `count` blocks spread evenly over the image (row-major block order), each posed as the registered block problem
// `problem_name` (munkberg.kite_linear / munkberg.kite_stretched, formats/munkberg/munkberg_problems.cpp: the
// problem `blocklab bench solvers` benchmarks).
std::vector<std::unique_ptr<Problem>> image_problems(const std::string& path, int count, const std::string& problem_name) {
  const RegisteredBlockProblem entry = find_block_problem(problem_name);
  Image image = read_image(path);
  apply_input_policy(image, InputPolicy::clamp, path);
  const long long bx = image.width / 4, by = image.height / 4;
  std::vector<std::unique_ptr<Problem>> problems;
  for (int b = 0; b < count; ++b) {
    const long long index = static_cast<long long>(b) * bx * by / count;
    const int x0 = static_cast<int>(index % bx) * 4, y0 = static_cast<int>(index / bx) * 4;
    BlockTexels texels;
    for (int t = 0; t < kBlockTexels; ++t)
      for (int c = 0; c < 4; ++c) texels.rgba[t][c] = image.texel(x0 + t % 4, y0 + t / 4)[c];
    problems.push_back(entry.problem.make(texels, 0));
  }
  return problems;
}

// Throughput of `solve` over all problems on one core: the median of three windows, each repeated until about 1 s
// of CPU time has passed (on the shared VMs we run on, one window can be 20 % off the next with nothing changed).
template <typename Solve>
double blocks_per_second(std::size_t n, Solve solve) {
  double rates[3];
  for (double& rate : rates) {
    std::size_t solved = 0;
    const double t0 = CpuClock::now();
    do {
      for (std::size_t i = 0; i < n; ++i) solve(i);
      solved += n;
    } while (seconds_since(t0) < 1.0);
    rate = static_cast<double>(solved) / seconds_since(t0);
  }
  std::sort(rates, rates + 3);
  return rates[1];
}

void report(const std::string& name, const std::vector<std::unique_ptr<Problem>>& problems, int certified_blocks,
            const ProcrustesOptions* custom) {
  const std::size_t n = problems.size();
  const ProcrustesOptions procrustes;   // defaults: closed form, 16 refined candidates
  ProcrustesOptions unrefined = procrustes;
  unrefined.refined_candidates = 0;
  ProcrustesOptions eigen = procrustes;
  eigen.svd = ProcrustesMethod::eigen_svd;
  const LatticePolishOptions polish;

  std::vector<SolveResult> fits(n), fast_fits(n), eigen_fits(n), polished(n), custom_fits(n);
  const double custom_rate = custom == nullptr ? 0.0 : blocks_per_second(n, [&](std::size_t i) {
    custom_fits[i] = solve_procrustes(*problems[i], *custom, nullptr, 0);
  });
  const double procrustes_rate = blocks_per_second(
      n, [&](std::size_t i) { fits[i] = solve_procrustes(*problems[i], procrustes, nullptr, 0); });
  const double fast_rate = blocks_per_second(
      n, [&](std::size_t i) { fast_fits[i] = solve_procrustes(*problems[i], unrefined, nullptr, 0); });
  const double eigen_rate = blocks_per_second(
      n, [&](std::size_t i) { eigen_fits[i] = solve_procrustes(*problems[i], eigen, nullptr, 0); });
  std::size_t disagreements = 0;   // blocks where the two fit methods end on a different lattice point
  for (std::size_t i = 0; i < n; ++i)
    if (fits[i].lattice_indices != eigen_fits[i].lattice_indices) ++disagreements;
  // The chain procrustes + lattice_polish, timed as one solver.
  const double chain_rate = blocks_per_second(n, [&](std::size_t i) {
    const SolveResult fit = solve_procrustes(*problems[i], procrustes, nullptr, 0);
    polished[i] = solve_lattice_polish(*problems[i], polish, fit.parameters.data(), 0);
  });

  // Certification of `certified_blocks` blocks spread evenly over the set, started from the chain's answer.
  const std::size_t m = std::min<std::size_t>(n, static_cast<std::size_t>(certified_blocks));
  double fit_sum = 0, fast_sum = 0, custom_sum = 0, polish_sum = 0, optimum_sum = 0, bb_seconds = 0, worst = 0, boxes = 0, points = 0;
  std::size_t optimal = 0;
  for (std::size_t c = 0; c < m; ++c) {
    const std::size_t i = c * n / m;
    const double t = CpuClock::now();
    const SolveResult bb = solve_interval_bb(*problems[i], IntervalBbOptions{}, polished[i].parameters.data(), 0);
    const double s = seconds_since(t);
    bb_seconds += s;
    worst = std::max(worst, s);
    boxes += static_cast<double>(bb.summary.interval_evaluations);
    points += static_cast<double>(bb.summary.evaluations);
    if (bb.summary.termination == Termination::optimal) ++optimal;
    fit_sum += fits[i].summary.final_error;
    fast_sum += fast_fits[i].summary.final_error;
    if (custom != nullptr) custom_sum += custom_fits[i].summary.final_error;
    polish_sum += polished[i].summary.final_error;
    optimum_sum += bb.summary.final_error;
  }
  const double per_block = m > 0 ? 1.0 / static_cast<double>(m) : 0.0;
  // One markdown table row (header printed by main).
  std::printf("| %s | %.0f | %.4f | %.0f | %.4f | %.0f (%zu/%zu differ) | %.0f | %.4f | %.1f (%.0f) | %.0f | %.0f | "
              "%zu/%zu |",
              name.c_str(), procrustes_rate, fit_sum / optimum_sum, fast_rate, fast_sum / optimum_sum, eigen_rate,
              disagreements, n, chain_rate, polish_sum / optimum_sum, 1e3 * bb_seconds * per_block, 1e3 * worst,
              boxes * per_block, points * per_block, optimal, m);
  if (custom != nullptr) std::printf(" %.0f | %.4f |", custom_rate, custom_sum / optimum_sum);
  std::printf("\n");
  std::fflush(stdout);
}

}  // namespace

int main(int argc, char** argv) {
  std::string root = std::string(BLOCKLAB_SOURCE_DIR) + "/../shared/data", custom_text;
  int per_image = 2000, certified = 20;
  bench::CommandLine command_line(
      "bench_solvers", "[DATA_ROOT] [BLOCKS_PER_IMAGE] [CERTIFIED_BLOCKS] [PROCRUSTES_OPTIONS]",
      "Speed goals of the solver library (docs/solver-bench.md) on 4x4 blocks of real HDR images: procrustes "
      "blocks/s and error ratio, interval_bb ms per certified shape fit.");
  command_line.app().add_option("DATA_ROOT", root, "data root (images in DATA_ROOT/hdr)")->capture_default_str();
  command_line.add_integer("BLOCKS_PER_IMAGE", per_image, 1, 10000000, "blocks per image");
  command_line.add_integer("CERTIFIED_BLOCKS", certified, 0, 1000000, "blocks certified by interval_bb per set");
  CLI::Option* custom_option = command_line.app().add_option(
      "PROCRUSTES_OPTIONS", custom_text,
      "one more pair of columns: procrustes with these options (e.g. \"refined_candidates=4,evaluated_candidates=4\")");
  if (const auto status = command_line.parse(argc, argv)) return *status;
  try {
    ProcrustesOptions custom_options;
    const bool has_custom = custom_option->count() > 0;
    if (has_custom)
      custom_options = ProcrustesOptions::from_resolved(resolve_solver_options(
          procrustes_solver(), parse_solver_option_list(custom_text, "PROCRUSTES_OPTIONS", "bench_solvers")));
    std::printf("| image, error | procrustes blocks/s | / optimum | refined_candidates=0 blocks/s | / optimum | "
                "svd=eigen blocks/s | + lattice_polish blocks/s | / optimum | interval_bb ms/block (worst) | "
                "boxes/block | points/block | certified |%s\n|---|---|---|---|---|---|---|---|---|---|---|---|%s\n",
                has_custom ? (" " + custom_text + " blocks/s | / optimum |").c_str() : "",
                has_custom ? "---|---|" : "");
    for (const ShapeErrorKind kind : {ShapeErrorKind::linear, ShapeErrorKind::stretched})
      for (const char* file : {"Desk.exr", "memorial.hdr"})
        report(std::string(file) + " " + to_string(kind),
               image_problems(root + "/hdr/" + file, per_image,
                              kind == ShapeErrorKind::linear ? "munkberg.kite_linear" : "munkberg.kite_stretched"),
               certified, has_custom ? &custom_options : nullptr);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "bench_solvers: %s\n", e.what());
    return 1;
  }
  return 0;
}
