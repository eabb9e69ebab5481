// The block problems of the `bc3` format (Format::block_problems(), formats/format.h).
#pragma once

#include <vector>

#include "formats/format.h"

namespace blocklab {

std::vector<BlockProblem> bc3_block_problems();

}  // namespace blocklab
