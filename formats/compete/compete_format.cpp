// The `compete` Format (compete_format.h): options and presets, the Munkberg and BC6H encoder settings taken from
// those formats' own presets (munkberg::mode_context_of, bc6h::encoder_settings), and the shared parallel block loop
// (formats/common/block_codec.h; per-block seeds derive from (seed, block index), so bytes do not depend on the
// thread count).
#include "formats/compete/compete_format.h"

#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "core/error.h"
#include "core/input_policy.h"
#include "formats/bc6h/bc6h_format.h"
#include "formats/bc6h/bc6h_presets.h"
#include "formats/common/block_codec.h"
#include "formats/compete/compete_block.h"
#include "formats/compete/compete_encoder.h"
#include "formats/munkberg/dct_tables.h"
#include "formats/munkberg/munkberg_format.h"
#include "solvers/seeding.h"

namespace blocklab {

namespace {

constexpr const char* kName = "compete";

struct CompeteOptions {
  std::string families = "shape,section6,bc6h";
  std::string munkberg_preset = "medium";
  std::string bc6h_preset = "medium";
  int refit_passes = 1;
  double good_enough = 0.1;
};

const OptionTable<CompeteOptions>& option_table() {
  using O = CompeteOptions;
  static const auto table = OptionTable<O>()
      .text("families", &O::families,
            "families competing per block, comma-separated: shape (Munkberg 2008 shape II / shape I), section6 "
            "(ext_s3tc, two_plane, dct), bc6h (BC6H two-region modes), or single Munkberg modes (shape_ii, shape_i, "
            "ext_s3tc, two_plane, dct); ablations remove one")
      .choice("munkberg_preset", &O::munkberg_preset, {"fast", "medium", "thorough"},
              "the munkberg format's preset its modes are encoded with (before fitting the compete budget)")
      .choice("bc6h_preset", &O::bc6h_preset, {"fast", "medium", "thorough"},
              "the bc6h format's preset its two-region modes are searched with (one-region modes are not in compete)")
      .integer("refit_passes", &O::refit_passes, 0, 8,
               "coordinate-descent passes over a Munkberg mode's index fields after its halved fields are rounded")
      .real("good_enough", &O::good_enough, 0.0, 1e6,
            "skip rule (approximate; 0 = off): once the best block error (squared log2[RGB] differences summed over 16 "
            "texels x 3 channels) is at most this, the remaining modes are not tried");
  return table;
}

// Measured on the gate's three HDR samples (formats/compete/README.md, "Presets"): the skip rule decides how often the
// Munkberg modes get tried after BC6H (tried first, cheap); good_enough 2 (the munkberg medium value) leaves BC6H the
// winner of almost every block, 0.1 keeps all but 0.001-0.002 of the log2[RGB] of good_enough 0 at half its time.
// BC6H's own fast preset keeps only two of its ten two-region modes, so every compete preset searches them at medium
// or above.
std::vector<FormatPreset> compete_presets() {
  const auto knobs = [](const char* munkberg_effort, const char* bc6h_effort, int refit, const char* good_enough) {
    return FormatOptions{{"munkberg_preset", munkberg_effort},
                         {"bc6h_preset", bc6h_effort},
                         {"refit_passes", std::to_string(refit)},
                         {"good_enough", good_enough}};
  };
  return {{"fast", "munkberg fast, bc6h medium, no index refit, stop at block error 0.5",
           knobs("fast", "medium", 0, "0.5"), {}},
          {kDefaultPreset, "munkberg medium, bc6h medium, one index refit pass, stop at block error 0.1",
           knobs("medium", "medium", 1, "0.1"), {}},
          {"thorough", "munkberg thorough, bc6h thorough, two index refit passes, every mode tried",
           knobs("thorough", "thorough", 2, "0"), {}}};
}

// The `families` option: family names (shape, section6, bc6h) and single Munkberg mode names (shape_ii, ..., dct),
// comma-separated; sets settings->bc6h_family and settings->munkberg_modes.
void parse_families(const std::string& text, compete::EncoderSettings* settings) {
  settings->bc6h_family = false;
  settings->munkberg_modes.fill(false);
  const std::vector<ModeSpec> munkberg_modes = munkberg_format().mode_table();
  std::string valid = "shape, section6, bc6h";
  for (const ModeSpec& mode : munkberg_modes) valid += ", " + mode.name;
  std::stringstream stream(text);
  std::string token;
  int count = 0;
  while (std::getline(stream, token, ',')) {
    const std::size_t begin = token.find_first_not_of(" \t");
    const std::size_t end = token.find_last_not_of(" \t");
    token = begin == std::string::npos ? "" : token.substr(begin, end - begin + 1);
    bool known = false;
    if (token == compete::kFamilyNames[static_cast<int>(compete::Family::bc6h)]) {
      settings->bc6h_family = true;
      known = true;
    }
    for (int m = 0; m < compete::kMunkbergModeCount; ++m)
      if (token == munkberg_modes[static_cast<std::size_t>(m)].name ||
          token == compete::kFamilyNames[static_cast<int>(compete::family_of_mode(m))]) {
        settings->munkberg_modes[static_cast<std::size_t>(m)] = true;
        known = true;
      }
    if (!known) fail(kName, "option 'families': unknown family or mode '" + token + "' in '" + text + "'; valid: " + valid);
    ++count;
  }
  if (count == 0) fail(kName, "option 'families' needs at least one of " + valid);
}

struct Setup {
  compete::EncoderSettings settings;
  std::uint64_t seed = 1;
};

Setup make_setup(const FormatOptions& resolved) {
  const CompeteOptions options = option_table().from_resolved(resolved);
  Setup setup;
  compete::EncoderSettings& settings = setup.settings;
  parse_families(options.families, &settings);
  // The Munkberg modes with the munkberg format's own preset (every mode enabled; the competition is ours).
  settings.munkberg = munkberg::mode_context_of(
      resolve_format_options(munkberg_format(), {{"preset", options.munkberg_preset}, {"modes", "all"}}));
  // BC6H's search with the bc6h format's preset, its one-region modes switched off (their code space is the
  // Munkberg families').
  const Format& bc6h = bc6h_format();
  settings.bc6h = bc6h::encoder_settings(
      bc6h::expand_bc6h_options(resolve_format_options(bc6h, {{"preset", options.bc6h_preset}}), kName), kName);
  for (int index = 0; index < bc6h::kModeCount; ++index)
    if (bc6h::mode_info(index).subset_count != 2) settings.bc6h.mode_enabled[index] = false;
  settings.refit_passes = options.refit_passes;
  settings.good_enough = options.good_enough;
  setup.seed = static_cast<std::uint64_t>(option_int(resolved, "seed"));
  return setup;
}

class CompeteFormat final : public Format {
 public:
  std::string name() const override { return kName; }
  std::string description() const override {
    return "cross-paper 8 bpp HDR mode competition: BC6H two-region blocks (as is) vs Munkberg 2008 shape modes and "
           "section 6 modes (ext_s3tc, two_plane, dct) in BC6H's one-region code space, lowest log2[RGB] wins";
  }
  std::vector<OptionSpec> option_specs() const override { return option_table().specs(CompeteOptions{}); }
  std::vector<ModeSpec> mode_table() const override {
    std::vector<ModeSpec> table;
    for (const ModeSpec& mode : munkberg_format().mode_table())
      table.push_back({mode.name, mode.description + " (compete: 2 bits less, README)"});
    const std::vector<ModeSpec> bc6h_modes = bc6h_format().mode_table();
    for (int index = 0; index < bc6h::kModeCount; ++index)
      if (bc6h::mode_info(index).subset_count == 2)
        table.push_back({"bc6h_" + bc6h_modes[static_cast<std::size_t>(index)].name,
                         "BC6H " + bc6h_modes[static_cast<std::size_t>(index)].description});
    return table;
  }
  std::vector<FormatPreset> presets() const override { return compete_presets(); }
  int block_bytes(const FormatOptions&) const override { return compete::kBlockBytes; }

  EncodedTexture encode(const Image& image, const FormatOptions& options, const CodecContext& context) const override {
    validate_encoder_input(image, kName);
    // The Munkberg modes need finite, non-negative RGB (the input policy's guarantee): anything else is an Error
    // naming the pixel, as the `error` policy reports it.
    Image checked = image;
    apply_input_policy(checked, InputPolicy::error, kName);
    const Setup setup = make_setup(options);
    EncodedTexture texture = encode_blocks(
        *this, image, options, context, compete::kBlockBytes,
        [] { return std::make_unique<munkberg::ChromaWorkspace>(); },
        [&](const BlockTexels& texels, std::size_t index, std::uint8_t* out, munkberg::ChromaWorkspace& workspace) {
          return compete::encode_block(texels, setup.settings, derive_stream_seed(setup.seed, index), &workspace, out)
              .mode;
        });
    // The DCT blocks decode through the tables they were made with (the munkberg format's rule).
    if (setup.settings.munkberg_modes[static_cast<std::size_t>(munkberg::BlockMode::dct)])
      texture.side_data[munkberg::kDctTablesSideDataKey] = munkberg::dct_tables_fingerprint(setup.settings.munkberg.dct());
    return texture;
  }

  Image decode(const EncodedTexture& texture, const CodecContext& context) const override {
    const munkberg::ModeContext mode_context;   // built-in shapes, ext_s3tc in rgb, compiled-in DCT tables
    const auto fingerprint = texture.side_data.find(munkberg::kDctTablesSideDataKey);
    if (fingerprint != texture.side_data.end() &&
        fingerprint->second != munkberg::dct_tables_fingerprint(mode_context.dct()))
      fail(kName, std::string("side data '") + munkberg::kDctTablesSideDataKey +
                      "': the texture was encoded with other DCT tables than this build's; re-encode it");
    return decode_blocks(*this, texture, context, rgb_only_decoded_channels(texture.channels),
                         [&](const std::uint8_t* bytes, std::size_t) { return compete::decode_block(bytes, mode_context); });
  }

};

}  // namespace

const Format& compete_format() {
  static const CompeteFormat format;
  return format;
}

}  // namespace blocklab
