// BC6H block <-> Params (bc6h_params.h): the mode bits, then each LayoutRun of the mode (bc6h_tables.cpp) in order,
// then the indices from bit 65 (one subset, 4 bits) or bit 82 (two subsets, 3 bits), texel order x + 4 y, each
// anchor with its top bit implicit (KDFS "BC6H": "Indices are read in the same way as the BC7 formats").
#include "formats/bc6h/bc6h_params.h"

#include <cstring>

#include "formats/bc7/bc7_tables.h"

namespace blocklab {
namespace bc6h {

namespace {

// Bit `position` of the block, LSB first (bit k is bit k % 8 of byte k / 8).
int get_bit(const std::uint8_t* bytes, int position) { return (bytes[position >> 3] >> (position & 7)) & 1; }
void put_bit(std::uint8_t* bytes, int position, int bit) {
  if (bit) bytes[position >> 3] = static_cast<std::uint8_t>(bytes[position >> 3] | (1u << (position & 7)));
}

}  // namespace

int field_bits(const ModeInfo& mode, int field) {
  if (field < 3 || !mode.transformed) return mode.endpoint_bits;
  return mode.delta_bits[field % 3];
}

bool is_anchor(int subset_count, int partition, int texel) {
  if (texel == 0) return true;
  return subset_count == 2 && texel == bc7::anchor_texel(2, partition, 1);
}

void pack(const Params& params, std::uint8_t* out) {
  std::memset(out, 0, kBlockBytes);
  if (params.mode_index == kReservedModeIndex) {
    out[0] = 19;   // a reserved mode number: decodes to 0
    return;
  }
  const ModeInfo& mode = mode_info(params.mode_index);
  int position = 0;
  for (int i = 0; i < mode.mode_bits; ++i) put_bit(out, position++, (mode.mode_number >> i) & 1);
  for (int r = 0; r < mode.run_count; ++r) {
    const LayoutRun& run = mode.runs[r];
    const int value = run.field == kPartitionField ? params.partition : params.fields[run.field];
    for (int i = 0; i < run.count; ++i) {
      const int source_bit = run.reversed ? run.first_bit - i : run.first_bit + i;
      put_bit(out, position++, (value >> source_bit) & 1);
    }
  }
  position = index_start_bit(mode.subset_count);
  const int width = index_bits(mode.subset_count);
  for (int texel = 0; texel < kTexels; ++texel) {
    const int stored = width - (is_anchor(mode.subset_count, params.partition, texel) ? 1 : 0);
    for (int i = 0; i < stored; ++i) put_bit(out, position++, (params.indices[texel] >> i) & 1);
  }
}

Params unpack(const std::uint8_t* bytes) {
  Params params;
  params.mode_index = mode_index_of_block(bytes);
  if (params.mode_index == kReservedModeIndex) return params;
  const ModeInfo& mode = mode_info(params.mode_index);
  int position = mode.mode_bits;
  for (int r = 0; r < mode.run_count; ++r) {
    const LayoutRun& run = mode.runs[r];
    int& value = run.field == kPartitionField ? params.partition : params.fields[run.field];
    for (int i = 0; i < run.count; ++i) {
      const int target_bit = run.reversed ? run.first_bit - i : run.first_bit + i;
      value |= get_bit(bytes, position++) << target_bit;
    }
  }
  position = index_start_bit(mode.subset_count);
  const int width = index_bits(mode.subset_count);
  for (int texel = 0; texel < kTexels; ++texel) {
    const int stored = width - (is_anchor(mode.subset_count, params.partition, texel) ? 1 : 0);
    int index = 0;
    for (int i = 0; i < stored; ++i) index |= get_bit(bytes, position++) << i;
    params.indices[texel] = static_cast<std::uint8_t>(index);
  }
  return params;
}

}  // namespace bc6h
}  // namespace blocklab
