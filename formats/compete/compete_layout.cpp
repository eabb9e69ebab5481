// The `compete` block layout (compete_layout.h, formats/compete/README.md "Block"): the family code, the dropped bits
// of each Munkberg mode, and the 128-bit shifts that remove / restore them.
#include "formats/compete/compete_layout.h"

#include <string>
#include <utility>

#include "core/error.h"
#include "formats/bc6h/bc6h_tables.h"
#include "formats/munkberg/dct_block.h"
#include "formats/munkberg/dct_tables.h"
#include "formats/munkberg/ext_s3tc_block.h"
#include "formats/munkberg/two_plane_block.h"

namespace blocklab::compete {

namespace {

using Bits128 = unsigned __int128;

Bits128 load(const std::uint8_t* bytes) {
  Bits128 value = 0;
  for (int i = kBlockBytes - 1; i >= 0; --i) value = (value << 8) | bytes[i];
  return value;
}

void store(Bits128 value, std::uint8_t* bytes) {
  for (int i = 0; i < kBlockBytes; ++i) bytes[i] = static_cast<std::uint8_t>(value >> (8 * i));
}

bool bit_of(Bits128 value, int position) { return ((value >> position) & 1u) != 0u; }

Bits128 low_bits(Bits128 value, int count) {
  return count == 0 ? 0 : (value & ((~Bits128{0}) >> (kBlockBits - count)));
}

// Removes bit `position`: the bits above move down by one.
Bits128 remove_bit(Bits128 value, int position) {
  return low_bits(value, position) | ((value >> (position + 1)) << position);
}

// Inserts `bit` at `position`: the bits from there up move up by one (the top bit falls off).
Bits128 insert_bit(Bits128 value, int position, bool bit) {
  return low_bits(value, position) | (Bits128{bit} << position) | ((value >> position) << (position + 1));
}

MunkbergBudget make_budget(munkberg::BlockMode mode, bool anchor, std::array<Field, 2> halved, int halved_count) {
  MunkbergBudget budget;
  budget.mode = mode;
  budget.luminance_anchor = anchor;
  budget.halved = halved;
  budget.halved_count = halved_count;
  int count = 0;
  for (int h = 0; h < halved_count; ++h) {
    if (halved[static_cast<std::size_t>(h)].width < 2)
      fail("compete", "a halved field of Munkberg mode " + std::to_string(static_cast<int>(mode)) + " has fewer than 2 bits");
    budget.dropped[static_cast<std::size_t>(count++)] = {halved[static_cast<std::size_t>(h)].position,
                                                         halved[static_cast<std::size_t>(h)].msb()};
  }
  if (anchor) budget.dropped[static_cast<std::size_t>(count++)] = {kShape2AnchorBit, -1};
  if (count != kDroppedBitsPerMode) fail("compete", "a Munkberg mode's budget must drop exactly 2 bits");
  if (budget.dropped[0].position > budget.dropped[1].position) std::swap(budget.dropped[0], budget.dropped[1]);
  return budget;
}

std::array<MunkbergBudget, kMunkbergModeCount> make_budgets() {
  using munkberg::BlockMode;
  using munkberg::Mode;
  // Base colour v1 / u1: the fourth / third 7-bit coordinate after the shape index (munkberg_layout.h).
  const auto base_coordinate = [](Mode mode, int coordinate) {
    return Field{munkberg::base_coordinate_position(mode) + coordinate * munkberg::kBaseCoordinateBits,
                 munkberg::kBaseCoordinateBits};
  };
  // Shape I: both log-luminance endpoints (8 bits), symmetric so its anchor swap stays exact.
  const auto luminance_endpoint = [](int endpoint) {
    return Field{munkberg::lum_endpoint_position(Mode::shape_i) + endpoint * munkberg::kLumEndpointBits,
                 munkberg::kLumEndpointBits};
  };
  // Extended S3TC: the third channel (7 bits) of each endpoint, symmetric so the anchor swap stays exact.
  const auto ext_third_channel = [](int endpoint) {
    return Field{munkberg::kExtS3tcEndpointPosition + endpoint * munkberg::kExtS3tcEndpointBits +
                     munkberg::kExtS3tcChannelBits[0] + munkberg::kExtS3tcChannelBits[1],
                 munkberg::kExtS3tcChannelBits[2]};
  };
  // Two-plane: each plane's 9-bit offset, symmetric so the mask anchor (plane swap) stays exact.
  const auto plane_offset = [](int plane) {
    return Field{munkberg::kTwoPlanePlanePosition + plane * munkberg::kPlaneBits, munkberg::kPlaneOffsetBits};
  };
  // DCT: the DC codes of Ybar and u (uniform quantisers; the first field of their channels).
  const munkberg::DctTables& tables = munkberg::default_dct_tables();
  const Field ybar_dc{munkberg::kDctSelectorBits, tables.channel[0].bits[0]};
  const Field u_dc{munkberg::kDctSelectorBits + munkberg::kDctChannelBudget[0], tables.channel[1].bits[0]};
  return {{
      make_budget(BlockMode::shape_ii, true, {base_coordinate(Mode::shape_ii, 3), Field{}}, 1),
      make_budget(BlockMode::shape_i, false, {luminance_endpoint(0), luminance_endpoint(1)}, 2),
      make_budget(BlockMode::ext_s3tc, false, {ext_third_channel(0), ext_third_channel(1)}, 2),
      make_budget(BlockMode::two_plane, false, {plane_offset(0), plane_offset(1)}, 2),
      make_budget(BlockMode::dct, false, {ybar_dc, u_dc}, 2),
  }};
}

}  // namespace

const MunkbergBudget& munkberg_budget(munkberg::BlockMode mode) {
  static const std::array<MunkbergBudget, kMunkbergModeCount> budgets = make_budgets();
  return budgets[static_cast<std::size_t>(mode)];
}

int block_mode_of(const std::uint8_t* bytes) {
  if (!is_munkberg_family(bytes)) return kBc6hFirstMode + bc6h::mode_index_of_block(bytes);
  // The Munkberg selector (at most 4 bits) starts at compete bit 2; no dropped bit lies below Munkberg bit 4.
  const std::uint8_t selector[kBlockBytes] = {static_cast<std::uint8_t>((bytes[0] >> kFamilyCodeBits) |
                                                                        (bytes[1] << (8 - kFamilyCodeBits)))};
  return static_cast<int>(munkberg::block_mode_of(selector));
}

bool representable(const std::uint8_t* munkberg_bytes) {
  const Bits128 block = load(munkberg_bytes);
  for (const DroppedBit& dropped : munkberg_budget(munkberg::block_mode_of(munkberg_bytes)).dropped) {
    const bool expected = dropped.copy_from >= 0 && bit_of(block, dropped.copy_from);
    if (bit_of(block, dropped.position) != expected) return false;
  }
  return true;
}

void pack_munkberg_block(const std::uint8_t* munkberg_bytes, std::uint8_t* out) {
  const munkberg::BlockMode mode = munkberg::block_mode_of(munkberg_bytes);
  const MunkbergBudget& budget = munkberg_budget(mode);
  Bits128 block = load(munkberg_bytes);
  for (const DroppedBit& dropped : budget.dropped) {
    const bool expected = dropped.copy_from >= 0 && bit_of(block, dropped.copy_from);
    if (bit_of(block, dropped.position) != expected)
      fail("compete", "Munkberg mode " + std::to_string(static_cast<int>(mode)) + ": bit " +
                          std::to_string(dropped.position) + " must be " + (expected ? "1" : "0") +
                          (dropped.copy_from >= 0 ? " (a copy of bit " + std::to_string(dropped.copy_from) + ")"
                                                  : std::string(" (anchor)")) +
                          " to be stored");
  }
  // Highest position first, so the lower one keeps its place.
  block = remove_bit(block, budget.dropped[1].position);
  block = remove_bit(block, budget.dropped[0].position);
  store((block << kFamilyCodeBits) | kMunkbergFamilyCode, out);
}

void unpack_munkberg_block(const std::uint8_t* bytes, std::uint8_t* munkberg_out) {
  if (!is_munkberg_family(bytes)) fail("compete", "the block is not of the Munkberg family (bits 0, 1 are not 1, 1)");
  Bits128 block = load(bytes) >> kFamilyCodeBits;
  std::uint8_t selector[kBlockBytes];
  store(block, selector);
  const MunkbergBudget& budget = munkberg_budget(munkberg::block_mode_of(selector));
  // Lowest position first (each insertion shifts the bits above it into place); then the copies of the MSBs.
  block = insert_bit(block, budget.dropped[0].position, false);
  block = insert_bit(block, budget.dropped[1].position, false);
  for (const DroppedBit& dropped : budget.dropped)
    if (dropped.copy_from >= 0 && bit_of(block, dropped.copy_from)) block |= Bits128{1} << dropped.position;
  store(block, munkberg_out);
}

}  // namespace blocklab::compete
