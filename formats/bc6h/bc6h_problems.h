// The block problems of the `bc6h` and `bc6h_sf` formats (Format::block_problems(), formats/format.h).
#pragma once

#include <vector>

#include "formats/format.h"

namespace blocklab {

std::vector<BlockProblem> bc6h_block_problems(bool is_signed);

}  // namespace blocklab
