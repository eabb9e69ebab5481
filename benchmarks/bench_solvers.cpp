// Speed goals of the solver library (issue 4 closing note), measured on 4x4 blocks of real HDR images:
//   * procrustes: blocks per second on one core (goal >= 100,000) and mean error relative to the certified optimum
//     (goal within 5%), also after lattice_polish (Munkberg 2008 sec. 7.1: "search in a small radius of quantized
//     values around each base point");
//   * interval_bb: milliseconds per block to certify the 4-parameter shape fit at 8 bits per coordinate, started
//     from the procrustes + lattice_polish answer (goal < 20 ms on average).
// Shape-fit points are the chroma (u, v) of Munkberg 2008 eq. 2 (rgb_to_logyuv) of each texel, weight 0 for black
// texels, the "kite" template (0,0), (1,0), (0.6,0.5), (0.2,-0.4), as `blocklab bench solvers` builds them.
// Usage: bench_solvers [DATA_ROOT] [BLOCKS_PER_IMAGE] [CERTIFIED_BLOCKS]; prints numbers, asserts nothing.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "core/color_spaces.h"
#include "core/image_io.h"
#include "core/input_policy.h"
#include "core/shape_fit_problem.h"
#include "solvers/interval_bb/interval_bb_solver.h"
#include "solvers/lattice_polish/lattice_polish_solver.h"
#include "solvers/procrustes/procrustes_solver.h"

namespace {

using namespace blocklab;

double seconds_since(std::chrono::steady_clock::time_point t) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count();
}

// `count` blocks spread evenly over the image (row-major block order).
std::vector<ShapeFitData> image_blocks(const std::string& path, int count, ShapeErrorKind kind) {
  Image image = read_image(path);
  apply_input_policy(image, InputPolicy::clamp, path);
  const long long bx = image.width / 4, by = image.height / 4;
  std::vector<ShapeFitData> blocks;
  for (int b = 0; b < count; ++b) {
    const long long index = static_cast<long long>(b) * bx * by / count;
    const int x0 = static_cast<int>(index % bx) * 4, y0 = static_cast<int>(index / bx) * 4;
    ShapeFitData data;
    data.shape = ShapeTemplate::from_landmarks({Point2{0, 0}, Point2{1, 0}, Point2{0.6, 0.5}, Point2{0.2, -0.4}});
    data.error_kind = kind;
    for (int t = 0; t < 16; ++t) {
      const float* texel = image.texel(x0 + t % 4, y0 + t / 4);
      const Rgb<double> rgb{texel[0], texel[1], texel[2]};
      const LogYuv<double> yuv = rgb_to_logyuv(rgb);
      data.points.push_back({std::min(1.0, std::max(0.0, yuv.u)), std::min(1.0, std::max(0.0, yuv.v))});
      data.weights.push_back(rgb.r == 0.0 && rgb.g == 0.0 && rgb.b == 0.0 ? 0.0 : 1.0);
    }
    blocks.push_back(data);
  }
  return blocks;
}

void report(const std::string& name, const std::vector<ShapeFitData>& blocks, int certified_blocks) {
  std::vector<ShapeFitProblem> problems;
  for (const ShapeFitData& data : blocks) problems.emplace_back(data);
  const std::size_t n = problems.size();
  const ProcrustesOptions procrustes;
  const LatticePolishOptions polish;

  // Procrustes throughput: repeated until about 1 s has passed.
  std::vector<SolveResult> fits(n);
  std::size_t solved = 0;
  const auto t0 = std::chrono::steady_clock::now();
  do {
    for (std::size_t i = 0; i < n; ++i) fits[i] = solve_procrustes(problems[i], problems[i], procrustes, nullptr, 0);
    solved += n;
  } while (seconds_since(t0) < 1.0);
  const double procrustes_rate = static_cast<double>(solved) / seconds_since(t0);

  std::vector<SolveResult> polished(n);
  const auto t1 = std::chrono::steady_clock::now();
  for (std::size_t i = 0; i < n; ++i)
    polished[i] = solve_lattice_polish(problems[i], polish, fits[i].parameters.data(), 0);
  const double polish_rate = static_cast<double>(n) / seconds_since(t1);

  // Certification of the first `certified_blocks` blocks.
  const std::size_t m = std::min<std::size_t>(n, static_cast<std::size_t>(certified_blocks));
  double fit_sum = 0, polish_sum = 0, optimum_sum = 0, bb_seconds = 0, worst = 0, boxes = 0;
  std::size_t optimal = 0;
  for (std::size_t i = 0; i < m; ++i) {
    const auto t = std::chrono::steady_clock::now();
    const SolveResult bb = solve_interval_bb(problems[i], IntervalBbOptions{}, polished[i].parameters.data(), 0);
    const double s = seconds_since(t);
    bb_seconds += s;
    worst = std::max(worst, s);
    boxes += static_cast<double>(bb.summary.interval_evaluations);
    if (bb.summary.termination == Termination::optimal) ++optimal;
    fit_sum += fits[i].summary.final_error;
    polish_sum += polished[i].summary.final_error;
    optimum_sum += bb.summary.final_error;
  }
  std::printf("%-34s procrustes %8.0f blocks/s, +lattice_polish %8.0f blocks/s | on %zu certified blocks: "
              "procrustes/optimum %.4f, +polish/optimum %.4f | interval_bb %.1f ms/block (worst %.0f), "
              "%.0f boxes/block, %zu/%zu optimal\n",
              name.c_str(), procrustes_rate, polish_rate, m, fit_sum / optimum_sum, polish_sum / optimum_sum,
              1e3 * bb_seconds / static_cast<double>(m), 1e3 * worst, boxes / static_cast<double>(m), optimal, m);
  std::fflush(stdout);
}

}  // namespace

int main(int argc, char** argv) {
  const std::string root = argc > 1 ? argv[1] : std::string(BLOCKLAB_SOURCE_DIR) + "/../shared/data";
  const int per_image = argc > 2 ? std::atoi(argv[2]) : 2000;
  const int certified = argc > 3 ? std::atoi(argv[3]) : 20;
  try {
    for (const ShapeErrorKind kind : {ShapeErrorKind::linear, ShapeErrorKind::stretched})
      for (const char* file : {"Desk.exr", "memorial.hdr"})
        report(std::string(file) + " " + to_string(kind), image_blocks(root + "/hdr/" + file, per_image, kind),
               certified);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "bench_solvers: %s\n", e.what());
    return 1;
  }
  return 0;
}
