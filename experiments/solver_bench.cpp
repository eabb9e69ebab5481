// `blocklab bench solvers` (experiments/solver_bench.h): every solver of the library on the block problems of real
// images, per problem and solver: mean error, the certified optimum's mean error where interval_bb can finish, the
// share of blocks where the solver found the optimum, blocks per second.
//
// Problems: the registered formats' block-problem tables (Format::block_problems()), named "<format>.<problem>";
// `blocklab list --json` and the error for an unknown name list them. One Problem per sampled 4x4 block of the
// problem's image kind (<data root>/ldr or <data root>/hdr, or the images given). Blocks: image and block (x, y)
// drawn from a SplitMix64 stream seeded with block_problem_stream_seed(seed, name) (experiments/block_samples.h), so
// a (seed, data root) pair always benchmarks the same blocks, whatever else the tables hold.
//
// Solvers: registry names, or chains "a+b" where each solver starts from the previous one's answer (the Munkberg
// recipe procrustes+lattice_polish). Each block's solve gets seed derive_stream_seed(seed, block). A solver's answer
// is snapped to the storage lattice (nearest point) on every parameter that has one: stored parameters are lattice
// points. A solver that cannot take a problem (procrustes without a point set, ceres_lm without residuals,
// exhaustive or interval_bb without a full lattice) is listed with the reason instead of numbers.
//
// Certified optimum per block: `exhaustive` when the lattice has at most 2^16 points (BC4), otherwise interval_bb
// started from the best answer any benchmarked solver found (a start only seeds the incumbent; the certificate is
// interval_bb's), with a box budget (certify_boxes); blocks where the budget runs out are not certified and only
// count in "mean error". Problems with continuous parameters (no full lattice) are not certified. "optimum found" =
// error <= optimum * (1 + 1e-9) + 1e-18 (the absolute floor only matters for an optimum of 0, where rounding leaves
// ~1e-33).
// blocks/s = blocks / the sum of the solver's own solve times (per core; blocks run in parallel with `threads`,
// each solve timed on its own thread, so the figure does not grow with the thread count).
#include "experiments/solver_bench.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <memory>

#include "core/error.h"
#include "core/parallel.h"
#include "experiments/block_samples.h"
#include "formats/registry.h"
#include "solvers/exhaustive/exhaustive_solver.h"
#include "solvers/interval_bb/interval_bb_solver.h"
#include "solvers/registry.h"
#include "solvers/seeding.h"

namespace blocklab {

namespace {

constexpr double kOptimumRelative = 1e-9;
constexpr double kOptimumAbsolute = 1e-18;
// Lattices up to this many points are certified by exhaustive enumeration instead of interval_bb.
constexpr std::uint64_t kExhaustiveLimit = std::uint64_t{1} << 16;

// The error of `result`: its lattice indices, or its parameters snapped to the nearest point of each parameter
// that has a lattice (continuous parameters are taken as they are).
double lattice_error(const Problem& problem, const SolveResult& result, std::vector<double>& snapped) {
  const int dim = problem.dim();
  snapped.assign(static_cast<std::size_t>(dim), 0.0);
  const bool indices = result.lattice_indices.size() == static_cast<std::size_t>(dim);
  for (int p = 0; p < dim; ++p) {
    const std::size_t pp = static_cast<std::size_t>(p);
    const Lattice& lattice = problem.lattice(p);
    if (!lattice.present())
      snapped[pp] = result.parameters[pp];
    else
      snapped[pp] = indices ? lattice.point(result.lattice_indices[pp])
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
};

std::string number(double value, const char* format = "%.6g") {
  char buffer[48];
  std::snprintf(buffer, sizeof buffer, format, value);
  return buffer;
}

std::vector<SolverRow> solver_rows(const SolverBenchSettings& settings) {
  std::vector<std::string> names = settings.solvers;
  if (names.empty()) {
    for (const Solver* solver : all_solvers()) names.push_back(solver->name());
    names.push_back("procrustes+lattice_polish");
  }
  std::map<std::string, SolverOptions> given = settings.solver_options;
  for (const auto& entry : given) find_solver(entry.first);   // throws on an unknown solver name
  // interval_bb as a benchmarked solver gets the certification budget unless told otherwise (its default, 2^30
  // boxes, can take hours on a 6-parameter BC1 block).
  if (given["interval_bb"].count("max_boxes") == 0)
    given["interval_bb"]["max_boxes"] = std::to_string(settings.certify_boxes);
  std::vector<SolverRow> rows;
  for (const std::string& name : names) {
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
    rows.push_back(row);
  }
  return rows;
}

// Runs every row's chain on every block (in parallel over blocks, each writing its own slot).
void run_rows(std::vector<SolverRow>& rows, const std::vector<DrawnProblem>& problems,
              const SolverBenchSettings& settings) {
  const std::size_t n = problems.size();
  for (SolverRow& row : rows) {
    row.error.assign(n, 0.0);
    row.answer.assign(n, {});
    row.seconds.assign(n, 0.0);
    std::vector<std::string> failures(n);
    parallel_for_index(n, settings.threads, [&](std::size_t b) {
      const Problem& problem = *problems[b].problem;
      const std::uint64_t seed = derive_stream_seed(settings.seed, b);
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
}

// The certified optimum of every block with a full lattice, started from the best answer of any solver.
std::vector<CertifiedOptimum> certify(const std::vector<SolverRow>& rows, const std::vector<DrawnProblem>& problems,
                                      const SolverBenchSettings& settings) {
  std::vector<CertifiedOptimum> optimum(problems.size());
  parallel_for_index(problems.size(), settings.threads, [&](std::size_t b) {
    const Problem& problem = *problems[b].problem;
    if (!problem.has_full_lattice()) return;   // continuous parameters: nothing to enumerate
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
      options.max_boxes = settings.certify_boxes;
      result = solve_interval_bb(problem, options, best != nullptr ? best->data() : nullptr, 0);
    }
    optimum[b].seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
    optimum[b].certified = result.summary.termination == Termination::optimal;
    optimum[b].error = result.summary.final_error;
  });
  return optimum;
}

void print_problem(const std::string& name, const std::vector<SolverRow>& rows,
                   const std::vector<DrawnProblem>& problems, const std::vector<CertifiedOptimum>& optimum,
                   std::ostream& out) {
  const std::size_t n = problems.size();
  std::size_t certified = 0;
  double certified_sum = 0.0, certify_seconds = 0.0;
  for (const CertifiedOptimum& o : optimum) {
    certify_seconds += o.seconds;
    if (!o.certified) continue;
    ++certified;
    certified_sum += o.error;
  }
  char line[1024];
  for (const SolverRow& row : rows) {
    if (!row.unavailable.empty()) {
      out << "| " << name << " | " << row.name << " | n/a: " << row.unavailable << " | | | | | |\n";
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
    std::snprintf(line, sizeof line, "| %s | %s | %s | %s (%zu/%zu blocks) | %s | %s | %s | %s |\n", name.c_str(),
                  row.name.c_str(), number(sum / n).c_str(), number(mean_certified).c_str(), certified, n,
                  number(mean_on_certified).c_str(), number(mean_on_certified / mean_certified, "%.4f").c_str(),
                  certified > 0 ? (number(100.0 * found / certified, "%.1f") + "%").c_str() : "n/a",
                  number(seconds > 0.0 ? n / seconds : 0.0, "%.0f").c_str());
    out << line;
  }
  const Problem& first = *problems.front().problem;
  const char* method = !first.has_full_lattice()                     ? "none: continuous parameters"
                       : first.lattice_point_count() <= kExhaustiveLimit ? "exhaustive"
                                                                         : "interval_bb from the best answer";
  std::snprintf(line, sizeof line, "| %s | (certification: %s) | | %s (%zu/%zu blocks) | | | | %s |\n", name.c_str(),
                method, number(certified > 0 ? certified_sum / certified : std::nan("")).c_str(), certified, n,
                number(certify_seconds > 0.0 ? n / certify_seconds : 0.0, "%.1f").c_str());
  out << line;
  out.flush();
}

}  // namespace

std::vector<std::string> expand_bench_problem_names(const std::vector<std::string>& entries) {
  const std::vector<RegisteredBlockProblem> known = registered_block_problems();
  std::vector<std::string> names;
  for (const std::string& entry : entries) {
    bool matched = false;
    for (const RegisteredBlockProblem& problem : known)
      if (problem.full_name() == entry || problem.format->name() == entry) {
        names.push_back(problem.full_name());
        matched = true;
      }
    if (!matched) {
      std::string valid;
      for (const RegisteredBlockProblem& problem : known) valid += (valid.empty() ? "" : ", ") + problem.full_name();
      fail("--problems", "unknown problem '" + entry + "'; valid problems: " + valid + " (or a format name for all of "
                         "its problems)");
    }
  }
  return names;
}

void run_solver_bench(const SolverBenchSettings& settings, std::ostream& out) {
  if (settings.blocks < 1) fail("--blocks", "must be >= 1, got " + std::to_string(settings.blocks));
  const std::vector<std::string> names = expand_bench_problem_names(settings.problems);
  const std::vector<SolverRow> prototype = solver_rows(settings);

  char line[512];
  std::snprintf(line, sizeof line,
                "blocklab bench solvers: data root %s, %d blocks per problem, seed %llu, interval_bb budget %lld "
                "boxes\n",
                settings.data_root.c_str(), settings.blocks, static_cast<unsigned long long>(settings.seed),
                static_cast<long long>(settings.certify_boxes));
  out << line
      << "| problem | solver | mean error | certified optimum (mean) | solver on certified blocks | ratio | "
         "optimum found | blocks/s |\n|---|---|---|---|---|---|---|---|\n";
  for (const std::string& name : names) {
    const RegisteredBlockProblem entry = find_block_problem(name);
    std::vector<std::string> files;
    if (settings.images.empty()) {
      files = image_files(block_image_folder(settings.data_root, entry.problem.image_kind));
    } else {
      for (const std::string& image : settings.images) files.push_back(settings.data_root + "/" + image);
    }
    const std::vector<DrawnProblem> problems = draw_block_problems(entry, files, settings.blocks, settings.seed);
    std::vector<SolverRow> rows = prototype;
    run_rows(rows, problems, settings);
    print_problem(name, rows, problems, certify(rows, problems, settings), out);
  }
}

}  // namespace blocklab
