// The `bc3` block problems, one per half of the block (Microsoft BC3 / S3TC DXT5 spec;
// formats/common/s3tc_endpoint_problem.h): the colour half is BC1 colour always in the four-colour mode, the alpha
// half is BC4 on the alpha channel (1 for images without alpha: a constant block).
#include "formats/bc3/bc3_problems.h"

#include "formats/common/s3tc_block_problems.h"

namespace blocklab {

std::vector<BlockProblem> bc3_block_problems() {
  return {
      {"color", "colour half: RGB565 endpoints (6 parameters), four-colour palette, squared RGB error",
       BlockImageKind::ldr,
       [](const BlockTexels& block, std::uint64_t) { return make_bc1_block_problem(block, Bc1Mode::four_color); }},
      {"alpha", "alpha half: alpha endpoints (2 parameters on [0, 255]), eight-value palette, squared alpha error",
       BlockImageKind::ldr,
       [](const BlockTexels& block, std::uint64_t) { return make_bc4_block_problem(block, 3, Bc4Mode::eight_value); }},
  };
}

}  // namespace blocklab
