// The BC6H block problem: the one-region endpoint fit of bc6h_endpoint_problem.h (mode 3, KDFS "BC6H") on a real HDR
// block, its indices fixed from the builtin fit of that block in mode 3 (encode_in_mode with one least-squares
// round). The fit has no random choice, so the seed is unused: the same block gives the same Problem.
#include "formats/bc6h/bc6h_problems.h"

#include "formats/bc6h/bc6h_endpoint_problem.h"
#include "formats/bc6h/bc6h_mode_search.h"

namespace blocklab {

std::vector<BlockProblem> bc6h_block_problems(bool is_signed) {
  const auto make = [is_signed](const BlockTexels& block, std::uint64_t) -> std::unique_ptr<Problem> {
    const bc6h::BlockTarget target = bc6h::make_block_target(block.rgba, is_signed);
    const bc6h::EncodedBlock fit = bc6h::encode_in_mode(target, bc6h::mode_index_of_number(3), 0, 1);
    return std::make_unique<ErrorProblem<bc6h::OneRegionEndpointError>>(
        bc6h::make_one_region_endpoint_problem(target.half, fit.params.indices, is_signed));
  };
  return {{"one_region_endpoints",
           "stored 10-bit endpoint codes of mode 3 (6 parameters, RGB x 2), indices fixed from the builtin fit, relaxed "
           "decoder error in half bits (KDFS BC6H)",
           BlockImageKind::hdr, make}};
}

}  // namespace blocklab
