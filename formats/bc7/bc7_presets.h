// BC7 encoder options and the named presets (fast | medium | thorough; `default` is an alias of medium).
//
// A preset (formats/format.h FormatPreset, expanded by resolve_format_options) fills the knobs the user did not set:
// modes, alpha_modes, partitions_to_refine, refine_iterations, pbit_search, rotation_search; the resolved map has
// every knob explicit. expand_bc7_options() writes the mode lists and weights canonically; the encoder stores that
// map in EncodedTexture::options, so results and cache keys record the settings that were really used.
#pragma once

#include <vector>

#include "formats/bc7/bc7_mode_search.h"
#include "formats/format.h"

namespace blocklab {
namespace bc7 {

// The format's own option specs (the common ones are appended by resolve_format_options).
std::vector<OptionSpec> option_specs();
// fast, medium, thorough: the only place preset values live.
std::vector<FormatPreset> presets();

// Canonicalises the mode lists ("6, 1" -> "1,6") and weights of a resolved option map. Throws Error naming the
// option on a malformed mode list or weights.
FormatOptions expand_bc7_options(const FormatOptions& resolved);

// Encoder settings from an expanded option map (expand_bc7_options first).
EncoderSettings encoder_settings(const FormatOptions& expanded);

}  // namespace bc7
}  // namespace blocklab
