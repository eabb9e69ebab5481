// BC6H encoder options and the named presets fast | medium | thorough (formats/format.h FormatPreset). The options:
// `modes` (the spec's mode numbers tried, comma-separated), `partitions_to_refine`, `modes_to_refine`,
// `refine_iterations`, `error` (the block error, formats/common/hdr_block_error.h).
// expand_bc6h_options() writes the mode list canonically (table order), so results record the settings really used.
#pragma once

#include <vector>

#include "formats/bc6h/bc6h_mode_search.h"
#include "formats/format.h"

namespace blocklab {
namespace bc6h {

std::vector<OptionSpec> option_specs();
std::vector<FormatPreset> presets();
// Canonicalises the mode list of a resolved option map; throws Error naming `where` and the option on a bad list.
FormatOptions expand_bc6h_options(const FormatOptions& resolved, const std::string& where);
EncoderSettings encoder_settings(const FormatOptions& expanded, const std::string& where);

}  // namespace bc6h
}  // namespace blocklab
