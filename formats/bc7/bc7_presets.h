// BC7 encoder options and the named presets (fast | default | thorough).
//
// A preset only fills the knobs the user left at "preset": modes, alpha_modes, partitions_to_refine, refine_iterations,
// pbit_search, rotation_search. expand_bc7_options() returns the resolved map with every knob explicit; the
// encoder stores that expanded map in EncodedTexture::options, so results and cache keys record the settings that
// were really used (e.g. preset=default, modes=0,1,2,3,4,5,6,7, partitions_to_refine=...).
#pragma once

#include <vector>

#include "formats/bc7/bc7_mode_search.h"
#include "formats/format.h"

namespace blocklab {
namespace bc7 {

// The format's own option specs (the common ones are appended by resolve_format_options).
std::vector<OptionSpec> option_specs();

// Replaces every "preset" / -1 knob of a resolved option map by the preset's value and canonicalises the mode list
// ("6, 1" -> "1,6"). Throws Error naming the option on a malformed mode list or weights.
FormatOptions expand_bc7_options(const FormatOptions& resolved);

// Encoder settings from an expanded option map (expand_bc7_options first).
EncoderSettings encoder_settings(const FormatOptions& expanded);

}  // namespace bc7
}  // namespace blocklab
