// The block problems of the `bc4` format (Format::block_problems(), formats/format.h).
#pragma once

#include <vector>

#include "formats/format.h"

namespace blocklab {

std::vector<BlockProblem> bc4_block_problems();

}  // namespace blocklab
