// Interval soundness of the solver library's problems (acceptance: for 10^5 random boxes of each problem, dense point
// samples lie inside the interval error; SPECS.md section 6, "compare interval bounds with dense sampling"). The
// boxes, samples and checks are tests/contract/interval_soundness.h.
//
// Synthetic blocks, 10^5 boxes each (1000 blocks): BC1 endpoints (formats/common/s3tc_endpoint_problem.h, both
// modes), BC4 endpoints (both modes), the 2D chroma shape fit of Munkberg 2008 section 7.1 with the linear error
// (eq. 11) and with the stretched error (section 7.2; the interval path is the natural extension, raised by a
// tangent-plane bound and by the pair bound of formats/munkberg/shape_fit/shape_fit_pair_bound.h,
// formats/munkberg/shape_fit/shape_fit_problem.h). The blocks
// reach the clamps and the ends of the lattices (noise, clusters, ramps, constants, extremes).
// Real blocks: every registered format's block problems (Format::block_problems(), the tables), 100 blocks of the
// bundled samples x 100 boxes each (tests/contract/registered_problem_checks.h), so a format that declares a problem
// is covered without an edit here.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <functional>
#include <string>
#include <vector>

#include "core/problem.h"
#include "formats/munkberg/shape_fit/shape_fit_problem.h"
#include "formats/common/s3tc_endpoint_problem.h"
#include "solvers/seeding.h"
#include "tests/contract/interval_soundness.h"
#include "tests/contract/registered_problem_checks.h"

namespace blocklab {
namespace {

using soundness::check_boxes;
using soundness::SoundnessCount;

constexpr int kBoxesPerProblem = 100000;   // the acceptance count, per synthetic problem
constexpr int kBoxesPerBlock = 100;         // so each synthetic problem sees 1000 different blocks

// Runs kBoxesPerProblem boxes over kBoxesPerProblem / kBoxesPerBlock blocks made by `make_and_check`.
void expect_sound(const char* name, std::uint64_t seed,
                  const std::function<void(int block, RandomStream& random, SoundnessCount& count)>& make_and_check) {
  RandomStream random(seed);
  SoundnessCount count;
  for (int block = 0; block < kBoxesPerProblem / kBoxesPerBlock; ++block) make_and_check(block, random, count);
  soundness::expect_sound_count(name, count, kBoxesPerProblem);
}

// A value in [0, 1] for texel `t` of a block of kind `kind`: uniform noise, two clusters, a ramp, near-constant,
// or the extremes 0 and 1 (the clamps and the ends of the lattices).
double texel_value(int kind, int t, double a, double b, RandomStream& random) {
  switch (kind % 5) {
    case 0: return random.uniform01();
    case 1: return std::clamp((t % 2 ? a : b) + 0.02 * (random.uniform01() - 0.5), 0.0, 1.0);
    case 2: return a + (b - a) * t / 15.0;
    case 3: return std::clamp(a + 0.004 * (random.uniform01() - 0.5), 0.0, 1.0);
    default: return random.next_word() >> 63 ? 1.0 : 0.0;
  }
}

TEST(IntervalSoundness, Bc1EndpointErrorEnclosesSampledErrorsOnRandomBoxes) {
  expect_sound("bc1 endpoints", 11, [](int block, RandomStream& random, SoundnessCount& count) {
    Bc1EndpointError error;
    error.mode = block % 2 == 0 ? Bc1Mode::four_color : Bc1Mode::three_color;
    // Perceptual-style channel weights on every fourth block, unit weights otherwise.
    if (block % 4 == 1) error.weights = {0.299, 0.587, 0.114};
    for (int c = 0; c < 3; ++c) {
      const double a = random.uniform01(), b = random.uniform01();
      for (int t = 0; t < 16; ++t)
        error.targets[static_cast<std::size_t>(t)][static_cast<std::size_t>(c)] =
            texel_value(block / 2, t, a, b, random);
    }
    check_boxes(make_bc1_endpoint_problem(error), kBoxesPerBlock, random, count);
  });
}

TEST(IntervalSoundness, Bc4EndpointErrorEnclosesSampledErrorsOnRandomBoxes) {
  expect_sound("bc4 endpoints", 12, [](int block, RandomStream& random, SoundnessCount& count) {
    Bc4EndpointError error;
    error.mode = block % 2 == 0 ? Bc4Mode::eight_value : Bc4Mode::six_value;
    const double a = random.uniform01(), b = random.uniform01();
    for (int t = 0; t < 16; ++t) error.targets[static_cast<std::size_t>(t)] = texel_value(block / 2, t, a, b, random);
    check_boxes(make_bc4_endpoint_problem(error), kBoxesPerBlock, random, count);
  });
}

// Shape-fit blocks: 16 points (uniform, four tight clusters, a line, all equal, or on the square's edges), unit or
// random weights (some zero), the unit square, a kite or a random template, 8-bit or coarser lattices.
ShapeFitData shape_block(int block, ShapeErrorKind kind, RandomStream& random) {
  ShapeFitData data;
  data.error_kind = kind;
  const int variant = block % 5;
  Point2 centres[4];
  for (Point2& c : centres) c = {random.uniform01(), random.uniform01()};
  for (int i = 0; i < 16; ++i) {
    Point2 p;
    switch (variant) {
      case 0: p = {random.uniform01(), random.uniform01()}; break;
      case 1:
        p = centres[i % 4];
        p.u = std::clamp(p.u + 0.02 * (random.uniform01() - 0.5), 0.0, 1.0);
        p.v = std::clamp(p.v + 0.02 * (random.uniform01() - 0.5), 0.0, 1.0);
        break;
      case 2:
        p = {centres[0].u + (centres[1].u - centres[0].u) * i / 15.0,
             centres[0].v + (centres[1].v - centres[0].v) * i / 15.0};
        break;
      case 3: p = centres[0]; break;
      default: p = {static_cast<double>(random.next_word() >> 63), random.uniform01()}; break;
    }
    data.points.push_back(p);
  }
  if (block % 3 == 1)
    for (int i = 0; i < 16; ++i) data.weights.push_back(i % 7 == 0 ? 0.0 : 4.0 * random.uniform01());
  switch (block % 4) {
    case 0: data.shape = ShapeTemplate(); break;
    case 1:
      data.shape = ShapeTemplate::from_landmarks({Point2{0, 0}, Point2{1, 0}, Point2{0.6, 0.5}, Point2{0.2, -0.4}});
      break;
    default:
      data.shape = ShapeTemplate::from_coefficients(
          {0.0, 1.0, 2.0 * random.uniform01() - 0.5, 2.0 * random.uniform01() - 0.5},
          {0.0, 0.0, 2.0 * random.uniform01() - 1.0, 2.0 * random.uniform01() - 1.0});
      break;
  }
  data.lattice_bits = block % 6 == 5 ? 4 : kDefaultShapeLatticeBits;
  return data;
}

TEST(IntervalSoundness, LinearShapeFitErrorEnclosesSampledErrorsOnRandomBoxes) {
  expect_sound("shape fit linear", 13, [](int block, RandomStream& random, SoundnessCount& count) {
    check_boxes(ShapeFitProblem(shape_block(block, ShapeErrorKind::linear, random)), kBoxesPerBlock, random, count);
  });
}

TEST(IntervalSoundness, StretchedShapeFitErrorEnclosesSampledErrorsOnRandomBoxes) {
  expect_sound("shape fit stretched", 14, [](int block, RandomStream& random, SoundnessCount& count) {
    check_boxes(ShapeFitProblem(shape_block(block, ShapeErrorKind::stretched, random)), kBoxesPerBlock, random, count);
  });
}

// Every registered format's every block problem (Format::block_problems()), on real blocks of the bundled samples:
// 100 blocks x 100 boxes each.
class RegisteredBlockProblemSoundness : public ::testing::TestWithParam<std::string> {};

TEST_P(RegisteredBlockProblemSoundness, EnclosesSampledErrorsOnRandomBoxesOfRealBlocks) {
  contract::check_registered_problem_soundness(find_block_problem(GetParam()));
}

INSTANTIATE_TEST_SUITE_P(Formats, RegisteredBlockProblemSoundness,
                         ::testing::ValuesIn(contract::registered_problem_names()),
                         [](const ::testing::TestParamInfo<std::string>& info) {
                           return contract::test_name_of(info.param);
                         });

}  // namespace
}  // namespace blocklab
