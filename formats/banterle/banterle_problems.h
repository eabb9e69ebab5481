// The block problems of the `banterle` format (Format::block_problems(), formats/format.h).
#pragma once

#include <vector>

#include "formats/format.h"

namespace blocklab {

std::vector<BlockProblem> banterle_block_problems();

}  // namespace blocklab
