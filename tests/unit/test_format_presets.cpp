// Format presets (formats/format.h FormatPreset, expanded by resolve_format_options): every registered format has
// fast, medium and thorough, medium is the default, a preset fills only the options the user did not set, and the
// resolved map records the preset and every value it set.
#include <gtest/gtest.h>

#include <set>
#include <string>

#include "core/error.h"
#include "formats/format.h"
#include "formats/registry.h"

namespace blocklab {
namespace {

Image gradient_image(int width, int height) {
  Image image(width, height, 3);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      float* t = image.texel(x, y);
      t[0] = 0.05f + 0.1f * static_cast<float>(x);
      t[1] = 0.02f + 0.07f * static_cast<float>(y);
      t[2] = 0.3f + 0.01f * static_cast<float>(x * y);
      t[3] = 1.0f;
    }
  return image;
}

TEST(FormatPresets, EveryFormatHasFastMediumAndThoroughAndMediumIsTheDefault) {
  for (const Format* format : all_formats()) {
    std::vector<std::string> names;
    for (const FormatPreset& preset : format->presets()) names.push_back(preset.name);
    ASSERT_GE(names.size(), 3u) << format->name();
    EXPECT_EQ(names[0], "fast") << format->name();
    EXPECT_EQ(names[1], "medium") << format->name();
    EXPECT_EQ(names[2], "thorough") << format->name();
    EXPECT_EQ(resolve_format_options(*format, {}), resolve_format_options(*format, {{"preset", "medium"}}))
        << format->name();
    EXPECT_EQ(resolve_format_options(*format, {}).at("preset"), "medium") << format->name();
  }
}

TEST(FormatPresets, EveryDeclaredDefaultIsTheValueTheDefaultPresetResolvesTo) {
  // `blocklab list` and the README tables show the spec defaults: they must be what an encode without options uses.
  for (const Format* format : all_formats()) {
    const FormatOptions defaults = resolve_format_options(*format, {});
    for (const OptionSpec& spec : all_option_specs(*format))
      EXPECT_EQ(defaults.at(spec.name), resolve_options("check", {spec}, {}).at(spec.name))
          << format->name() << " " << spec.name;
  }
}

TEST(FormatPresets, EveryPresetValueIsAValidOptionAndIsRecordedInTheResolvedMap) {
  for (const Format* format : all_formats())
    for (const FormatPreset& preset : format->presets()) {
      const FormatOptions resolved = resolve_format_options(*format, {{"preset", preset.name}});
      EXPECT_EQ(resolved.at("preset"), preset.name);
      for (const auto& value : preset.values) {
        // Values are written canonically in the preset tables, so the resolved map keeps them verbatim.
        EXPECT_EQ(resolved.at(value.first), value.second) << format->name() << " " << preset.name;
      }
      // Resolving a resolved map again gives the same map (what the container reader does).
      EXPECT_EQ(resolve_format_options(*format, resolved), resolved) << format->name() << " " << preset.name;
    }
}

TEST(FormatPresets, AnExplicitOptionWinsOverThePreset) {
  const Format& bc1 = find_format("bc1");
  EXPECT_EQ(resolve_format_options(bc1, {{"preset", "fast"}}).at("search"), "fast");
  EXPECT_EQ(resolve_format_options(bc1, {{"preset", "fast"}, {"search", "exhaustive"}}).at("search"), "exhaustive");
  const Format& munkberg = find_format("munkberg");
  const FormatOptions fast = resolve_format_options(munkberg, {{"preset", "fast"}, {"good_enough", "0.5"}});
  EXPECT_EQ(fast.at("good_enough"), "0.5");
  EXPECT_EQ(fast.at("polish_search"), "coordinate");   // the preset's other values still apply
}

TEST(FormatPresets, SwitchingPresetsNeverKeepsAnotherPresetsValue) {
  // Each preset lists every option any of the format's presets sets, so a preset's map does not depend on which
  // preset is the default.
  for (const Format* format : all_formats()) {
    std::set<std::string> keys;
    for (const FormatPreset& preset : format->presets())
      for (const auto& value : preset.values) keys.insert(value.first);
    for (const FormatPreset& preset : format->presets())
      for (const std::string& key : keys)
        EXPECT_EQ(preset.values.count(key), 1u) << format->name() << " preset " << preset.name << " key " << key;
  }
}

TEST(FormatPresets, AnUnknownPresetIsAnErrorListingThePresets) {
  try {
    resolve_format_options(find_format("bc4"), {{"preset", "best"}});
    FAIL() << "no error";
  } catch (const Error& error) {
    EXPECT_NE(std::string(error.what()).find("option 'preset' must be one of fast, medium, thorough, got 'best'"),
              std::string::npos)
        << error.what();
  }
}

TEST(FormatPresets, Bc7AcceptsDefaultAsAnAliasOfMedium) {
  const Format& bc7 = find_format("bc7");
  EXPECT_EQ(resolve_format_options(bc7, {{"preset", "default"}}), resolve_format_options(bc7, {}));
}

TEST(FormatPresets, DeterministicFormatsGiveTheSameBytesForEveryPreset) {
  const Image image = gradient_image(12, 8);
  for (const char* name : {"fp16", "rgbe"}) {
    const Format& format = find_format(name);
    const EncodedTexture medium = format.encode(image, resolve_format_options(format, {}), CodecContext{1, 1});
    for (const char* preset : {"fast", "thorough"}) {
      const EncodedTexture other =
          format.encode(image, resolve_format_options(format, {{"preset", preset}}), CodecContext{1, 1});
      EXPECT_EQ(other.blocks, medium.blocks) << name << " " << preset;
    }
    EXPECT_NE(format.presets()[0].summary.find("identical"), std::string::npos) << name;
  }
}

TEST(FormatPresets, MunkbergThoroughIsTheFullGlobalSearchAndPaperSolvesEachShape) {
  const Format& munkberg = find_format("munkberg");
  const FormatOptions thorough = resolve_format_options(munkberg, {{"preset", "thorough"}});
  EXPECT_EQ(thorough.at("solver"), "builtin");
  EXPECT_EQ(thorough.at("search_candidates"), "64");
  EXPECT_EQ(thorough.at("good_enough"), "0");
  EXPECT_EQ(thorough.at("procrustes_options"), "");
  EXPECT_EQ(resolve_format_options(munkberg, {{"preset", "paper"}}).at("solver"), "procrustes");
}

}  // namespace
}  // namespace blocklab
