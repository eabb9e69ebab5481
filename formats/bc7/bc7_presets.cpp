// BC7 options and presets (see bc7_presets.h). presets() is the only place preset values live; docs/benchmarks-bc7.md
// reports what each preset costs and gains.
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

// Chosen from measurements (docs/benchmarks-bc7.md): mode 6 alone (one subset, 4-bit indices) is the cheapest good
// mode; adding mode 1 (two subsets, 3-bit indices) gains ~3 dB on Kodak for ~4x the time. medium refines the 3 best
// estimated partitions and polishes the winner once (each about +0.1 dB), which puts it at or above astcenc 4x4
// -medium at more than twice its speed; the 3-subset modes and more partitions, refinement and polish add a few
// tenths of a dB at several times the cost, so they are `thorough` only. thorough re-ranks 8 partitions by the
// palette estimate (bc7_partition_palette_estimate.h) and fits 3 (about the PSNR of fitting the 4 best by line
// error), and tries the 3-subset modes only on blocks still at weighted SSE >= 200 after modes 6, 1 and 3 (their
// 64-partition ranking is most of their cost; on 4 Kodak images this keeps ~80 % of their gain at ~1.4x the
// speed).
std::vector<FormatPreset> presets() {
  const auto knobs = [](const char* modes, const char* alpha_modes, int partitions, int candidates,
                        int three_subset_threshold, int iterations, bool pbit, bool rotation, int polish) {
    return FormatOptions{{"modes", modes},
                         {"alpha_modes", alpha_modes},
                         {"partitions_to_refine", std::to_string(partitions)},
                         {"partition_candidates", std::to_string(candidates)},
                         {"three_subset_threshold", std::to_string(three_subset_threshold)},
                         {"refine_iterations", std::to_string(iterations)},
                         {"pbit_search", pbit ? "on" : "off"},
                         {"rotation_search", rotation ? "on" : "off"},
                         {"polish_passes", std::to_string(polish)}};
  };
  return {{"fast", "mode 6 only", knobs("6", "6", 1, 1, 0, 1, false, false, 0), {}},
          {kDefaultPreset, "modes 1 and 6, three partitions refined, the winner polished",
           knobs("1,6", "4,5,6,7", 3, 1, 0, 1, false, false, 1), {"default"}},
          {"thorough", "modes 0-3 and 6 (4-7 with alpha; 3-subset modes only on blocks with weighted SSE >= 200), "
                       "the 8 best line-error partitions re-ranked by the palette estimate and the best 3 fitted, "
                       "two refinements and polish passes, rotation search",
           knobs("0,1,2,3,6", "4,5,6,7", 3, 8, 200, 2, false, true, 2), {}}};
}

namespace {

// Every option of the format, declared once; the knobs' defaults are the medium preset's (option_specs()).
struct Bc7Options {
  std::string modes, alpha_modes;
  int partitions_to_refine = 1;
  int partition_candidates = 1;
  int three_subset_threshold = 0;
  int refine_iterations = 0;
  bool pbit_search = false;
  bool rotation_search = false;
  int polish_passes = 0;
  std::string weights = "1,1,1,1";
  std::string solver = "builtin";
};

const OptionTable<Bc7Options>& bc7_option_table() {
  using O = Bc7Options;
  const std::vector<std::pair<std::string, bool>> on_off = {{"on", true}, {"off", false}};
  static const auto table = OptionTable<O>()
      .text("modes", &O::modes, "comma-separated BC7 modes (0..7) tried for opaque blocks (all alpha 255)")
      .text("alpha_modes", &O::alpha_modes, "comma-separated BC7 modes (4..7) tried for blocks with alpha below 255")
      .integer("partitions_to_refine", &O::partitions_to_refine, 1, 64,
               "partitions fully fitted per partitioned mode, best PCA estimates first")
      .integer("partition_candidates", &O::partition_candidates, 1, 64,
               "partitions re-ranked by the palette-along-axis estimate before the best partitions_to_refine are "
               "fitted (at most partitions_to_refine: the line-error ranking alone)")
      .integer("three_subset_threshold", &O::three_subset_threshold, 0, 1 << 24,
               "3-subset modes (0, 2) are tried only for blocks whose best weighted squared error so far (8-bit "
               "units, summed over the 16 texels) is at least this; 0 = always")
      .integer("refine_iterations", &O::refine_iterations, 0, 32, "least-squares endpoint refinement rounds per subset")
      .choice("pbit_search", &O::pbit_search, on_off,
              "try every P-bit combination (on) or the nearest per endpoint (off)")
      .choice("rotation_search", &O::rotation_search, on_off, "modes 4/5: try the channel rotations 1-3 as well as 0")
      .integer("polish_passes", &O::polish_passes, 0, 16,
               "lattice polish passes per subset fit: each stored endpoint code one step up/down, kept if better")
      .text("weights", &O::weights,
            "per-channel error weights r,g,b,a (Mavridis & Papaioannou 2012 use 0.6,0.2,0.2 for RGB)")
      .choice("solver", &O::solver, {"builtin"},
              "endpoint search: builtin = closed-form PCA + least squares (bc7_endpoint_fit); the same subset problem "
              "is exposed as a core Problem for the solver library");
  return table;
}

}  // namespace

std::vector<OptionSpec> option_specs() {
  // Defaults are the medium preset's values, which the default preset writes anyway.
  const std::vector<FormatPreset> all = presets();
  FormatOptions medium = bc7_option_table().to_options(Bc7Options{});
  for (const auto& value : all[1].values) medium[value.first] = value.second;
  return bc7_option_table().specs(bc7_option_table().from_resolved(medium));
}

FormatOptions expand_bc7_options(const FormatOptions& resolved) {
  FormatOptions expanded = resolved;
  bool enabled[kModeCount];
  parse_modes("modes", get(resolved, "modes"), 0, enabled);
  expanded["modes"] = modes_text(enabled);
  parse_modes("alpha_modes", get(resolved, "alpha_modes"), 4, enabled);
  expanded["alpha_modes"] = modes_text(enabled);
  float weights[4];
  parse_weights(get(resolved, "weights"), weights);
  expanded["weights"] = canonical_weights(weights);
  return expanded;
}

EncoderSettings encoder_settings(const FormatOptions& expanded) {
  const Bc7Options options = bc7_option_table().from_resolved(expanded);
  EncoderSettings settings;
  parse_modes("modes", options.modes, 0, settings.mode_enabled);
  parse_modes("alpha_modes", options.alpha_modes, 4, settings.alpha_mode_enabled);
  settings.partitions_to_refine = options.partitions_to_refine;
  settings.refine_iterations = options.refine_iterations;
  settings.partition_candidates = options.partition_candidates;
  settings.three_subset_threshold = options.three_subset_threshold;
  std::string why;
  if (!bc7_option_table().is_valid(options, &why)) fail(kWhere, why + " (resolve the options first)");
  settings.pbit_search = options.pbit_search;
  settings.rotation_search = options.rotation_search;
  settings.polish_passes = options.polish_passes;
  parse_weights(options.weights, settings.weights);
  return settings;
}

}  // namespace bc7
}  // namespace blocklab
