// BC6H options and presets (bc6h_presets.h). presets() is the only place preset values live; formats/bc6h/README.md
// reports what each costs and gains against astcenc.
#include "formats/bc6h/bc6h_presets.h"

#include <sstream>
#include <string>

#include "core/error.h"

namespace blocklab {
namespace bc6h {

namespace {

struct Bc6hOptions {
  std::string modes = "0,1,2,6,10,14,18,22,26,30,3,7,11,15";
  int partitions_to_refine = 2;
  int modes_to_refine = 2;
  int refine_iterations = 4;
  HdrBlockError error = HdrBlockError::mpsnr_weighted;
};

const OptionTable<Bc6hOptions>& option_table() {
  using O = Bc6hOptions;
  static const auto table = OptionTable<O>()
      .text("modes", &O::modes,
            "comma-separated BC6H mode numbers tried (KDFS numbering: two subsets 0, 1, 2, 6, 10, 14, 18, 22, 26, 30; "
            "one subset 3, 7, 11, 15)")
      .integer("partitions_to_refine", &O::partitions_to_refine, 1, 32,
               "two-subset partitions fully fitted per block, best off-line-spread estimates first")
      .integer("modes_to_refine", &O::modes_to_refine, 1, 14,
               "per group of modes sharing regions (the one-subset modes; the two-subset modes on one partition), how "
               "many of the best line fits get least-squares rounds")
      .integer("refine_iterations", &O::refine_iterations, 0, 8,
               "least-squares endpoint rounds after the principal-axis fit (stops early when the error stops dropping)")
      .choice("error", &O::error, hdr_block_error_choices(), hdr_block_error_help());
  return table;
}

// "3, 11" -> enabled mode indices; rejects empty lists, non-numbers and reserved or unknown mode numbers.
void parse_modes(const std::string& text, const std::string& where, bool (&enabled)[kModeCount]) {
  for (bool& e : enabled) e = false;
  std::stringstream stream(text);
  std::string part;
  int count = 0;
  while (std::getline(stream, part, ',')) {
    const std::size_t begin = part.find_first_not_of(" \t");
    const std::size_t end = part.find_last_not_of(" \t");
    const std::string item = begin == std::string::npos ? "" : part.substr(begin, end - begin + 1);
    int number = -1;
    if (!item.empty() && item.size() <= 2 && item.find_first_not_of("0123456789") == std::string::npos)
      number = std::stoi(item);
    const int index = number < 0 ? kReservedModeIndex : mode_index_of_number(number);
    if (index == kReservedModeIndex)
      fail(where, "option 'modes': '" + item + "' is not a BC6H mode number (0, 1, 2, 6, 10, 14, 18, 22, 26, 30, 3, 7, "
                  "11, 15), in '" + text + "'");
    enabled[index] = true;
    ++count;
  }
  if (count == 0 || (!text.empty() && text.back() == ','))
    fail(where, "option 'modes' needs a comma-separated list of BC6H mode numbers, got '" + text + "'");
}

std::string modes_text(const bool (&enabled)[kModeCount]) {
  std::string text;
  for (int index = 0; index < kModeCount; ++index)
    if (enabled[index]) text += (text.empty() ? "" : ",") + std::to_string(mode_info(index).mode_number);
  return text;
}

}  // namespace

// Every preset scores blocks with error=mpsnr_weighted (formats/common/hdr_block_error.h): on the 28 HDR images of
// ../shared/data (512 crops, formats/bc6h/README.md, "Error choice") it gains mPSNR (+0.11 dB at medium) and
// skip-rule log2[RGB] (-0.013) over log2_floor for a higher floor-rule log2[RGB] (0.244 -> 0.290, still below
// astcenc's 0.48-0.50) at 1.1-1.2x the time. fast: the four one-subset modes plus two two-subset modes (1: widest
// range, 14: 9-bit endpoints) on the best partition; medium: every mode, two partitions, the two best line fits of
// each group refined up to four rounds (rounds stop when the error stops dropping; the cheapest setting measured at or
// above astcenc -thorough's mPSNR and below astcenc -medium's time on the 28 whole HDR images: 45.101 against
// 45.096 dB at 0.91x; two rounds gave 45.090); thorough: every mode, eight partitions, three modes refined three rounds.
std::vector<FormatPreset> presets() {
  const auto knobs = [](const char* modes, int partitions, int modes_refined, int iterations) {
    return FormatOptions{{"modes", modes},
                         {"partitions_to_refine", std::to_string(partitions)},
                         {"modes_to_refine", std::to_string(modes_refined)},
                         {"refine_iterations", std::to_string(iterations)},
                         {"error", "mpsnr_weighted"}};
  };
  return {{"fast", "one-subset modes 3, 7, 11, 15 and two-subset modes 1, 14 on the best partition, the best line fit "
                   "of each group refined once; mPSNR-weighted error",
           knobs("1,14,3,7,11,15", 1, 1, 1), {}},
          {kDefaultPreset, "every mode, the two best partitions, the two best line fits of each group refined up to "
                           "four rounds; mPSNR-weighted error",
           knobs("0,1,2,6,10,14,18,22,26,30,3,7,11,15", 2, 2, 4), {"default"}},
          {"thorough", "every mode, the eight best partitions, the three best line fits of each group refined up to three "
                       "rounds; mPSNR-weighted error",
           knobs("0,1,2,6,10,14,18,22,26,30,3,7,11,15", 8, 3, 3), {}}};
}

std::vector<OptionSpec> option_specs() { return option_table().specs(Bc6hOptions{}); }

FormatOptions expand_bc6h_options(const FormatOptions& resolved, const std::string& where) {
  FormatOptions expanded = resolved;
  const auto found = resolved.find("modes");
  if (found == resolved.end()) fail(where, "option 'modes' is missing (resolve the options first)");
  bool enabled[kModeCount];
  parse_modes(found->second, where, enabled);
  expanded["modes"] = modes_text(enabled);
  return expanded;
}

EncoderSettings encoder_settings(const FormatOptions& expanded, const std::string& where) {
  const Bc6hOptions options = option_table().from_resolved(expanded);
  std::string why;
  if (!option_table().is_valid(options, &why)) fail(where, why + " (resolve the options first)");
  EncoderSettings settings;
  parse_modes(options.modes, where, settings.mode_enabled);
  settings.partitions_to_refine = options.partitions_to_refine;
  settings.modes_to_refine = options.modes_to_refine;
  settings.refine_iterations = options.refine_iterations;
  settings.error = options.error;
  return settings;
}

}  // namespace bc6h
}  // namespace blocklab
