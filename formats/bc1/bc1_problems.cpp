// The `bc1` block problems: the colour endpoint search in each of the two palette modes (Microsoft BC1 / S3TC DXT1
// spec; formats/common/s3tc_endpoint_problem.h), on the RGB code values of an LDR block.
#include "formats/bc1/bc1_problems.h"

#include "formats/common/s3tc_block_problems.h"

namespace blocklab {

std::vector<BlockProblem> bc1_block_problems() {
  return {
      {"four_color", "RGB565 endpoints (6 parameters), four-colour palette, squared RGB error of the block's texels",
       BlockImageKind::ldr,
       [](const BlockTexels& block, std::uint64_t) { return make_bc1_block_problem(block, Bc1Mode::four_color); }},
      {"three_color", "RGB565 endpoints (6 parameters), three colours and black, squared RGB error",
       BlockImageKind::ldr,
       [](const BlockTexels& block, std::uint64_t) { return make_bc1_block_problem(block, Bc1Mode::three_color); }},
  };
}

}  // namespace blocklab
