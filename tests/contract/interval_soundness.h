// Interval soundness of a Problem on random boxes (SPECS.md section 6, "compare interval bounds with dense
// sampling"), shared by tests/stress/test_interval_soundness.cpp and the registered-format tests
// (tests/contract/registered_problem_checks.h). interval_bb's certificate is only as good as these enclosures: a
// box whose interval error misses a point error could be pruned while holding the optimum.
//   * half the boxes are as interval_bb builds them, [point(lo), point(hi)] for lattice index ranges whose spans are
//     spread over every bisection depth (log-uniform), including single-point sides; their samples include random
//     LATTICE points of the box (the candidates interval_bb certifies). A parameter without a lattice gets a real
//     side instead;
//   * half are boxes with arbitrary real corners (so the continuous extensions are checked between lattice points).
// Per box: two random corners, the centre, and random interior points (kSamplesPerBox in all). Every sampled double
// error must lie in the enclosure, and the enclosure must be finite (a [-inf, inf] enclosure would make the check
// vacuous; the problems checked have finite errors on their whole box). A problem whose natural extension is
// unbounded above on wide boxes (BlockProblem::bounded_enclosures false) must still have a finite LOWER bound (the
// one a branch-and-bound prunes with); its boxes unbounded above are counted and their samples checked.
// Randomness is the portable SplitMix64 stream of solvers/seeding.h: the same boxes for the same seed.
#pragma once

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <string>
#include <vector>

#include "core/problem.h"
#include "solvers/seeding.h"

namespace blocklab::soundness {

constexpr int kSamplesPerBox = 8;   // 2 corners + centre + 5 interior (lattice or real) points
constexpr int kReportedFailures = 5;

struct SoundnessCount {
  std::uint64_t boxes = 0;
  std::uint64_t samples = 0;
  std::uint64_t outside = 0;         // samples outside their box's enclosure
  std::uint64_t infinite = 0;        // enclosures with a non-finite bound that is not allowed
  std::uint64_t unbounded_above = 0; // allowed enclosures [finite, +inf]
  double relative_width_sum = 0.0;   // width / (|upper| + 1e-300), for the printed summary
};

inline std::string box_text(const std::vector<Interval>& box) {
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
inline void lattice_side(const Lattice& lattice, RandomStream& random, std::int64_t& lo, std::int64_t& hi) {
  const double depth = random.uniform01() * std::log2(static_cast<double>(lattice.count));
  const std::int64_t span = std::min<std::int64_t>(lattice.count - 1, static_cast<std::int64_t>(std::exp2(depth)) - 1);
  lo = static_cast<std::int64_t>(random.uniform_index(static_cast<std::uint64_t>(lattice.count - span)));
  hi = lo + span;
}

// A real side inside [lower, upper]: half of them short (about one lattice step or less, as near the end of a
// bisection), some degenerate.
inline Interval real_side(double lower, double upper, double step, RandomStream& random) {
  const double scale = random.uniform01() < 0.5 ? (upper - lower) : std::max(step, 1e-3) * random.uniform01();
  const double a = random.uniform(lower, upper);
  double c = std::min(upper, a + scale * random.uniform01());
  if (random.uniform01() < 0.05) c = a;   // a degenerate side
  return Interval(a, c);
}

// Checks `box_count` boxes of `problem`, accumulating into `count`. `bounded_above`: the enclosure's upper bound must
// be finite too.
inline void check_boxes(const Problem& problem, int box_count, RandomStream& random, SoundnessCount& count,
                        bool bounded_above = true) {
  const int dim = problem.dim();
  const std::size_t n = static_cast<std::size_t>(dim);
  std::vector<Interval> box(n);
  std::vector<std::int64_t> lo_index(n), hi_index(n);
  std::vector<bool> on_lattice(n);
  std::vector<double> x(n);
  for (int b = 0; b < box_count; ++b) {
    const bool lattice_box = (b % 2) == 0;
    for (std::size_t p = 0; p < n; ++p) {
      const Lattice& lattice = problem.lattice(static_cast<int>(p));
      on_lattice[p] = lattice_box && lattice.present();
      if (on_lattice[p]) {
        lattice_side(lattice, random, lo_index[p], hi_index[p]);
        box[p] = Interval(lattice.point(lo_index[p]), lattice.point(hi_index[p]));
      } else {
        box[p] = real_side(problem.lower(static_cast<int>(p)), problem.upper(static_cast<int>(p)), lattice.step,
                           random);
      }
    }
    const Interval enclosure = problem.eval(box.data());
    ++count.boxes;
    const bool finite_upper = std::isfinite(enclosure.upper());
    if (!std::isfinite(enclosure.lower()) || (bounded_above && !finite_upper)) {
      // Reported once per box; a non-finite enclosure still "contains" every sample, so it must not hide here.
      if (count.infinite++ < kReportedFailures)
        ADD_FAILURE() << "non-finite enclosure " << to_string(enclosure) << " over box " << box_text(box);
      continue;
    }
    if (finite_upper)
      count.relative_width_sum += width(enclosure) / (std::abs(enclosure.upper()) + 1e-300);
    else
      ++count.unbounded_above;
    for (int s = 0; s < kSamplesPerBox; ++s) {
      for (std::size_t p = 0; p < n; ++p) {
        const Interval& side = box[p];
        if (s < 2) {
          x[p] = random.next_word() >> 63 ? side.upper() : side.lower();   // a random corner
        } else if (s == 2) {
          x[p] = midpoint(side);
        } else if (on_lattice[p] && s % 2 == 1) {
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

// Prints the summary line of `name` and expects `expected_boxes` finite enclosures holding every sample.
inline void expect_sound_count(const std::string& name, const SoundnessCount& count, std::uint64_t expected_boxes) {
  std::printf("%-30s %llu boxes, %llu samples, %llu outside, mean relative enclosure width %.3g", name.c_str(),
              static_cast<unsigned long long>(count.boxes), static_cast<unsigned long long>(count.samples),
              static_cast<unsigned long long>(count.outside),
              count.relative_width_sum / static_cast<double>(count.boxes - count.unbounded_above));
  if (count.unbounded_above > 0)
    std::printf(" (of the %llu bounded above)", static_cast<unsigned long long>(count.boxes - count.unbounded_above));
  std::printf("\n");
  EXPECT_EQ(count.boxes, expected_boxes);
  EXPECT_EQ(count.infinite, 0u);
  EXPECT_EQ(count.samples, expected_boxes * kSamplesPerBox);
  EXPECT_EQ(count.outside, 0u);
}

}  // namespace blocklab::soundness
