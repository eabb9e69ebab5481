// The block problems of the `munkberg` format (Format::block_problems(), formats/format.h).
#pragma once

#include <vector>

#include "formats/format.h"

namespace blocklab {

std::vector<BlockProblem> munkberg_block_problems();

}  // namespace blocklab
