// The `munkberg` block modes as plug-ins (Munkberg et al. 2008, sections 5 and 6): the paper's shape II and shape I
// and the rejected modes of section 6 (extended S3TC, fixed-rate DCT, two-plane luminance), each a block model of its own
// (pack/unpack, templated decode, reference decode, encoder in its own files), registered here in one table the
// format, the encoder's competition and the tests iterate. Adding a mode: docs/adding-a-mode.md.
//
// The 128-bit block starts with the mode selector (a complete prefix code, munkberg_layout.h), so any 16 bytes are a
// block of exactly one mode, and the encoder tries every enabled mode and keeps the lowest log2[RGB] error (§6:
// "each of the compression modes is tested, and the one with the smallest error in the chosen metric (we use
// log[RGB] error) is selected"; ties keep the mode listed first).
#pragma once

#include <array>
#include <optional>
#include <cstdint>
#include <string>
#include <vector>

#include "core/blocks.h"
#include "formats/format.h"
#include "formats/munkberg/dct_tables.h"
#include "formats/munkberg/ext_s3tc_block.h"
#include "formats/munkberg/munkberg_encoder.h"
#include "formats/munkberg/munkberg_layout.h"
#include "formats/munkberg/munkberg_shapes.h"
#include "formats/munkberg/two_plane_block.h"

namespace blocklab::munkberg {

// Texture-level data every mode's decoder may need (from side data) and the encoder's settings.
struct ModeContext {
  ShapeSet shapes = default_shape_set();
  ExtS3tcSpace ext_s3tc_space = ExtS3tcSpace::rgb;
  EncoderSettings settings;
  // The DCT mode's tables; nullptr = the compiled-in ones (parsed on first use, so contexts that never meet a DCT
  // block never parse them).
  const DctTables* dct_tables = nullptr;
  const DctTables& dct() const { return dct_tables != nullptr ? *dct_tables : default_dct_tables(); }
};

// Per-block work the modes of one competition may share (filled by the first mode that computes it).
struct BlockScratch {
  ShapeSolveCache shape_i_solves;   // shape I's 8 shape solves (shape_i and two_plane)
  ChromaWorkspace* workspace = nullptr;   // the worker's chroma search buffers (nullptr: each search makes its own)
  // The shape modes' luminance fits (index: Mode), when the mode bound already computed them.
  std::array<std::optional<LuminanceFit>, 2> luminance;
  // two_plane's luminance planes and mask, when its bound already computed them.
  std::optional<TwoPlaneParams> two_plane_luminance;
  // The source block's analysis for the shape modes (munkberg_encoder.h), made on first use.
  std::optional<BlockAnalysis> analysis;
  const BlockAnalysis& analysis_of(const BlockTexels& texels) {
    if (!analysis) analysis = analyse_block(texels);
    return *analysis;
  }
};

struct BlockModeModel {
  BlockMode mode;
  const char* name;         // Format::modes() entry and `modes` option token
  const char* description;  // one line, citing the paper's section (Format::mode_table())
  int selector_bits;        // the selector's length and value (munkberg_layout.h)
  unsigned selector;
  // Every field's width in layout order, selector first; the sum must be 128 (tested).
  std::vector<int> (*field_widths)();
  BlockTexels (*decode)(const std::uint8_t* bytes, const ModeContext& context);
  BlockTexels (*reference_decode)(const std::uint8_t* bytes, const ModeContext& context);
  // pack(unpack(in)) into out: must give back `in` for every block of the mode.
  void (*repack)(const std::uint8_t* in, std::uint8_t* out);
  // Encodes `texels` in this mode into out; returns the block's log2[RGB] error (eq. 1, per-block sum). `scratch` is
  // per block and shared by the modes of one competition (e.g. shape solves both shape I and two_plane use).
  double (*encode)(const BlockTexels& texels, const ModeContext& context, std::uint64_t block_seed,
                   BlockScratch* scratch, std::uint8_t* out);
};

// All modes, in BlockMode order (= Format::modes() order, the block_modes index).
const std::array<BlockModeModel, kBlockModeCount>& block_mode_models();
const BlockModeModel& block_mode_model(BlockMode mode);
// The format's mode table (Format::mode_table()): name and description of every model, in BlockMode order.
std::vector<ModeSpec> mode_table();

// Parses the `modes` option: a comma-separated list of mode names, or `both` (shape_ii,shape_i, the paper's format),
// `all` (every mode). Error naming the unknown token and the valid ones.
ModeMask parse_mode_list(const std::string& text);

// Decodes any block (dispatch on the selector) / the same through each mode's reference decoder.
BlockTexels decode_any_block(const std::uint8_t* bytes, const ModeContext& context);
BlockTexels reference_decode_any_block(const std::uint8_t* bytes, const ModeContext& context);

// The competition: every enabled mode of context.settings.modes encodes the block, the lowest log2[RGB] error wins
// (strict: ties keep the earlier mode), unless a skip rule (EncoderSettings: skip_mode_bound exact; good_enough and
// mode_predictor approximate) shows that a mode cannot or is not expected to win. Writes the winner's 16 bytes; returns its mode; `error` gets its error.
// `workspace` (optional): the worker's chroma search buffers, one per thread of the block loop.
BlockMode encode_best_block(const BlockTexels& texels, const ModeContext& context, std::uint64_t block_seed,
                            std::uint8_t* out, double* error = nullptr, ChromaWorkspace* workspace = nullptr);

}  // namespace blocklab::munkberg
