// The S3TC endpoint Problems (s3tc_endpoint_problem.h) drawn from one real 4x4 block, shared by the block-problem
// tables of bc1, bc3 and bc4 (formats/<name>/<name>_problems.cpp, Format::block_problems()).
#pragma once

#include <memory>

#include "core/blocks.h"
#include "core/problem.h"
#include "formats/common/s3tc_common.h"

namespace blocklab {

// BC1 / BC3 colour endpoints in `mode` with unit channel weights; targets are the block's RGB clamped to [0, 1]
// (PNG code values already are; the clamp only guards other inputs).
std::unique_ptr<Problem> make_bc1_block_problem(const BlockTexels& block, Bc1Mode mode);
// BC4 / BC3 alpha endpoints in `mode`; targets are channel `channel` (0 red .. 3 alpha) clamped to [0, 1].
std::unique_ptr<Problem> make_bc4_block_problem(const BlockTexels& block, int channel, Bc4Mode mode);

}  // namespace blocklab
