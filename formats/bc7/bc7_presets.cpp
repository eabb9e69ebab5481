// BC7 options and preset expansion (see bc7_presets.h). The preset table is the only place preset values live;
// docs/benchmarks-bc7.md reports what each preset costs and gains.
#include "formats/bc7/bc7_presets.h"

#include <charconv>
#include <cmath>
#include <sstream>
#include <string>

#include "core/error.h"

namespace blocklab {
namespace bc7 {

namespace {

constexpr const char* kWhere = "bc7";
constexpr const char* kFromPreset = "preset";

struct Preset {
  const char* name;
  const char* modes;         // for opaque blocks (all alpha 255)
  const char* alpha_modes;   // for blocks with some alpha below 255 (modes 4-7 only)
  int partitions_to_refine;
  int refine_iterations;
  bool pbit_search;
  bool rotation_search;
};

// Chosen from measurements (docs/benchmarks-bc7.md): mode 6 alone (one subset, 4-bit indices) is the cheapest good
// mode; adding mode 1 (two subsets, 3-bit indices) gains ~3.7 dB on Kodak for ~4x the time; the 3-subset modes,
// P-bit search and more partitions add a few tenths of a dB at several times the cost, so they are `thorough` only.
constexpr Preset kPresets[] = {
    {"fast", "6", "6", 1, 1, false, false},
    {"default", "1,6", "4,5,6,7", 2, 1, false, false},
    {"thorough", "0,1,2,3,4,5,6,7", "4,5,6,7", 16, 4, true, true},
};

const Preset& find_preset(const std::string& name) {
  for (const Preset& preset : kPresets)
    if (name == preset.name) return preset;
  fail(kWhere, "option 'preset' must be one of fast, default, thorough, got '" + name + "'");
}

std::string trim(const std::string& text) {
  std::size_t begin = 0, end = text.size();
  while (begin < end && (text[begin] == ' ' || text[begin] == '\t')) ++begin;
  while (end > begin && (text[end - 1] == ' ' || text[end - 1] == '\t')) --end;
  return text.substr(begin, end - begin);
}

std::vector<std::string> split_commas(const std::string& text) {
  std::vector<std::string> parts;
  std::stringstream stream(text);
  std::string part;
  while (std::getline(stream, part, ',')) parts.push_back(trim(part));
  if (!text.empty() && text.back() == ',') parts.push_back("");   // "1,6," has an empty last item
  return parts;
}

// "6, 1,1" -> enabled {1, 6}; rejects empty lists, non-numbers and modes outside first_mode..7.
void parse_modes(const std::string& key, const std::string& text, int first_mode, bool (&enabled)[kModeCount]) {
  for (bool& e : enabled) e = false;
  const auto parts = split_commas(text);
  const std::string range = std::to_string(first_mode) + "..7";
  if (parts.empty()) fail(kWhere, "option '" + key + "' is empty; give a comma-separated list of modes " + range);
  for (const std::string& part : parts) {
    if (part.size() != 1 || part[0] < '0' + first_mode || part[0] > '7')
      fail(kWhere, "option '" + key + "': '" + part + "' is not a BC7 mode number " + range + ", in '" + text + "'");
    enabled[part[0] - '0'] = true;
  }
}

std::string modes_text(const bool (&enabled)[kModeCount]) {
  std::string text;
  for (int mode = 0; mode < kModeCount; ++mode)
    if (enabled[mode]) text += (text.empty() ? "" : ",") + std::to_string(mode);
  return text;
}

// "r,g,b,a": four finite non-negative reals, not all zero.
void parse_weights(const std::string& text, float (&weights)[4]) {
  const auto parts = split_commas(text);
  if (parts.size() != 4)
    fail(kWhere, "option 'weights' needs four comma-separated values r,g,b,a, got '" + text + "'");
  double sum = 0.0;
  for (int c = 0; c < 4; ++c) {
    double value = 0.0;
    const char* first = parts[c].data();
    const char* last = first + parts[c].size();
    const auto result = std::from_chars(first, last, value);
    if (parts[c].empty() || result.ec != std::errc() || result.ptr != last || !std::isfinite(value) || value < 0.0)
      fail(kWhere, "option 'weights': '" + parts[c] + "' is not a finite non-negative number, in '" + text + "'");
    weights[c] = static_cast<float>(value);
    sum += value;
  }
  // All-zero weights make every block equally good: reject instead of encoding arbitrary bits.
  if (sum <= 0.0) fail(kWhere, "option 'weights' must have at least one positive value, got '" + text + "'");
}

std::string canonical_weights(const float (&weights)[4]) {
  std::string text;
  for (int c = 0; c < 4; ++c) {
    char buffer[32];
    const auto result = std::to_chars(buffer, buffer + sizeof buffer, weights[c]);
    text += (c ? "," : "") + std::string(buffer, result.ptr);
  }
  return text;
}

const std::string& get(const FormatOptions& options, const std::string& key) {
  const auto found = options.find(key);
  if (found == options.end()) fail(kWhere, "option '" + key + "' is missing (resolve the options first)");
  return found->second;
}

}  // namespace

std::vector<OptionSpec> option_specs() {
  std::vector<OptionSpec> specs;
  specs.push_back({"preset", OptionType::choice, "default", {"fast", "default", "thorough"},
                   "search effort; fills every knob left at 'preset' (-1); the values are in formats/bc7/README.md "
                   "and in the options an encode records"});
  specs.push_back({"modes", OptionType::text, kFromPreset, {},
                   "comma-separated BC7 modes (0..7) tried for opaque blocks (all alpha 255), or 'preset'"});
  specs.push_back({"alpha_modes", OptionType::text, kFromPreset, {},
                   "comma-separated BC7 modes (4..7) tried for blocks with alpha below 255, or 'preset'"});
  OptionSpec partitions{"partitions_to_refine", OptionType::integer, "-1", {},
                        "partitions fully fitted per partitioned mode, best PCA estimates first (1..64); -1 = preset"};
  partitions.min_value = -1;
  partitions.max_value = 64;
  specs.push_back(partitions);
  OptionSpec iterations{"refine_iterations", OptionType::integer, "-1", {},
                        "least-squares endpoint refinement rounds per subset (0..32); -1 = preset"};
  iterations.min_value = -1;
  iterations.max_value = 32;
  specs.push_back(iterations);
  specs.push_back({"pbit_search", OptionType::choice, kFromPreset, {kFromPreset, "on", "off"},
                   "try every P-bit combination (on) or the nearest per endpoint (off)"});
  specs.push_back({"rotation_search", OptionType::choice, kFromPreset, {kFromPreset, "on", "off"},
                   "modes 4/5: try the channel rotations 1-3 as well as 0"});
  specs.push_back({"weights", OptionType::text, "1,1,1,1", {},
                   "per-channel error weights r,g,b,a (Mavridis & Papaioannou 2012 use 0.6,0.2,0.2 for RGB)"});
  specs.push_back({"solver", OptionType::choice, "builtin", {"builtin"},
                   "endpoint search: builtin = closed-form PCA + least squares (bc7_endpoint_fit); the same "
                   "subset problem is exposed as a core Problem for the solver library"});
  return specs;
}

FormatOptions expand_bc7_options(const FormatOptions& resolved) {
  FormatOptions expanded = resolved;
  const Preset& preset = find_preset(get(resolved, "preset"));
  bool enabled[kModeCount];
  const std::string& modes = get(resolved, "modes");
  parse_modes("modes", trim(modes) == kFromPreset ? preset.modes : modes, 0, enabled);
  expanded["modes"] = modes_text(enabled);
  const std::string& alpha_modes = get(resolved, "alpha_modes");
  parse_modes("alpha_modes", trim(alpha_modes) == kFromPreset ? preset.alpha_modes : alpha_modes, 4, enabled);
  expanded["alpha_modes"] = modes_text(enabled);
  if (get(resolved, "partitions_to_refine") == "-1")
    expanded["partitions_to_refine"] = std::to_string(preset.partitions_to_refine);
  // 0 partitions would disable the partitioned modes silently: reject it instead.
  if (option_int(expanded, "partitions_to_refine") < 1)
    fail(kWhere, "option 'partitions_to_refine' must be 1..64 (or -1 for the preset), got " +
                     get(resolved, "partitions_to_refine"));
  if (get(resolved, "refine_iterations") == "-1")
    expanded["refine_iterations"] = std::to_string(preset.refine_iterations);
  if (get(resolved, "pbit_search") == kFromPreset) expanded["pbit_search"] = preset.pbit_search ? "on" : "off";
  if (get(resolved, "rotation_search") == kFromPreset)
    expanded["rotation_search"] = preset.rotation_search ? "on" : "off";
  float weights[4];
  parse_weights(get(resolved, "weights"), weights);
  expanded["weights"] = canonical_weights(weights);
  return expanded;
}

EncoderSettings encoder_settings(const FormatOptions& expanded) {
  EncoderSettings settings;
  parse_modes("modes", get(expanded, "modes"), 0, settings.mode_enabled);
  parse_modes("alpha_modes", get(expanded, "alpha_modes"), 4, settings.alpha_mode_enabled);
  settings.partitions_to_refine = static_cast<int>(option_int(expanded, "partitions_to_refine"));
  settings.refine_iterations = static_cast<int>(option_int(expanded, "refine_iterations"));
  if (settings.partitions_to_refine < 1 || settings.refine_iterations < 0)
    fail(kWhere, "options 'partitions_to_refine' / 'refine_iterations' are not expanded (call expand_bc7_options)");
  const std::string& pbit = get(expanded, "pbit_search");
  const std::string& rotation = get(expanded, "rotation_search");
  if (pbit == kFromPreset || rotation == kFromPreset)
    fail(kWhere, "options 'pbit_search' / 'rotation_search' are not expanded (call expand_bc7_options)");
  settings.pbit_search = pbit == "on";
  settings.rotation_search = rotation == "on";
  parse_weights(get(expanded, "weights"), settings.weights);
  return settings;
}

}  // namespace bc7
}  // namespace blocklab
