// Speed and quality report for the shape-fit solvers (not run by default: every test is DISABLED_, run with
// --gtest_also_run_disabled_tests). For each block set (random uniform, random clustered, 4x4 blocks of real
// HDR images' logYuv chroma) and both error kinds it prints:
//   procrustes blocks per second and its mean error relative to the certified optimum;
//   procrustes + lattice_polish mean error ratio;
//   interval_bb certification time per block (started from the polished answer), boxes per block.
// No timing is asserted (preamble rule); correctness is still checked (B&B never worse than its start).
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <random>
#include <string>
#include <vector>

#include "formats/munkberg/munkberg_color_spaces.h"
#include "core/image_io.h"
#include "formats/munkberg/shape_fit/shape_fit_problem.h"
#include "solvers/interval_bb/interval_bb_solver.h"
#include "solvers/lattice_polish/lattice_polish_solver.h"
#include "solvers/procrustes/procrustes_solver.h"

namespace blocklab {
namespace {

ShapeTemplate kite() {
  return ShapeTemplate::from_landmarks({Point2{0, 0}, Point2{1, 0}, Point2{0.6, 0.5}, Point2{0.2, -0.4}});
}

std::vector<std::vector<Point2>> random_blocks(int count, bool clustered, std::uint64_t seed) {
  std::mt19937_64 random(seed);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::vector<std::vector<Point2>> blocks;
  for (int b = 0; b < count; ++b) {
    Point2 centres[4];
    for (Point2& c : centres) c = {0.1 + 0.4 * unit(random), 0.1 + 0.4 * unit(random)};
    std::vector<Point2> points;
    for (int i = 0; i < 16; ++i) {
      Point2 p = clustered ? centres[(i * 7) % 4] : Point2{unit(random), unit(random)};
      if (clustered) {
        p.u = std::min(1.0, std::max(0.0, p.u + 0.03 * (unit(random) - 0.5)));
        p.v = std::min(1.0, std::max(0.0, p.v + 0.03 * (unit(random) - 0.5)));
      }
      points.push_back(p);
    }
    blocks.push_back(points);
  }
  return blocks;
}

// logYuv chroma (Munkberg 2008 eq. 2) of `count` 4x4 blocks spread evenly over an image.
std::vector<std::vector<Point2>> image_blocks(const std::string& file, int count) {
  const Image image = read_image(std::string(BLOCKLAB_TEST_SHARED_DATA) + "/hdr/" + file);
  const int bx = image.width / 4, by = image.height / 4;
  std::vector<std::vector<Point2>> blocks;
  for (int b = 0; b < count; ++b) {
    const long long index = static_cast<long long>(b) * bx * by / count;
    const int x0 = static_cast<int>(index % bx) * 4, y0 = static_cast<int>(index / bx) * 4;
    std::vector<Point2> points;
    for (int y = 0; y < 4; ++y)
      for (int x = 0; x < 4; ++x) {
        const float* t = image.texel(x0 + x, y0 + y);
        const Rgb<double> rgb{std::max(0.0, double(t[0])), std::max(0.0, double(t[1])), std::max(0.0, double(t[2]))};
        const LogYuv<double> yuv = rgb_to_logyuv(rgb);
        points.push_back({std::min(1.0, std::max(0.0, yuv.u)), std::min(1.0, std::max(0.0, yuv.v))});
      }
    blocks.push_back(points);
  }
  return blocks;
}

double seconds_since(std::chrono::steady_clock::time_point t) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count();
}

void report(const char* name, const std::vector<std::vector<Point2>>& blocks, ShapeErrorKind kind, bool certify) {
  std::vector<ShapeFitProblem> problems;
  for (const auto& points : blocks) {
    ShapeFitData data;
    data.points = points;
    data.shape = kite();
    data.error_kind = kind;
    problems.emplace_back(data);
  }
  // Procrustes speed (repeated to get a stable time).
  const int repeats = certify ? 20 : 50;
  std::vector<SolveResult> fits(problems.size());
  auto t = std::chrono::steady_clock::now();
  for (int r = 0; r < repeats; ++r)
    for (std::size_t i = 0; i < problems.size(); ++i)
      fits[i] = solve_procrustes(problems[i], ProcrustesOptions{}, nullptr, 0);
  const double procrustes_rate = repeats * problems.size() / seconds_since(t);
  ProcrustesOptions all;
  all.evaluated_candidates = 0;
  std::vector<SolveResult> fits_all(problems.size()), polished(problems.size());
  for (std::size_t i = 0; i < problems.size(); ++i) {
    fits_all[i] = solve_procrustes(problems[i], all, nullptr, 0);
    polished[i] = solve_lattice_polish(problems[i], LatticePolishOptions{}, fits[i].parameters.data(), 0);
  }
  double sum_fit = 0, sum_fit_all = 0, sum_polish = 0, sum_opt = 0, bb_seconds = 0, boxes = 0, worst_ms = 0;
  int certified = 0;
  for (std::size_t i = 0; i < problems.size(); ++i) {
    sum_fit += fits[i].summary.final_error;
    sum_fit_all += fits_all[i].summary.final_error;
    sum_polish += polished[i].summary.final_error;
    if (!certify) continue;
    t = std::chrono::steady_clock::now();
    const SolveResult bb = solve_interval_bb(problems[i], IntervalBbOptions{}, polished[i].parameters.data(), 0);
    const double s = seconds_since(t);
    bb_seconds += s;
    worst_ms = std::max(worst_ms, 1e3 * s);
    boxes += static_cast<double>(bb.summary.interval_evaluations);
    EXPECT_LE(bb.summary.final_error, polished[i].summary.final_error);
    if (bb.summary.termination == Termination::optimal) ++certified;
    sum_opt += bb.summary.final_error;
  }
  const double n = static_cast<double>(problems.size());
  std::printf("%-28s %-9s procrustes %8.0f blocks/s  mean error: procrustes %.4g (all candidates %.4g), +polish %.4g",
              name, to_string(kind).c_str(), procrustes_rate, sum_fit / n, sum_fit_all / n, sum_polish / n);
  if (certify)
    std::printf(", certified %.4g -> ratios %.3f / %.3f; interval_bb %.2f ms/block (worst %.1f), %.0f boxes/block, %d/%d optimal",
                sum_opt / n, sum_fit / sum_opt, sum_polish / sum_opt, 1e3 * bb_seconds / n, worst_ms, boxes / n,
                certified, static_cast<int>(n));
  std::printf("\n");
}

TEST(ShapeFitSpeed, DISABLED_ReportsRandomBlocks) {
  for (const ShapeErrorKind kind : {ShapeErrorKind::linear, ShapeErrorKind::stretched}) {
    report("random uniform", random_blocks(40, false, 1), kind, true);
    report("random clustered", random_blocks(40, true, 2), kind, true);
  }
}

TEST(ShapeFitSpeed, DISABLED_ReportsRealImageBlocks) {
  for (const ShapeErrorKind kind : {ShapeErrorKind::linear, ShapeErrorKind::stretched}) {
    report("Desk.exr", image_blocks("Desk.exr", 100), kind, true);
    report("memorial.hdr", image_blocks("memorial.hdr", 100), kind, true);
  }
}

}  // namespace
}  // namespace blocklab
