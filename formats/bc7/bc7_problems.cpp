// The `bc7` block problem: the subset endpoint search of bc7_endpoint_problem.h (Khronos Data Format Spec, BPTC)
// on a real LDR block. The block's seed draws what the mode search would try: one of the modes that fit every
// subset on all its stored lanes with one index set (0, 1, 2, 3, 6, 7), a partition of it, and the partition's
// subset 0; the lattice, P-bit kind and lane weights are those bc7_mode_search.cpp gives that mode (alpha weighs 0
// when the block is opaque or the mode stores no alpha), and the indices and P-bits are fixed from the builtin fit
// (fit_subset) of the subset's texels, as the Problem's header describes.
#include "formats/bc7/bc7_problems.h"

#include <algorithm>
#include <array>
#include <cmath>

#include "formats/bc7/bc7_endpoint_problem.h"
#include "formats/bc7/bc7_tables.h"
#include "solvers/seeding.h"

namespace blocklab {

namespace {

constexpr std::array<int, 6> kSingleIndexSetModes = {0, 1, 2, 3, 6, 7};

std::unique_ptr<Problem> make_subset_problem(const BlockTexels& block, std::uint64_t seed) {
  RandomStream random(seed);
  const int mode = kSingleIndexSetModes[static_cast<std::size_t>(random.uniform_index(kSingleIndexSetModes.size()))];
  const bc7::ModeInfo& info = bc7::mode_info(mode);
  const int partition = static_cast<int>(random.uniform_index(std::uint64_t{1} << info.partition_bits));
  float members[kBlockTexels][4];
  int count = 0;
  bool opaque = true;
  const std::uint8_t* subsets = bc7::partition_subsets(info.subset_count, partition);
  for (int t = 0; t < kBlockTexels; ++t) {
    // Code values 0..255, as the encoder sees them (round of the clamped [0, 1] value).
    float code[4];
    for (int c = 0; c < 4; ++c) code[c] = std::round(std::clamp(block.rgba[t][c], 0.0f, 1.0f) * 255.0f);
    if (code[3] != 255.0f) opaque = false;
    if (subsets[t] == 0) std::copy(code, code + 4, members[count++]);
  }
  bc7::SubsetFitSettings settings;
  settings.index_bits = info.index_bits;
  settings.lattice.lane_bits[0] = settings.lattice.lane_bits[1] = settings.lattice.lane_bits[2] = info.color_bits;
  settings.lattice.lane_bits[3] = info.alpha_bits;
  settings.lattice.pbit = info.endpoint_pbits ? bc7::PbitKind::per_endpoint
                                              : (info.shared_pbits ? bc7::PbitKind::shared : bc7::PbitKind::none);
  settings.lattice.force_pbit_one = opaque && info.alpha_bits > 0 && settings.lattice.pbit != bc7::PbitKind::none;
  if (info.alpha_bits == 0 || opaque) settings.weights[3] = 0.0f;
  const bc7::SubsetFit fit = bc7::fit_subset(members, count, settings);
  const std::uint8_t pbits[2] = {fit.endpoints.pbits[0], fit.endpoints.pbits[1]};
  return std::make_unique<ErrorProblem<bc7::SubsetEndpointError>>(
      bc7::make_subset_endpoint_problem(members, count, settings, fit.indices, pbits));
}

}  // namespace

std::vector<BlockProblem> bc7_block_problems() {
  return {{"subset_endpoints",
           "stored endpoint codes of one subset (8 parameters, RGBA x 2), indices and P-bits fixed from the builtin "
           "fit, relaxed decoder error; mode 0-3, 6 or 7 and the partition drawn per block",
           BlockImageKind::ldr, make_subset_problem}};
}

}  // namespace blocklab
