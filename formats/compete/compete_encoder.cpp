// The `compete` block encoder (compete_encoder.h; formats/compete/README.md "Encoder").
#include "formats/compete/compete_encoder.h"

#include <algorithm>
#include <cstring>
#include <vector>

#include "formats/bc6h/bc6h_endpoint_fit.h"
#include "formats/bc6h/bc6h_params.h"
#include "formats/compete/compete_block.h"
#include "formats/munkberg/ext_s3tc_block.h"
#include "formats/munkberg/two_plane_block.h"

namespace blocklab::compete {

namespace {

int read_field(const std::uint8_t* bytes, Field field) {
  int value = 0;
  for (int b = field.width - 1; b >= 0; --b) {
    const int k = field.position + b;
    value = (value << 1) | ((bytes[k / 8] >> (k % 8)) & 1);
  }
  return value;
}

void write_field(std::uint8_t* bytes, Field field, int value) {
  for (int b = 0; b < field.width; ++b) {
    const int k = field.position + b;
    const auto mask = static_cast<std::uint8_t>(1u << (k % 8));
    bytes[k / 8] = static_cast<std::uint8_t>(((value >> b) & 1) ? (bytes[k / 8] | mask) : (bytes[k / 8] & ~mask));
  }
}

// The w-bit code a halved field decodes to from its stored (w - 1)-bit value s: bit replication.
int replicated_code(int stored, int width) { return (stored << 1) | (stored >> (width - 2)); }

// The index fields re-chosen after the halved fields moved (the texels' choices among the decoded palette).
std::vector<Field> refit_fields(munkberg::BlockMode mode) {
  using munkberg::BlockMode;
  std::vector<Field> fields;
  switch (mode) {
    case BlockMode::shape_ii:
      // Texel 0's index only in its low 3 bits: its MSB is the anchor bit, 0.
      fields.push_back({munkberg::lum_index_position(munkberg::Mode::shape_ii), munkberg::kShape2LumIndexBits - 1});
      for (int t = 1; t < munkberg::kTexels; ++t)
        fields.push_back({munkberg::lum_index_position(munkberg::Mode::shape_ii) + t * munkberg::kShape2LumIndexBits,
                          munkberg::kShape2LumIndexBits});
      for (int g = 0; g < munkberg::kShape2ChromaGroups; ++g)
        fields.push_back({munkberg::kShape2ChromaIndexPosition + g * munkberg::kChromaIndexBits, munkberg::kChromaIndexBits});
      break;
    case BlockMode::shape_i:
      fields.push_back({munkberg::lum_index_position(munkberg::Mode::shape_i), munkberg::kShape1AnchorIndexBits});
      for (int t = 1; t < munkberg::kTexels; ++t)
        fields.push_back({munkberg::lum_index_position(munkberg::Mode::shape_i) + munkberg::kShape1AnchorIndexBits +
                              (t - 1) * munkberg::kShape1LumIndexBits,
                          munkberg::kShape1LumIndexBits});
      for (int t = 0; t < munkberg::kTexels; ++t)
        fields.push_back({munkberg::kShape1ChromaIndexPosition + t * munkberg::kChromaIndexBits, munkberg::kChromaIndexBits});
      break;
    case BlockMode::ext_s3tc:
      fields.push_back({munkberg::kExtS3tcIndexPosition, munkberg::kExtS3tcAnchorIndexBits});
      for (int t = 1; t < munkberg::kTexels; ++t)
        fields.push_back({munkberg::kExtS3tcIndexPosition + munkberg::kExtS3tcAnchorIndexBits +
                              (t - 1) * munkberg::kExtS3tcIndexBits,
                          munkberg::kExtS3tcIndexBits});
      break;
    case BlockMode::two_plane:
      for (int t = 1; t < munkberg::kTexels; ++t) fields.push_back({munkberg::kTwoPlaneMaskPosition + t - 1, 1});
      break;
    case BlockMode::dct:   // no per-texel choices: every code is a coefficient
      break;
  }
  return fields;
}

const std::vector<Field>& refit_fields_of(munkberg::BlockMode mode) {
  static const std::array<std::vector<Field>, kMunkbergModeCount> table = [] {
    std::array<std::vector<Field>, kMunkbergModeCount> fields;
    for (int m = 0; m < kMunkbergModeCount; ++m) fields[static_cast<std::size_t>(m)] = refit_fields(static_cast<munkberg::BlockMode>(m));
    return fields;
  }();
  return table[static_cast<std::size_t>(mode)];
}

// Shape II's anchor orientation: texel 0's luminance index <= 7, else swap Y0 <-> Y1 and l -> 15 - l (q = (15 - l)
// e0 + l e1 is symmetric, so the texels decode identically).
void canonicalize_shape_ii_anchor(std::uint8_t* bytes) {
  using munkberg::Mode;
  const int index_position = munkberg::lum_index_position(Mode::shape_ii);
  const Field texel0{index_position, munkberg::kShape2LumIndexBits};
  if (read_field(bytes, texel0) <= munkberg::lum_levels_minus_one(Mode::shape_ii) / 2) return;
  const Field y0{munkberg::lum_endpoint_position(Mode::shape_ii), munkberg::kLumEndpointBits};
  const Field y1{y0.position + munkberg::kLumEndpointBits, munkberg::kLumEndpointBits};
  const int e0 = read_field(bytes, y0), e1 = read_field(bytes, y1);
  write_field(bytes, y0, e1);
  write_field(bytes, y1, e0);
  for (int t = 0; t < munkberg::kTexels; ++t) {
    const Field index{index_position + t * munkberg::kShape2LumIndexBits, munkberg::kShape2LumIndexBits};
    write_field(bytes, index, munkberg::lum_levels_minus_one(Mode::shape_ii) - read_field(bytes, index));
  }
}

double error_of(const munkberg::TexelLog2& source_log2, const munkberg::ModeContext& context,
                const std::uint8_t* munkberg_bytes) {
  return munkberg::block_log2_error(source_log2, munkberg::decode_any_block(munkberg_bytes, context));
}

double error_of_compete(const munkberg::TexelLog2& source_log2, const munkberg::ModeContext& context,
                        const std::uint8_t* bytes) {
  return munkberg::block_log2_error(source_log2, decode_block(bytes, context));
}

}  // namespace

double fit_to_budget(const munkberg::TexelLog2& source_log2, const munkberg::ModeContext& context, int refit_passes,
                     std::uint8_t* munkberg_bytes) {
  const munkberg::BlockMode mode = munkberg::block_mode_of(munkberg_bytes);
  const MunkbergBudget& budget = munkberg_budget(mode);
  if (budget.luminance_anchor) canonicalize_shape_ii_anchor(munkberg_bytes);

  // Each halved field: the stored values next to its code (s = v >> 1 first, then s - 1, s + 1), every combination.
  std::array<std::array<int, 3>, 2> candidates{};
  std::array<int, 2> candidate_count{};
  for (int h = 0; h < budget.halved_count; ++h) {
    const Field field = budget.halved[static_cast<std::size_t>(h)];
    const int stored_max = (1 << (field.width - 1)) - 1;
    const int middle = read_field(munkberg_bytes, field) >> 1;
    for (const int s : {middle, middle - 1, middle + 1})
      if (s >= 0 && s <= stored_max)
        candidates[static_cast<std::size_t>(h)][static_cast<std::size_t>(candidate_count[static_cast<std::size_t>(h)]++)] = s;
  }
  std::uint8_t best[kBlockBytes] = {};
  double best_error = 0.0;
  bool have_best = false;
  const int second_count = budget.halved_count > 1 ? candidate_count[1] : 1;
  for (int a = 0; a < candidate_count[0]; ++a)
    for (int b = 0; b < second_count; ++b) {
      std::uint8_t trial[kBlockBytes];
      std::memcpy(trial, munkberg_bytes, kBlockBytes);
      const std::array<int, 2> pick = {a, b};
      for (int h = 0; h < budget.halved_count; ++h) {
        const Field field = budget.halved[static_cast<std::size_t>(h)];
        write_field(trial, field,
                    replicated_code(candidates[static_cast<std::size_t>(h)][static_cast<std::size_t>(pick[static_cast<std::size_t>(h)])], field.width));
      }
      const double error = error_of(source_log2, context, trial);
      if (!have_best || error < best_error) {
        std::memcpy(best, trial, kBlockBytes);
        best_error = error;
        have_best = true;
      }
    }
  std::memcpy(munkberg_bytes, best, kBlockBytes);

  // Coordinate descent over the index fields: 1- and 2-bit fields try every value, wider ones the two codes either side.
  for (int pass = 0; pass < refit_passes; ++pass) {
    bool improved = false;
    for (const Field& field : refit_fields_of(mode)) {
      const int current = read_field(munkberg_bytes, field);
      const int top = (1 << field.width) - 1;
      const int low = field.width <= 2 ? 0 : std::max(0, current - 2);
      const int high = field.width <= 2 ? top : std::min(top, current + 2);
      int best_value = current;
      for (int value = low; value <= high; ++value) {
        if (value == current) continue;
        write_field(munkberg_bytes, field, value);
        const double error = error_of(source_log2, context, munkberg_bytes);
        if (error < best_error) {
          best_error = error;
          best_value = value;
          improved = true;
        }
      }
      write_field(munkberg_bytes, field, best_value);
    }
    if (!improved) break;
  }
  return best_error;
}

BlockChoice encode_block(const BlockTexels& texels, const EncoderSettings& settings, std::uint64_t block_seed,
                         munkberg::ChromaWorkspace* workspace, std::uint8_t* out) {
  const munkberg::TexelLog2 source_log2 = munkberg::texel_log2(texels);
  BlockChoice best;
  bool have_best = false;
  const auto done = [&] { return have_best && best.error <= settings.good_enough; };

  if (settings.bc6h_family) {
    const bc6h::BlockTarget target = bc6h::make_block_target(texels.rgba, false);
    const bc6h::EncodedBlock encoded = bc6h::encode_block(target, settings.bc6h);
    bc6h::pack(encoded.params, out);
    best = {kBc6hFirstMode + encoded.params.mode_index, error_of_compete(source_log2, settings.munkberg, out)};
    have_best = true;
  }

  munkberg::BlockScratch scratch;
  scratch.workspace = workspace;
  for (const munkberg::BlockModeModel& model : munkberg::block_mode_models()) {
    const int mode = static_cast<int>(model.mode);
    if (!settings.munkberg_modes[static_cast<std::size_t>(mode)] || done()) continue;
    if (family_of_mode(mode) == Family::shape) {
      // Exact skip rule: the shape modes' lower bound holds whatever the chroma, and the budget changes only chroma
      // (and shape II's luminance orientation, which decodes identically). A mode whose bound reaches the best error
      // cannot win (ties keep the earlier).
      const munkberg::Mode shape =
          model.mode == munkberg::BlockMode::shape_ii ? munkberg::Mode::shape_ii : munkberg::Mode::shape_i;
      munkberg::LuminanceFit luminance;
      const double bound = munkberg::shape_mode_lower_bound(texels, scratch.analysis_of(texels), shape,
                                                            settings.munkberg.settings, &luminance);
      scratch.luminance[static_cast<std::size_t>(shape)] = luminance;   // the mode's encode reuses it
      if (have_best && bound >= best.error) continue;
    }
    std::uint8_t munkberg_block[kBlockBytes];
    model.encode(texels, settings.munkberg, block_seed, &scratch, munkberg_block);
    const double error = fit_to_budget(source_log2, settings.munkberg, settings.refit_passes, munkberg_block);
    if (!have_best || error < best.error) {
      pack_munkberg_block(munkberg_block, out);
      best = {mode, error};
      have_best = true;
    }
  }
  return best;
}

}  // namespace blocklab::compete
