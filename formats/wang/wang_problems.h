// The block problems of the `wang` format (Format::block_problems(), formats/format.h): the section 3.5 1D codec's
// endpoint searches (formats/wang/wang_block_problem.h) posed on one real HDR block.
#pragma once

#include <vector>

#include "formats/format.h"

namespace blocklab {

std::vector<BlockProblem> wang_block_problems();

}  // namespace blocklab
