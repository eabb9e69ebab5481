// Packing and unpacking of one BC7 block: symbolic Params <-> 16 bytes (KDFS "BPTC", table-bptcmodebits; field
// order and anchor rule in SPECS.md 2.3). Both directions walk the same field list in the same order, so
// pack(unpack(b)) == b for every non-reserved block b.
#include "formats/bc7/bc7_params.h"

#include <cstring>
#include <string>
#include <type_traits>

#include "core/bits.h"
#include "core/error.h"

namespace blocklab {
namespace bc7 {

namespace {

constexpr const char* kPackWhere = "bc7::pack";

// Visits every field of a block of mode `mode` in bit order, calling field(name, reference-to-value, width).
// The same walk serves reading and writing; `Value` is int for header fields and std::uint8_t elsewhere.
template <typename Params_, typename Visitor>
void visit_fields(Params_& params, Visitor&& field) {
  const ModeInfo& info = mode_info(params.mode);
  field("partition", params.partition, info.partition_bits);
  field("rotation", params.rotation, info.rotation_bits);
  field("index selection", params.index_selection, info.index_selection_bits);
  const int endpoint_count = 2 * info.subset_count;
  // Colour endpoints: all R, then all G, then all B, each in subset-major, endpoint-minor order.
  for (int channel = 0; channel < 3; ++channel)
    for (int e = 0; e < endpoint_count; ++e)
      field("colour endpoint", params.endpoints[e / 2][e % 2][channel], info.color_bits);
  for (int e = 0; e < endpoint_count && info.alpha_bits > 0; ++e)
    field("alpha endpoint", params.endpoints[e / 2][e % 2][3], info.alpha_bits);
  if (info.endpoint_pbits)
    for (int e = 0; e < endpoint_count; ++e) field("P-bit", params.pbits[e / 2][e % 2], 1);
  if (info.shared_pbits)
    for (int subset = 0; subset < info.subset_count; ++subset) field("shared P-bit", params.pbits[subset][0], 1);
  // Index fields: one bit less at the anchor texel of each subset (its implicit most significant bit is 0).
  const std::uint8_t* subsets = partition_subsets(info.subset_count, params.partition);
  for (int texel = 0; texel < kTexels; ++texel) {
    const bool anchor = texel == anchor_texel(info.subset_count, params.partition, subsets[texel]);
    field(anchor ? "anchor index" : "index", params.indices[texel], info.index_bits - (anchor ? 1 : 0));
  }
  for (int texel = 0; texel < kTexels && info.index2_bits > 0; ++texel)
    field(texel == 0 ? "anchor secondary index" : "secondary index", params.indices2[texel],
          info.index2_bits - (texel == 0 ? 1 : 0));
}

}  // namespace

bool operator==(const Params& a, const Params& b) {
  return a.mode == b.mode && a.partition == b.partition && a.rotation == b.rotation &&
         a.index_selection == b.index_selection && std::memcmp(a.endpoints, b.endpoints, sizeof a.endpoints) == 0 &&
         std::memcmp(a.pbits, b.pbits, sizeof a.pbits) == 0 && std::memcmp(a.indices, b.indices, sizeof a.indices) == 0 &&
         std::memcmp(a.indices2, b.indices2, sizeof a.indices2) == 0;
}

void pack(const Params& params, std::uint8_t* bytes) {
  if (params.mode < 0 || params.mode >= kModeCount)
    fail(kPackWhere, "mode " + std::to_string(params.mode) + " is not 0..7 (the reserved mode is never written)");
  const ModeInfo& info = mode_info(params.mode);
  if (params.partition < 0 || params.partition >= (1 << info.partition_bits))
    fail(kPackWhere, "mode " + std::to_string(params.mode) + " partition " + std::to_string(params.partition) +
                         " does not fit in " + std::to_string(info.partition_bits) + " bits");
  if (info.shared_pbits)
    for (int subset = 0; subset < info.subset_count; ++subset)
      // Mode 1 stores one P-bit per subset: the two endpoint entries must agree.
      if (params.pbits[subset][0] != params.pbits[subset][1])
        fail(kPackWhere, "mode 1 subset " + std::to_string(subset) + " has different P-bits for its two endpoints "
                                                                     "(mode 1 shares one P-bit per subset)");
  BitWriter128 writer;
  writer.write(std::uint64_t{1} << params.mode, params.mode + 1);   // mode m: m zero bits, then a one
  visit_fields(params, [&](const char* name, auto& value, int width) {
    const long long v = static_cast<long long>(value);
    if (v < 0 || v >= (1LL << width))
      fail(kPackWhere, std::string("mode ") + std::to_string(params.mode) + " " + name + " value " +
                           std::to_string(v) + " does not fit in " + std::to_string(width) + " bits");
    writer.write(static_cast<std::uint64_t>(v), width);
  });
  // Every mode's fields add up to exactly 128 bits.
  if (!writer.full()) fail(kPackWhere, "internal: mode " + std::to_string(params.mode) + " fields do not fill 128 bits");
  writer.to_bytes(bytes);
}

Params unpack(const std::uint8_t* bytes) {
  Params params;
  params.mode = mode_of_first_byte(bytes[0]);
  if (params.mode == kReservedMode) return params;   // reserved: nothing else is defined
  BitReader128 reader(bytes);
  reader.seek(params.mode + 1);
  visit_fields(params, [&](const char*, auto& value, int width) {
    value = static_cast<std::remove_reference_t<decltype(value)>>(reader.read(width));
  });
  const ModeInfo& info = mode_info(params.mode);
  if (info.shared_pbits)
    for (int subset = 0; subset < info.subset_count; ++subset) params.pbits[subset][1] = params.pbits[subset][0];
  return params;
}

int expanded_endpoint(const Params& params, int subset, int endpoint, int channel) {
  const ModeInfo& info = mode_info(params.mode);
  const int stored_bits = channel == 3 ? info.alpha_bits : info.color_bits;
  // Modes 0-3 store no alpha: the spec's alpha is 1.0 (255).
  if (stored_bits == 0) return 255;
  const int code = params.endpoints[subset][endpoint][channel];
  const bool has_pbit = info.endpoint_pbits || info.shared_pbits;
  if (!has_pbit) return expand_endpoint(code, stored_bits);
  return expand_endpoint((code << 1) | params.pbits[subset][endpoint], stored_bits + 1);
}

}  // namespace bc7
}  // namespace blocklab
