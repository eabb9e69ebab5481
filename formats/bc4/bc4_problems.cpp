// The `bc4` block problems: the endpoint search in each of the two palette modes (Microsoft BC4 unorm spec;
// formats/common/s3tc_endpoint_problem.h), on the red code values of an LDR block (the channel bc4 stores).
#include "formats/bc4/bc4_problems.h"

#include "formats/common/s3tc_block_problems.h"

namespace blocklab {

std::vector<BlockProblem> bc4_block_problems() {
  return {
      {"eight_value", "red endpoints (2 parameters on [0, 255]), eight-value palette, squared error of the red channel",
       BlockImageKind::ldr,
       [](const BlockTexels& block, std::uint64_t) { return make_bc4_block_problem(block, 0, Bc4Mode::eight_value); }},
      {"six_value", "red endpoints (2 parameters), six values plus 0 and 1, squared error of the red channel",
       BlockImageKind::ldr,
       [](const BlockTexels& block, std::uint64_t) { return make_bc4_block_problem(block, 0, Bc4Mode::six_value); }},
  };
}

}  // namespace blocklab
