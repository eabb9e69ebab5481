// Real 4x4 blocks for the block problems of the format tables (formats/format.h BlockProblem): the image files of a
// data root's ldr/ or hdr/ folder, blocks drawn from them by a seeded stream, and the Problems of a registered
// block problem on those blocks. Used by `blocklab bench solvers` (experiments/solver_bench.h) and by the contract
// and interval-soundness tests, so all of them see the same blocks for the same (seed, data root).
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "core/blocks.h"
#include "core/problem.h"
#include "formats/registry.h"

namespace blocklab {

// Every image file (.png .exr .hdr .pfm) below `folder`, sorted by path (the order the seeded sampling indexes).
// Throws Error naming the folder when it is missing or holds no image.
std::vector<std::string> image_files(const std::string& folder);

// <root>/ldr or <root>/hdr.
std::string block_image_folder(const std::string& root, BlockImageKind kind);

struct SampledBlock {
  BlockTexels texels;   // after the clamp input policy (finite, >= 0); alpha 1 for images without alpha
  std::string source;   // "file (x, y)"
};

// Draws `count` blocks: per block an image uniformly, then a whole 4x4 block of it uniformly, from a SplitMix64
// stream seeded with `stream_seed`. Images are loaded on first use and kept (the data sets are small). Throws Error
// naming an image smaller than one block.
std::vector<SampledBlock> sample_blocks(const std::vector<std::string>& files, int count, std::uint64_t stream_seed);

// The stream seed of a block problem: derive_stream_seed(seed, FNV-1a of its full name), so adding a problem to a
// table does not move the blocks of the others.
std::uint64_t block_problem_stream_seed(std::uint64_t seed, const std::string& full_name);

struct DrawnProblem {
  std::unique_ptr<Problem> problem;
  std::string source;   // the block's "file (x, y)"
};

// `count` Problems of `entry`, one per block sampled from `files` with block_problem_stream_seed(seed, name);
// block b's Problem gets seed derive_stream_seed(stream seed, b).
std::vector<DrawnProblem> draw_block_problems(const RegisteredBlockProblem& entry,
                                              const std::vector<std::string>& files, int count, std::uint64_t seed);

}  // namespace blocklab
