// The explicit format table (formats/registry.h): unique names, lookup errors that list the valid names, and
// well-formed declarations for every registered format.
#include <gtest/gtest.h>

#include <set>
#include <string>

#include "core/error.h"
#include "core/image.h"
#include "formats/registry.h"

namespace blocklab {
namespace {

TEST(FormatRegistry, NamesAreUniqueAndFindFormatReturnsEachEntry) {
  std::set<std::string> names;
  for (const Format* format : all_formats()) {
    ASSERT_NE(format, nullptr);
    EXPECT_TRUE(names.insert(format->name()).second) << "duplicate format name " << format->name();
    EXPECT_EQ(&find_format(format->name()), format);
  }
  EXPECT_TRUE(names.count("fp16"));
  EXPECT_TRUE(names.count("rgbe"));
}

// Every change of what the bytes mean (decoder_revision, .blk headers) is also a change of the output (revision, the
// cache key), so the decoder revision never runs ahead of the revision.
TEST(FormatRegistry, DecoderRevisionIsPositiveAndNeverAheadOfTheRevision) {
  for (const Format* format : all_formats()) {
    EXPECT_GE(format->decoder_revision(), 1) << format->name();
    EXPECT_LE(format->decoder_revision(), format->revision()) << format->name();
  }
}

// `encode OUT.dds` asks has_gpu_textures() before encoding; it must say what gpu_textures() of a real texture does.
TEST(FormatRegistry, HasGpuTexturesAgreesWithTheTexturesOfAnEncodedImage) {
  Image image(8, 8);
  for (std::size_t i = 0; i < image.texel_count(); ++i)
    for (int c = 0; c < 4; ++c) image.pixels[i * 4 + c] = c == 3 ? 1.0f : 0.05f + 0.1f * ((i + c) % 7);
  for (const Format* format : all_formats()) {
    const EncodedTexture texture =
        format->encode(image, resolve_format_options(*format, {{"preset", "fast"}}), CodecContext{1, 1});
    EXPECT_EQ(format->has_gpu_textures(), !format->gpu_textures(texture).empty()) << format->name();
  }
}

TEST(FormatRegistry, UnknownNameIsAnErrorListingTheValidNames) {
  try {
    find_format("fp61");
    FAIL() << "find_format accepted an unknown name";
  } catch (const Error& error) {
    const std::string message = error.what();
    EXPECT_EQ(message.rfind("unknown format 'fp61'; valid formats: ", 0), 0u) << message;
    for (const Format* format : all_formats()) EXPECT_NE(message.find(format->name()), std::string::npos);
  }
}

TEST(FormatRegistry, EveryFormatResolvesItsDefaultsAndDeclaresModesAndBlockSize) {
  for (const Format* format : all_formats()) {
    SCOPED_TRACE(format->name());
    FormatOptions resolved;
    ASSERT_NO_THROW(resolved = resolve_format_options(*format, {}));
    EXPECT_EQ(resolved.at("seed"), "1");
    EXPECT_EQ(resolved.size(), all_option_specs(*format).size());
    EXPECT_FALSE(format->description().empty());
    EXPECT_FALSE(format->modes().empty());
    EXPECT_LE(format->modes().size(), 256u);   // block_modes stores one byte per block
    EXPECT_GT(format->block_bytes(resolved), 0);
    EXPECT_GE(format->revision(), 1);
    for (const OptionSpec& spec : format->option_specs()) {
      EXPECT_FALSE(spec.help.empty()) << spec.name;
      if (spec.type == OptionType::choice) {
        EXPECT_FALSE(spec.choices.empty()) << spec.name;
      }
    }
  }
}

TEST(FormatRegistry, BaselineRatesMatchThePapersTables) {
  const FormatOptions none;
  EXPECT_EQ(find_format("fp16").bits_per_pixel(resolve_format_options(find_format("fp16"), none)), 48.0);
  EXPECT_EQ(find_format("rgbe").bits_per_pixel(resolve_format_options(find_format("rgbe"), none)), 32.0);
}

}  // namespace
}  // namespace blocklab
