// Interval soundness of the solver library's problems (issue 4 acceptance: "for 10^5 random boxes of each problem,
// dense point samples lie inside the interval error"; SPECS.md section 6, "compare interval bounds with dense
// sampling"). interval_bb's certificate is only as good as these enclosures: a box whose interval error misses a
// point error could be pruned while holding the optimum.
//
// Problems: BC1 endpoints (formats/common/s3tc_endpoint_problem.h, both modes), BC4 endpoints (both modes), the
// 2D chroma shape fit of Munkberg 2008 section 7.1 with the linear error (eq. 11) and with the stretched error
// (section 7.2; the interval path is the natural extension, raised by a tangent-plane bound and by the pair bound
// of formats/munkberg/shape_fit/shape_fit_pair_bound.h, formats/munkberg/shape_fit/shape_fit_problem.h). For each
// problem 10^5 boxes over many random blocks:
//   * half are boxes as interval_bb builds them, [point(lo), point(hi)] for lattice index ranges whose spans are
//     spread over every bisection depth (log-uniform), including single-point sides; their samples include
//     random LATTICE points of the box (the candidates interval_bb certifies);
//   * half are boxes with arbitrary real corners (so the continuous extensions are checked between lattice points).
// Per box: two random corners, the centre, and random interior points (kSamplesPerBox in all). Every sampled
// double error must lie in the enclosure, and the enclosure must be finite (a [-inf, inf] enclosure would make the
// check vacuous; these problems have finite errors on their whole box).
// Randomness is the portable SplitMix64 stream of solvers/seeding.h with fixed seeds: the same boxes on every run.
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

namespace blocklab {
namespace {

constexpr int kBoxesPerProblem = 100000;   // the acceptance count, per problem
constexpr int kBoxesPerBlock = 100;         // so each problem sees 1000 different blocks
constexpr int kSamplesPerBox = 8;           // 2 corners + centre + 5 interior (lattice or real) points
constexpr int kReportedFailures = 5;

struct SoundnessCount {
  std::uint64_t boxes = 0;
  std::uint64_t samples = 0;
  std::uint64_t outside = 0;         // samples outside their box's enclosure
  std::uint64_t infinite = 0;        // enclosures with a non-finite bound
  double relative_width_sum = 0.0;   // width / (|upper| + 1e-300), for the printed summary
};

std::string box_text(const std::vector<Interval>& box) {
  std::string text;
  char buffer[96];
  for (const Interval& side : box) {
    std::snprintf(buffer, sizeof buffer, "%s[%.17g, %.17g]", text.empty() ? "" : " x ", side.lower(), side.upper());
    text += buffer;
  }
  return text;
}

// A side of an interval_bb-style box: lattice indices [lo, hi] with a span 2^(u * log2(count)) - 1 (log-uniform
// over the bisection depths; 0 = a single lattice point).
void lattice_side(const Lattice& lattice, RandomStream& random, std::int64_t& lo, std::int64_t& hi) {
  const double depth = random.uniform01() * std::log2(static_cast<double>(lattice.count));
  const std::int64_t span = std::min<std::int64_t>(lattice.count - 1, static_cast<std::int64_t>(std::exp2(depth)) - 1);
  lo = static_cast<std::int64_t>(random.uniform_index(static_cast<std::uint64_t>(lattice.count - span)));
  hi = lo + span;
}

// Checks kBoxesPerBlock boxes of `problem`, accumulating into `count`.
void check_boxes(const Problem& problem, RandomStream& random, SoundnessCount& count) {
  const int dim = problem.dim();
  const std::size_t n = static_cast<std::size_t>(dim);
  std::vector<Interval> box(n);
  std::vector<std::int64_t> lo_index(n), hi_index(n);
  std::vector<double> x(n);
  for (int b = 0; b < kBoxesPerBlock; ++b) {
    const bool lattice_box = (b % 2) == 0;
    for (std::size_t p = 0; p < n; ++p) {
      const Lattice& lattice = problem.lattice(static_cast<int>(p));
      if (lattice_box) {
        lattice_side(lattice, random, lo_index[p], hi_index[p]);
        box[p] = Interval(lattice.point(lo_index[p]), lattice.point(hi_index[p]));
      } else {
        const double lower = problem.lower(static_cast<int>(p)), upper = problem.upper(static_cast<int>(p));
        // Half the real sides are short (about one lattice step or less), as near the end of a bisection.
        const double scale =
            random.uniform01() < 0.5 ? (upper - lower) : std::max(lattice.step, 1e-3) * random.uniform01();
        double a = random.uniform(lower, upper);
        double c = std::min(upper, a + scale * random.uniform01());
        if (random.uniform01() < 0.05) c = a;   // a degenerate side
        box[p] = Interval(a, c);
      }
    }
    const Interval enclosure = problem.eval(box.data());
    ++count.boxes;
    const bool finite = std::isfinite(enclosure.lower()) && std::isfinite(enclosure.upper());
    if (!finite) {
      // Reported once per box; a non-finite enclosure still "contains" every sample, so it must not hide here.
      if (count.infinite++ < kReportedFailures)
        ADD_FAILURE() << "non-finite enclosure " << to_string(enclosure) << " over box " << box_text(box);
      continue;
    }
    count.relative_width_sum += width(enclosure) / (std::abs(enclosure.upper()) + 1e-300);
    for (int s = 0; s < kSamplesPerBox; ++s) {
      for (std::size_t p = 0; p < n; ++p) {
        const Interval& side = box[p];
        if (s < 2) {
          x[p] = random.next_word() >> 63 ? side.upper() : side.lower();   // a random corner
        } else if (s == 2) {
          x[p] = midpoint(side);
        } else if (lattice_box && s % 2 == 1) {
          const Lattice& lattice = problem.lattice(static_cast<int>(p));
          const auto span = static_cast<std::uint64_t>(hi_index[p] - lo_index[p] + 1);
          x[p] = lattice.point(lo_index[p] + static_cast<std::int64_t>(random.uniform_index(span)));
        } else {
          // uniform(lo, hi) is in [lo, hi) up to rounding; clamp so rounding never leaves the box.
          x[p] = std::clamp(random.uniform(side.lower(), side.upper()), side.lower(), side.upper());
        }
      }
      const double value = problem.eval(x.data());
      ++count.samples;
      if (!contains(enclosure, value)) {
        if (count.outside++ < kReportedFailures) {
          std::string point;
          for (double v : x) point += (point.empty() ? "" : ", ") + std::to_string(v);
          ADD_FAILURE() << "error " << value << " at (" << point << ") lies outside the enclosure "
                        << to_string(enclosure) << " of box " << box_text(box);
        }
      }
    }
  }
}

// Runs kBoxesPerProblem boxes over kBoxesPerProblem / kBoxesPerBlock blocks made by `make_and_check`.
void expect_sound(const char* name, std::uint64_t seed,
                  const std::function<void(int block, RandomStream& random, SoundnessCount& count)>& make_and_check) {
  RandomStream random(seed);
  SoundnessCount count;
  for (int block = 0; block < kBoxesPerProblem / kBoxesPerBlock; ++block) make_and_check(block, random, count);
  std::printf("%-22s %llu boxes, %llu samples, %llu outside, mean relative enclosure width %.3g\n", name,
              static_cast<unsigned long long>(count.boxes), static_cast<unsigned long long>(count.samples),
              static_cast<unsigned long long>(count.outside),
              count.relative_width_sum / static_cast<double>(count.boxes));
  EXPECT_EQ(count.boxes, static_cast<std::uint64_t>(kBoxesPerProblem));
  EXPECT_EQ(count.infinite, 0u);
  EXPECT_EQ(count.samples, static_cast<std::uint64_t>(kBoxesPerProblem) * kSamplesPerBox);
  EXPECT_EQ(count.outside, 0u);
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
    check_boxes(make_bc1_endpoint_problem(error), random, count);
  });
}

TEST(IntervalSoundness, Bc4EndpointErrorEnclosesSampledErrorsOnRandomBoxes) {
  expect_sound("bc4 endpoints", 12, [](int block, RandomStream& random, SoundnessCount& count) {
    Bc4EndpointError error;
    error.mode = block % 2 == 0 ? Bc4Mode::eight_value : Bc4Mode::six_value;
    const double a = random.uniform01(), b = random.uniform01();
    for (int t = 0; t < 16; ++t) error.targets[static_cast<std::size_t>(t)] = texel_value(block / 2, t, a, b, random);
    check_boxes(make_bc4_endpoint_problem(error), random, count);
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
    check_boxes(ShapeFitProblem(shape_block(block, ShapeErrorKind::linear, random)), random, count);
  });
}

TEST(IntervalSoundness, StretchedShapeFitErrorEnclosesSampledErrorsOnRandomBoxes) {
  expect_sound("shape fit stretched", 14, [](int block, RandomStream& random, SoundnessCount& count) {
    check_boxes(ShapeFitProblem(shape_block(block, ShapeErrorKind::stretched, random)), random, count);
  });
}

}  // namespace
}  // namespace blocklab
