// S3TC endpoint Problems of a real block (formats/common/s3tc_block_problems.h).
#include "formats/common/s3tc_block_problems.h"

#include <algorithm>

#include "formats/common/s3tc_endpoint_problem.h"

namespace blocklab {

namespace {

double unit_clamped(float value) { return std::clamp(static_cast<double>(value), 0.0, 1.0); }

}  // namespace

std::unique_ptr<Problem> make_bc1_block_problem(const BlockTexels& block, Bc1Mode mode) {
  Bc1EndpointError error;
  error.mode = mode;
  for (int t = 0; t < kBlockTexels; ++t)
    for (int c = 0; c < 3; ++c)
      error.targets[static_cast<std::size_t>(t)][static_cast<std::size_t>(c)] = unit_clamped(block.rgba[t][c]);
  return std::make_unique<ErrorProblem<Bc1EndpointError>>(make_bc1_endpoint_problem(error));
}

std::unique_ptr<Problem> make_bc4_block_problem(const BlockTexels& block, int channel, Bc4Mode mode) {
  Bc4EndpointError error;
  error.mode = mode;
  for (int t = 0; t < kBlockTexels; ++t)
    error.targets[static_cast<std::size_t>(t)] = unit_clamped(block.rgba[t][channel]);
  return std::make_unique<ErrorProblem<Bc4EndpointError>>(make_bc4_endpoint_problem(error));
}

}  // namespace blocklab
