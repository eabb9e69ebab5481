// The block problems of the `bc1` format (Format::block_problems(), formats/format.h).
#pragma once

#include <vector>

#include "formats/format.h"

namespace blocklab {

std::vector<BlockProblem> bc1_block_problems();

}  // namespace blocklab
