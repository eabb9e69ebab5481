// Real blocks for the format tables' block problems (experiments/block_samples.h).
#include "experiments/block_samples.h"

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <map>

#include "core/error.h"
#include "core/image_io.h"
#include "core/input_policy.h"
#include "solvers/seeding.h"

namespace blocklab {

namespace {

bool is_image_file(const std::filesystem::path& path) {
  std::string ext = path.extension().string();
  for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return ext == ".png" || ext == ".exr" || ext == ".hdr" || ext == ".pfm";
}

}  // namespace

std::vector<std::string> image_files(const std::string& folder) {
  std::error_code error;
  if (!std::filesystem::is_directory(folder, error)) fail(folder, "not a folder (check --data-root)");
  std::vector<std::string> files;
  for (const auto& entry : std::filesystem::recursive_directory_iterator(folder))
    if (entry.is_regular_file() && is_image_file(entry.path())) files.push_back(entry.path().string());
  std::sort(files.begin(), files.end());
  if (files.empty()) fail(folder, "holds no image (.png .exr .hdr .pfm)");
  return files;
}

std::string block_image_folder(const std::string& root, BlockImageKind kind) {
  return root + (kind == BlockImageKind::hdr ? "/hdr" : "/ldr");
}

std::vector<SampledBlock> sample_blocks(const std::vector<std::string>& files, int count, std::uint64_t stream_seed) {
  std::map<std::size_t, Image> loaded;
  RandomStream random(stream_seed);
  std::vector<SampledBlock> blocks;
  for (int b = 0; b < count; ++b) {
    const std::size_t which = static_cast<std::size_t>(random.uniform_index(files.size()));
    auto found = loaded.find(which);
    if (found == loaded.end()) {
      Image image = read_image(files[which]);
      apply_input_policy(image, InputPolicy::clamp, files[which]);
      found = loaded.emplace(which, std::move(image)).first;
    }
    const Image& image = found->second;
    const int blocks_x = image.width / 4, blocks_y = image.height / 4;
    // Images smaller than one block cannot give a whole block.
    if (blocks_x == 0 || blocks_y == 0) fail(files[which], "is smaller than one 4x4 block");
    const int bx = static_cast<int>(random.uniform_index(static_cast<std::uint64_t>(blocks_x)));
    const int by = static_cast<int>(random.uniform_index(static_cast<std::uint64_t>(blocks_y)));
    SampledBlock block;
    block.source = files[which] + " (" + std::to_string(4 * bx) + ", " + std::to_string(4 * by) + ")";
    for (int t = 0; t < kBlockTexels; ++t) {
      const float* texel = image.texel(4 * bx + t % 4, 4 * by + t / 4);
      for (int c = 0; c < 4; ++c) block.texels.rgba[t][c] = texel[c];
    }
    blocks.push_back(block);
  }
  return blocks;
}

std::uint64_t block_problem_stream_seed(std::uint64_t seed, const std::string& full_name) {
  std::uint64_t hash = 14695981039346656037ull;   // FNV-1a, 64 bits
  for (const char c : full_name) {
    hash ^= static_cast<unsigned char>(c);
    hash *= 1099511628211ull;
  }
  return derive_stream_seed(seed, hash);
}

std::vector<DrawnProblem> draw_block_problems(const RegisteredBlockProblem& entry,
                                              const std::vector<std::string>& files, int count, std::uint64_t seed) {
  const std::uint64_t stream_seed = block_problem_stream_seed(seed, entry.full_name());
  std::vector<DrawnProblem> drawn;
  const std::vector<SampledBlock> blocks = sample_blocks(files, count, stream_seed);
  for (std::size_t b = 0; b < blocks.size(); ++b)
    drawn.push_back({entry.problem.make(blocks[b].texels, derive_stream_seed(stream_seed, b)), blocks[b].source});
  return drawn;
}

}  // namespace blocklab
