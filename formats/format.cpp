// Format option resolution (the format's own options plus the common ones, resolved by core/options.h) and the
// texture / encoder-input consistency checks (formats/format.h).
#include "formats/format.h"
#include "formats/option_markdown.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/blocks.h"
#include "core/error.h"

namespace blocklab {

namespace {

// Largest seed accepted: 2^53 - 1, so tools that read JSON numbers as doubles (Python's json, pandas, notebooks)
// keep a recorded seed exact.
constexpr double kMaxSeed = 9007199254740991.0;

}  // namespace

std::vector<FormatPreset> identical_presets() {
  const char* same = "identical to the other presets (the format has no search effort to trade)";
  return {{"fast", same, {}, {}}, {kDefaultPreset, same, {}, {}}, {"thorough", same, {}, {}}};
}

std::vector<FormatPreset> one_option_presets(const std::string& option, const std::string& fast,
                                             const std::string& medium, const std::string& thorough) {
  return {{"fast", "", {{option, fast}}, {}},
          {kDefaultPreset, "", {{option, medium}}, {}},
          {"thorough", "", {{option, thorough}}, {}}};
}

std::vector<FormatPreset> Format::presets() const { return identical_presets(); }

std::size_t Format::stored_block_count(const EncodedTexture& texture) const {
  return BlockGrid(texture.width, texture.height).block_count();
}

std::vector<OptionSpec> common_option_specs(const Format& format) {
  std::vector<std::string> names;
  for (const FormatPreset& preset : format.presets()) names.push_back(preset.name);
  OptionSpec preset = choice_option("preset", kDefaultPreset, names,
                                    "named option set (" + join_names(names) + "): fills every option it lists that "
                                    "is not set explicitly; `blocklab list` shows the values");
  OptionSpec seed;
  seed.name = "seed";
  seed.type = OptionType::integer;
  seed.default_value = "1";
  seed.help = "seed of the format's randomised searches (per-block seeds derive from it); deterministic formats "
              "accept and record it";
  seed.min_value = 0.0;
  seed.max_value = kMaxSeed;
  return {preset, seed};
}

std::vector<OptionSpec> all_option_specs(const Format& format) {
  std::vector<OptionSpec> specs = format.option_specs();
  for (OptionSpec& common : common_option_specs(format)) specs.push_back(std::move(common));
  return specs;
}

std::string format_options_markdown(const Format& format) {
  std::string text = option_table_markdown(all_option_specs(format));
  text += "\n| preset | expands to |\n|---|---|\n";
  for (const FormatPreset& preset : format.presets()) {
    std::string values;
    for (const auto& value : preset.values)
      values += (values.empty() ? "`" : ", `") + value.first + "=" + value.second + "`";
    std::string name = "`" + preset.name + "`";
    for (const std::string& alias : preset.aliases) name += " (alias `" + alias + "`)";
    text += "| " + name + " | " + (values.empty() ? "the defaults" : values) +
            (preset.summary.empty() ? "" : ": " + preset.summary) + " |\n";
  }
  return text;
}

FormatOptions resolve_format_options(const Format& format, const FormatOptions& given) {
  FormatOptions expanded = given;
  const auto chosen = given.find("preset");
  std::string name = kDefaultPreset;
  if (chosen != given.end()) {
    name = chosen->second;
    const std::size_t begin = name.find_first_not_of(" \t"), end = name.find_last_not_of(" \t");
    name = begin == std::string::npos ? "" : name.substr(begin, end - begin + 1);
  }
  for (const FormatPreset& preset : format.presets()) {
    const bool alias = std::find(preset.aliases.begin(), preset.aliases.end(), name) != preset.aliases.end();
    if (preset.name != name && !alias) continue;
    expanded["preset"] = preset.name;
    for (const auto& value : preset.values) expanded.emplace(value.first, value.second);   // explicit values win
  }
  // An unknown preset name is reported by the `preset` spec's choice check, with the valid names.
  return resolve_options(format.name(), all_option_specs(format), expanded);
}

void validate_encoded_texture(const Format& format, const EncodedTexture& texture, const std::string& where) {
  if (texture.format != format.name())
    fail(where, "texture is in format '" + texture.format + "', not '" + format.name() + "'");
  // Sizes are checked before any product is formed, so block counts below cannot overflow.
  if (texture.width < 1 || texture.width > kMaxTextureDimension)
    fail(where, "width " + std::to_string(texture.width) + " is outside [1, " +
                    std::to_string(kMaxTextureDimension) + "]");
  if (texture.height < 1 || texture.height > kMaxTextureDimension)
    fail(where, "height " + std::to_string(texture.height) + " is outside [1, " +
                    std::to_string(kMaxTextureDimension) + "]");
  if (texture.channels != 1 && texture.channels != 3 && texture.channels != 4)
    fail(where, "channels must be 1, 3 or 4, got " + std::to_string(texture.channels));
  const int expected_block_bytes = format.block_bytes(texture.options);
  if (texture.block_bytes != expected_block_bytes)
    fail(where, "block_bytes is " + std::to_string(texture.block_bytes) + " but format '" + format.name() +
                    "' with these options uses " + std::to_string(expected_block_bytes));
  for (const auto& entry : texture.side_data)
    for (std::size_t i = 0; i < entry.second.size(); ++i)
      if (!std::isfinite(entry.second[i]))
        fail(where, "side data '" + entry.first + "'[" + std::to_string(i) + "] is not finite");
  std::size_t block_count = 0;
  try {
    block_count = format.stored_block_count(texture);
  } catch (const Error& error) {
    fail(where, error.what());
  }
  const std::size_t expected_bytes = block_count * static_cast<std::size_t>(expected_block_bytes);
  if (texture.blocks.size() != expected_bytes)
    fail(where, "block data holds " + std::to_string(texture.blocks.size()) + " bytes, expected " +
                    std::to_string(expected_bytes) + " (" + std::to_string(block_count) + " blocks of " +
                    std::to_string(expected_block_bytes) + " bytes)");
  if (!texture.block_modes.empty() && texture.block_modes.size() != block_count)
    fail(where, "block_modes holds " + std::to_string(texture.block_modes.size()) + " entries for " +
                    std::to_string(block_count) + " blocks");
  const std::size_t mode_count = format.modes().size();
  for (std::size_t i = 0; i < texture.block_modes.size(); ++i)
    if (texture.block_modes[i] >= mode_count)
      fail(where, "block " + std::to_string(i) + " has mode index " + std::to_string(texture.block_modes[i]) +
                      " but the format has " + std::to_string(mode_count) + " modes");
}

void validate_encoder_input(const Image& image, const std::string& where) {
  if (image.width < 1 || image.width > kMaxTextureDimension || image.height < 1 ||
      image.height > kMaxTextureDimension)
    fail(where, "cannot encode a " + std::to_string(image.width) + "x" + std::to_string(image.height) +
                    " image (each side must be in [1, " + std::to_string(kMaxTextureDimension) + "])");
  if (image.channels != 1 && image.channels != 3 && image.channels != 4)
    fail(where, "image channels must be 1, 3 or 4, got " + std::to_string(image.channels));
  if (image.pixels.size() != image.texel_count() * 4)
    fail(where, "image holds " + std::to_string(image.pixels.size()) + " floats, expected " +
                    std::to_string(image.texel_count() * 4) + " (RGBA per texel)");
}

}  // namespace blocklab
