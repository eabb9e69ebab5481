// The checks every registered block problem (formats/format.h BlockProblem, formats/registry.h) gets, shared by the
// table-driven tests (tests/contract/test_problem_contract.cpp, tests/stress/test_interval_soundness.cpp) and by
// tests/contract/test_registered_tiny_format.cpp, which registers a format of its own and calls exactly these:
//   * check_registered_problem_contract: the Problem contract (problem_contract.h) on Problems drawn from real
//     blocks of the bundled samples (samples/ldr or samples/hdr, experiments/block_samples.h);
//   * check_registered_problem_soundness: interval soundness (interval_soundness.h) on random boxes of such Problems;
//   * registered_problem_names: the "<format>.<problem>" names the parameterised tests are instantiated over.
// Blocks are drawn with a fixed seed, so every run checks the same Problems.
#pragma once

#include <gtest/gtest.h>

#include <cstdint>
#include <string>
#include <vector>

#include "experiments/block_samples.h"
#include "formats/registry.h"
#include "tests/contract/interval_soundness.h"
#include "tests/contract/problem_contract.h"

namespace blocklab::contract {

constexpr std::uint64_t kRegisteredProblemSeed = 20240611;

inline std::vector<std::string> registered_problem_names() {
  std::vector<std::string> names;
  for (const RegisteredBlockProblem& entry : registered_block_problems()) names.push_back(entry.full_name());
  return names;
}

// A GoogleTest parameter name for "<format>.<problem>" (letters, digits and '_' only).
inline std::string test_name_of(const std::string& full_name) {
  std::string name = full_name;
  for (char& c : name)
    if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
  return name;
}

// `count` Problems of `entry` from the bundled samples of its image kind.
inline std::vector<DrawnProblem> draw_sample_problems(const RegisteredBlockProblem& entry, int count) {
  const std::vector<std::string> files =
      image_files(block_image_folder(BLOCKLAB_TEST_SAMPLES, entry.problem.image_kind));
  return draw_block_problems(entry, files, count, kRegisteredProblemSeed);
}

// The Problem contract on `blocks` Problems of `entry` drawn from real blocks.
inline void check_registered_problem_contract(const RegisteredBlockProblem& entry, int blocks = 3) {
  ContractOptions options;
  options.box_count = 100;
  options.samples_per_box = 50;
  options.min_checked_gradient_fraction = entry.problem.min_checked_gradient_fraction;
  for (const DrawnProblem& drawn : draw_sample_problems(entry, blocks)) {
    SCOPED_TRACE(entry.full_name() + " on " + drawn.source);
    // The residual check (d) costs points x residuals^2 x parameters evaluations: fewer points for long residual
    // vectors (banterle's eq. 3 has one per histogram bin, 1024) keep every problem's check to a fraction of a second.
    options.point_count = drawn.problem->residual_count() > 64 ? 20 : 100;
    check_problem_contract(*drawn.problem, options);
  }
}

// Interval soundness on `boxes_per_block` random boxes of each of `blocks` Problems of `entry`.
inline void check_registered_problem_soundness(const RegisteredBlockProblem& entry, int blocks = 100,
                                               int boxes_per_block = 100) {
  RandomStream random(block_problem_stream_seed(kRegisteredProblemSeed, entry.full_name()));
  soundness::SoundnessCount count;
  for (const DrawnProblem& drawn : draw_sample_problems(entry, blocks)) {
    SCOPED_TRACE(entry.full_name() + " on " + drawn.source);
    soundness::check_boxes(*drawn.problem, boxes_per_block, random, count, entry.problem.bounded_enclosures);
  }
  soundness::expect_sound_count(entry.full_name(), count,
                                static_cast<std::uint64_t>(blocks) * static_cast<std::uint64_t>(boxes_per_block));
}

}  // namespace blocklab::contract
