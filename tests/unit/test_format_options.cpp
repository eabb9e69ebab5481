// Option resolution (formats/format.h): defaults, validation, canonical spelling, the common `seed` and `preset` options,
// unknown-key errors and the typed accessors.
#include <gtest/gtest.h>

#include <string>

#include "core/error.h"
#include "formats/format.h"

namespace blocklab {
namespace {

// A format that only declares options, one of each type.
class OptionsOnlyFormat final : public Format {
 public:
  std::string name() const override { return "toy"; }
  std::string description() const override { return "test double declaring one option of each type"; }
  std::vector<OptionSpec> option_specs() const override {
    OptionSpec count{"count", OptionType::integer, "3", {}, "an integer in [1, 10]", 1.0, 10.0};
    OptionSpec weight{"weight", OptionType::real, "0.5", {}, "a real in [0, 2]", 0.0, 2.0};
    OptionSpec unbounded{"offset", OptionType::real, "-1.25", {}, "a real without bounds"};
    OptionSpec flag{"flag", OptionType::boolean, "no", {}, "a boolean"};
    OptionSpec mode{"mode", OptionType::choice, "fast", {"fast", "exhaustive"}, "a choice"};
    OptionSpec label{"label", OptionType::text, " free text ", {}, "text kept verbatim"};
    return {count, weight, unbounded, flag, mode, label};
  }
  std::vector<ModeSpec> mode_table() const override { return {{"only", "the one mode"}}; }
  int block_bytes(const FormatOptions&) const override { return 8; }
  EncodedTexture encode(const Image&, const FormatOptions&, const CodecContext&) const override { return {}; }
  Image decode(const EncodedTexture&, const CodecContext&) const override { return {}; }
};

// Declares `seed` itself, which collides with the common option.
class SeedDeclaringFormat final : public Format {
 public:
  std::string name() const override { return "seedy"; }
  std::string description() const override { return "test double"; }
  std::vector<OptionSpec> option_specs() const override {
    return {OptionSpec{"seed", OptionType::integer, "7", {}, "collides"}};
  }
  std::vector<ModeSpec> mode_table() const override { return {{"only", "the one mode"}}; }
  int block_bytes(const FormatOptions&) const override { return 8; }
  EncodedTexture encode(const Image&, const FormatOptions&, const CodecContext&) const override { return {}; }
  Image decode(const EncodedTexture&, const CodecContext&) const override { return {}; }
};

std::string error_of(const Format& format, const FormatOptions& given) {
  try {
    resolve_format_options(format, given);
  } catch (const Error& error) {
    return error.what();
  }
  return "";
}

TEST(FormatOptions, FillsEveryDefaultInCanonicalSpellingPlusTheCommonSeed) {
  const FormatOptions resolved = resolve_format_options(OptionsOnlyFormat(), {});
  const FormatOptions expected = {{"count", "3"}, {"weight", "0.5"}, {"offset", "-1.25"}, {"flag", "false"},
                                  {"mode", "fast"}, {"label", " free text "}, {"preset", "medium"},
                                  {"seed", "1"}};
  EXPECT_EQ(resolved, expected);
}

TEST(FormatOptions, EqualSettingsSpelledDifferentlyResolveToTheSameMap) {
  const OptionsOnlyFormat format;
  const FormatOptions a = resolve_format_options(format, {{"weight", "1.50"}, {"count", "+007"}, {"flag", "YES"},
                                                          {"offset", "-0"}, {"seed", "0042"}});
  const FormatOptions b = resolve_format_options(format, {{"weight", "1.5"}, {"count", "7"}, {"flag", "true"},
                                                          {"offset", "0"}, {"seed", "42"}});
  EXPECT_EQ(a, b);
  EXPECT_EQ(a.at("weight"), "1.5");
  EXPECT_EQ(a.at("count"), "7");
  EXPECT_EQ(a.at("flag"), "true");
  EXPECT_EQ(a.at("offset"), "0");
  EXPECT_EQ(a.at("seed"), "42");
  EXPECT_EQ(resolve_format_options(format, {{"weight", "1e0"}}).at("weight"), "1");
  EXPECT_EQ(resolve_format_options(format, {{"weight", " .25 "}}).at("weight"), "0.25");
  EXPECT_EQ(resolve_format_options(format, {{"offset", "1e-3"}}).at("offset"), "0.001");
}

TEST(FormatOptions, BooleansAcceptTrueFalseYesNoOneZeroInAnyCase) {
  const OptionsOnlyFormat format;
  for (const char* text : {"true", "True", "YES", "yes", "1"})
    EXPECT_EQ(resolve_format_options(format, {{"flag", text}}).at("flag"), "true") << text;
  for (const char* text : {"false", "FALSE", "no", "No", "0"})
    EXPECT_EQ(resolve_format_options(format, {{"flag", text}}).at("flag"), "false") << text;
  EXPECT_NE(error_of(format, {{"flag", "on"}}).find("option 'flag' expects a boolean"), std::string::npos);
  EXPECT_NE(error_of(format, {{"flag", ""}}).find("option 'flag'"), std::string::npos);
}

TEST(FormatOptions, UnknownKeyIsAnErrorListingEveryValidKeyIncludingSeed) {
  EXPECT_EQ(error_of(OptionsOnlyFormat(), {{"cuont", "3"}}),
            "toy: unknown option 'cuont'; valid options: count, flag, label, mode, offset, preset, seed, weight");
}

TEST(FormatOptions, MalformedIntegersAreRejectedWithKeyAndValue) {
  const OptionsOnlyFormat format;
  for (const char* text : {"", "3.0", "1e1", "0x5", "five", "3 4", "--3", "99999999999999999999999"}) {
    const std::string error = error_of(format, {{"count", text}});
    EXPECT_NE(error.find("toy: option 'count' expects an integer, got '" + std::string(text) + "'"),
              std::string::npos)
        << "'" << text << "' -> " << error;
  }
}

TEST(FormatOptions, MalformedOrNonFiniteRealsAreRejected) {
  const OptionsOnlyFormat format;
  for (const char* text : {"", "abc", "1.5x", "nan", "inf", "-inf", "1e999", "0x1p3", "+-1", "1,5"}) {
    const std::string error = error_of(format, {{"offset", text}});
    EXPECT_NE(error.find("toy: option 'offset' expects a finite real number"), std::string::npos)
        << "'" << text << "' -> " << error;
  }
}

TEST(FormatOptions, ValuesOutsideTheDeclaredRangeAreRejectedInclusiveBoundsAccepted) {
  const OptionsOnlyFormat format;
  EXPECT_EQ(resolve_format_options(format, {{"count", "1"}}).at("count"), "1");
  EXPECT_EQ(resolve_format_options(format, {{"count", "10"}}).at("count"), "10");
  EXPECT_EQ(error_of(format, {{"count", "11"}}), "toy: option 'count' must be an integer in [1, 10], got '11'");
  EXPECT_EQ(error_of(format, {{"count", "0"}}), "toy: option 'count' must be an integer in [1, 10], got '0'");
  EXPECT_EQ(resolve_format_options(format, {{"weight", "2"}}).at("weight"), "2");
  EXPECT_EQ(error_of(format, {{"weight", "2.0001"}}), "toy: option 'weight' must be a real in [0, 2], got '2.0001'");
  EXPECT_EQ(error_of(format, {{"weight", "-0.1"}}), "toy: option 'weight' must be a real in [0, 2], got '-0.1'");
  // A spec without min < max has no range.
  EXPECT_EQ(resolve_format_options(format, {{"offset", "-1e300"}}).at("offset"), "-1e+300");
}

TEST(FormatOptions, ChoicesAreExactNamesAndTheErrorListsThem) {
  const OptionsOnlyFormat format;
  EXPECT_EQ(resolve_format_options(format, {{"mode", "exhaustive"}}).at("mode"), "exhaustive");
  EXPECT_EQ(error_of(format, {{"mode", "Fast"}}), "toy: option 'mode' must be one of fast, exhaustive, got 'Fast'");
}

TEST(FormatOptions, TextIsKeptVerbatim) {
  EXPECT_EQ(resolve_format_options(OptionsOnlyFormat(), {{"label", "  a b  "}}).at("label"), "  a b  ");
}

TEST(FormatOptions, SeedIsANonNegativeIntegerUpToTwoToThe53MinusOne) {
  const OptionsOnlyFormat format;
  EXPECT_EQ(resolve_format_options(format, {{"seed", "9007199254740991"}}).at("seed"), "9007199254740991");
  EXPECT_NE(error_of(format, {{"seed", "-1"}}).find("option 'seed' must be an integer in"), std::string::npos);
  EXPECT_NE(error_of(format, {{"seed", "1.5"}}).find("option 'seed' expects an integer"), std::string::npos);
}

TEST(FormatOptions, AFormatDeclaringACommonOptionIsRejected) {
  EXPECT_EQ(error_of(SeedDeclaringFormat(), {}), "seedy: option 'seed' is declared twice");
}

TEST(FormatOptions, AllOptionSpecsAppendsTheCommonOnes) {
  const std::vector<OptionSpec> specs = all_option_specs(OptionsOnlyFormat());
  ASSERT_EQ(specs.size(), 8u);
  EXPECT_EQ(specs.front().name, "count");
  EXPECT_EQ(specs[6].name, "preset");
  EXPECT_EQ(specs[6].default_value, "medium");
  EXPECT_EQ(specs.back().name, "seed");
  EXPECT_EQ(specs.back().default_value, "1");
  ASSERT_EQ(common_option_specs(OptionsOnlyFormat()).size(), 2u);
}

TEST(FormatOptions, TypedAccessorsReadResolvedValues) {
  const FormatOptions resolved =
      resolve_format_options(OptionsOnlyFormat(), {{"count", "9"}, {"weight", "0.75"}, {"flag", "yes"}});
  EXPECT_EQ(option_int(resolved, "count"), 9);
  EXPECT_EQ(option_int(resolved, "seed"), 1);
  EXPECT_EQ(option_real(resolved, "weight"), 0.75);
  EXPECT_EQ(option_real(resolved, "offset"), -1.25);
  EXPECT_TRUE(option_bool(resolved, "flag"));
  EXPECT_EQ(option_text(resolved, "mode"), "fast");
}

TEST(FormatOptions, TypedAccessorsNameTheKeyOnMissingOrMalformedValues) {
  const FormatOptions options = {{"count", "many"}, {"weight", "nan"}, {"flag", "maybe"}};
  const auto message = [](auto&& call) {
    try {
      call();
    } catch (const Error& error) {
      return std::string(error.what());
    }
    return std::string();
  };
  EXPECT_EQ(message([&] { option_int(options, "count"); }), "count: expected an integer, got 'many'");
  EXPECT_EQ(message([&] { option_real(options, "weight"); }), "weight: expected a finite real number, got 'nan'");
  EXPECT_EQ(message([&] { option_bool(options, "flag"); }), "flag: expected a boolean (true/false), got 'maybe'");
  EXPECT_EQ(message([&] { option_text(options, "absent"); }), "absent: option is missing from the resolved option map");
  EXPECT_EQ(message([&] { option_int(options, "absent"); }), "absent: option is missing from the resolved option map");
}

TEST(FormatOptions, OptionTypesHaveStableNames) {
  EXPECT_EQ(to_string(OptionType::integer), "integer");
  EXPECT_EQ(to_string(OptionType::real), "real");
  EXPECT_EQ(to_string(OptionType::boolean), "boolean");
  EXPECT_EQ(to_string(OptionType::text), "text");
  EXPECT_EQ(to_string(OptionType::choice), "choice");
}

}  // namespace
}  // namespace blocklab
