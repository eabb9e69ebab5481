// Solver-library endpoint searches for S3TC blocks (formats/common/s3tc_solver_fit.h).
#include "formats/common/s3tc_solver_fit.h"

#include <vector>

#include "formats/bc4/bc4_encoder.h"
#include "formats/common/s3tc_endpoint_problem.h"

namespace blocklab {

Bc1Params fit_color_block_with_solver(const ColorBlock& block, const ColorFitSettings& settings,
                                      const BlockSolverSetup& setup, std::size_t block_index) {
  ColorFitSettings fast = settings;
  fast.search = S3tcSearch::fast;
  const Bc1Params start_block = fit_color_block(block, fast);
  std::vector<double> start;
  for (const auto& endpoint : start_block.endpoints)
    for (int channel = 0; channel < 3; ++channel) start.push_back(endpoint[channel]);

  Bc1EndpointError error;
  for (int texel = 0; texel < 16; ++texel)
    for (int channel = 0; channel < 3; ++channel)
      error.targets[texel][channel] = block.texels[texel][channel] / 255.0;   // code units -> [0, 1]
  for (int channel = 0; channel < 3; ++channel) error.weights[channel] = block.weights[channel];

  Bc1Params best;
  float best_error = 0.0f;
  bool have_best = false;
  for (const Bc1Mode mode : {Bc1Mode::four_color, Bc1Mode::three_color}) {
    if (mode == Bc1Mode::three_color && !settings.allow_three_color) continue;
    error.mode = mode;
    const auto problem = make_bc1_endpoint_problem(error);
    const std::vector<std::int64_t> answer = solve_block_on_lattice(setup, problem, start, block_index);
    ColorCandidate candidate;
    candidate.mode = mode;
    for (int k = 0; k < 6; ++k) candidate.endpoints[k / 3][k % 3] = static_cast<int>(answer[k]);
    Bc1Params params;
    const float candidate_error = evaluate_color_candidate(block, candidate, params.indices.data());
    // Strictly better only: on a tie the 4-colour answer (tried first) stays.
    if (!have_best || candidate_error < best_error) {
      params.endpoints = candidate.endpoints;
      params.mode = mode;
      best = params;
      best_error = candidate_error;
      have_best = true;
    }
  }
  return settings.allow_three_color ? canonicalise_bc1(best) : canonicalise_bc3_color(best);
}

Bc4Params fit_bc4_block_with_solver(const float values[16], const BlockSolverSetup& setup, std::size_t block_index) {
  const Bc4Params start_block = fit_bc4_block(values, S3tcSearch::fast);
  const std::vector<double> start = {static_cast<double>(start_block.endpoints[0]),
                                     static_cast<double>(start_block.endpoints[1])};
  Bc4EndpointError error;
  for (int texel = 0; texel < 16; ++texel) error.targets[texel] = values[texel] / 255.0;   // code units -> [0, 1]

  Bc4Params best;
  float best_error = 0.0f;
  bool have_best = false;
  for (const Bc4Mode mode : {Bc4Mode::eight_value, Bc4Mode::six_value}) {
    error.mode = mode;
    const auto problem = make_bc4_endpoint_problem(error);
    const std::vector<std::int64_t> answer = solve_block_on_lattice(setup, problem, start, block_index);
    Bc4Params params;
    params.endpoints = {static_cast<int>(answer[0]), static_cast<int>(answer[1])};
    params.mode = mode;
    const float candidate_error =
        evaluate_bc4_candidate(values, params.endpoints[0], params.endpoints[1], mode, params.indices.data());
    if (!have_best || candidate_error < best_error) {   // ties keep the 8-value answer (tried first)
      best = params;
      best_error = candidate_error;
      have_best = true;
    }
  }
  return canonicalise_bc4(best);
}

}  // namespace blocklab
