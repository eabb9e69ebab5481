// Strict YAML loading of experiment configs (experiments/config.h): every mistake is an Error with file:line:col,
// the YAML path and the valid names, before any work starts.
#include <gtest/gtest.h>

#include <cstdio>
#include <fstream>

#include "core/error.h"
#include "experiments/config.h"
#include "experiments/strict_yaml.h"
#include "test_experiment_fakes.h"

namespace blocklab {
namespace {

using testing::parse_fake;

const char* const kMinimal =
    "schema: 1\n"
    "name: tiny\n"
    "images: [a.pfm]\n"
    "metrics: [fake_mae]\n"
    "formats:\n"
    "  - format: fake_quant\n";

// The message of the Error `yaml` raises (fails the test if it loads).
std::string error_of(const std::string& yaml) {
  try {
    parse_fake(yaml);
  } catch (const Error& e) {
    return e.what();
  }
  ADD_FAILURE() << "config loaded but should have been rejected:\n" << yaml;
  return "";
}

TEST(ExperimentConfig, LoadsMinimalConfigWithDocumentedDefaults) {
  const ExperimentConfig config = parse_fake(kMinimal);
  EXPECT_EQ(config.name, "tiny");
  EXPECT_EQ(config.images, std::vector<std::string>{"a.pfm"});
  EXPECT_EQ(config.input_policy, InputPolicy::clamp);
  EXPECT_FALSE(config.seed_given);
  EXPECT_FALSE(config.save_decoded);
  EXPECT_TRUE(config.error_maps.empty());
  ASSERT_EQ(config.metrics.size(), 1u);
  EXPECT_EQ(config.metrics[0].name, "fake_mae");
  ASSERT_EQ(config.variants.size(), 1u);
  EXPECT_EQ(config.variants[0].label, "fake_quant");
  EXPECT_EQ(config.variants[0].resolved.at("step"), "0.25");   // default filled by resolve_format_options
  ASSERT_EQ(config.treatments.size(), 1u);
  EXPECT_EQ(config.treatments[0].ablation, "baseline");
}

TEST(ExperimentConfig, ReadsEveryOptionalKey) {
  const ExperimentConfig config = parse_fake(
      "schema: 1\nname: full.run-2\ndescription: \"all keys\"\ndata_root: some/dir\n"
      "images: [a.pfm, \"b/*.pfm\"]\ninput_policy: zero\nseed: 7\n"
      "metrics:\n  - fake_mae\n  - {name: fake_peak}\n"
      "formats:\n  - format: fake_quant\n    label: q\n    options: {step: 0.5}\n"
      "ablations:\n  flagged: {flag: true}\nsave_decoded: true\nerror_maps: [fake_mae]\n");
  EXPECT_EQ(config.description, "all keys");
  EXPECT_EQ(config.data_root, "some/dir");
  EXPECT_EQ(config.input_policy, InputPolicy::zero);
  EXPECT_TRUE(config.seed_given);
  EXPECT_EQ(config.seed, 7);
  EXPECT_EQ(config.metric_names(), (std::vector<std::string>{"fake_mae", "fake_peak"}));
  EXPECT_EQ(config.variants[0].label, "q");
  EXPECT_EQ(config.variants[0].resolved.at("seed"), "7");   // the experiment seed reaches the format
  EXPECT_TRUE(config.save_decoded);
  EXPECT_EQ(config.error_maps, std::vector<std::string>{"fake_mae"});
  ASSERT_EQ(config.ablations.size(), 1u);
  EXPECT_EQ(config.ablations[0].patch.at("flag"), "true");
}

TEST(ExperimentConfig, MetricOptionsAreReadFromTheMetricMap) {
  const ExperimentConfig config = parse_fake(
      "schema: 1\nname: m\nimages: [a.pfm]\nmetrics:\n  - {name: fake_mae, scale: 2.5}\n"
      "formats: [{format: fake_quant}]\n");
  EXPECT_EQ(config.metrics[0].options.at("scale"), "2.5");
}

TEST(ExperimentConfig, UnknownTopLevelKeyGivesFileLineColumnAndValidKeys) {
  const std::string message = error_of(std::string(kMinimal) + "imagez: [b.pfm]\n");
  EXPECT_NE(message.find("test.yaml:7:1: unknown key 'imagez' in the top level; valid keys: schema, name,"),
            std::string::npos) << message;
}

TEST(ExperimentConfig, MisspelledKeyInsideFormatEntryGivesItsLine) {
  const std::string message = error_of(
      "schema: 1\nname: bad\nimages: [a.pfm]\nmetrics: [fake_mae]\nformats:\n  - format: fake_quant\n"
      "    optoins: {seed: 2}\n");
  EXPECT_NE(message.find("test.yaml:7:5: unknown key 'optoins' in formats[0]; valid keys: format, label, options"),
            std::string::npos) << message;
}

TEST(ExperimentConfig, DuplicateTopLevelKeyIsRejectedWithBothLines) {
  const std::string message = error_of(std::string(kMinimal) + "name: again\n");
  EXPECT_NE(message.find("test.yaml:7:1: duplicate key 'name' in the top level (first at line 2)"), std::string::npos)
      << message;
}

TEST(ExperimentConfig, DuplicateOptionKeyIsRejected) {
  const std::string message = error_of(
      "schema: 1\nname: d\nimages: [a.pfm]\nmetrics: [fake_mae]\nformats:\n"
      "  - format: fake_quant\n    options:\n      step: 0.5\n      step: 1\n");
  EXPECT_NE(message.find("test.yaml:9:7: duplicate key 'step' in formats[0].options"), std::string::npos) << message;
}

TEST(ExperimentConfig, MissingRequiredKeyNamesTheEnclosingMap) {
  EXPECT_NE(error_of("schema: 1\nname: x\nimages: [a.pfm]\nmetrics: [fake_mae]\n")
                .find("test.yaml:1:1: missing required key 'formats' in the top level"),
            std::string::npos);
  const std::string entry = error_of(
      "schema: 1\nname: x\nimages: [a.pfm]\nmetrics: [fake_mae]\nformats:\n  - label: nothing\n");
  EXPECT_NE(entry.find("test.yaml:6:5: missing required key 'format' in formats[0]"), std::string::npos) << entry;
  const std::string metric = error_of(
      "schema: 1\nname: x\nimages: [a.pfm]\nmetrics:\n  - {scale: 2}\nformats: [{format: fake_quant}]\n");
  EXPECT_NE(metric.find("missing required key 'name' in metrics[0]"), std::string::npos) << metric;
}

TEST(ExperimentConfig, WrongTypesAreRejected) {
  EXPECT_NE(error_of("schema: 1\nname: x\nimages: a.pfm\nmetrics: [fake_mae]\nformats: [{format: fake_quant}]\n")
                .find("test.yaml:3:9: images must be a list"),
            std::string::npos);
  EXPECT_NE(error_of(std::string(kMinimal) + "seed: 1.5\n").find("seed must be an integer, got '1.5'"),
            std::string::npos);
  EXPECT_NE(error_of(std::string(kMinimal) + "seed: \"3\"\n").find("seed must be an integer"), std::string::npos);
  EXPECT_NE(error_of(std::string(kMinimal) + "save_decoded: 1\n").find("save_decoded must be true or false"),
            std::string::npos);
  EXPECT_NE(error_of(std::string(kMinimal) + "description: [a, b]\n").find("description must be a single value"),
            std::string::npos);
  EXPECT_NE(error_of(std::string(kMinimal) + "seed:\n").find("seed has no value"), std::string::npos);
  EXPECT_NE(error_of(std::string(kMinimal) + "seed: -1\n").find("seed must be >= 0"), std::string::npos);
  EXPECT_NE(error_of(std::string(kMinimal) + "seed: 99999999999999999999\n").find("out of range"), std::string::npos);
}

TEST(ExperimentConfig, UnquotedYaml11BooleanWordsAreRejectedEverywhere) {
  EXPECT_NE(error_of(std::string(kMinimal) + "save_decoded: yes\n")
                .find("save_decoded: 'yes' is a YAML 1.1 boolean; write true/false, or quote it"),
            std::string::npos);
  EXPECT_NE(error_of("schema: 1\nname: on\nimages: [a.pfm]\nmetrics: [fake_mae]\nformats: [{format: fake_quant}]\n")
                .find("test.yaml:2:7: name: 'on' is a YAML 1.1 boolean"),
            std::string::npos);
  EXPECT_NE(error_of("schema: 1\nname: x\nimages: [a.pfm]\nmetrics: [fake_mae]\n"
                     "formats: [{format: fake_quant, options: {flag: n}}]\n")
                .find("formats[0].options.flag: 'n' is a YAML 1.1 boolean"),
            std::string::npos);
  // Quoted, the word is text and goes to the format's own parser (which accepts "yes" for a boolean).
  const ExperimentConfig quoted = parse_fake(
      "schema: 1\nname: x\nimages: [a.pfm]\nmetrics: [fake_mae]\n"
      "formats: [{format: fake_quant, options: {flag: \"yes\"}}]\n");
  EXPECT_EQ(quoted.variants[0].resolved.at("flag"), "true");
}

TEST(ExperimentConfig, OctalLookingNumbersAreRejectedUnlessQuoted) {
  EXPECT_NE(error_of(std::string(kMinimal) + "seed: 042\n").find("seed: '042' has a leading zero"),
            std::string::npos);
  EXPECT_NE(error_of("schema: 1\nname: x\nimages: [a.pfm]\nmetrics: [fake_mae]\n"
                     "formats: [{format: fake_quant, options: {seed: 0x1F}}]\n")
                .find("'0x1F' has a leading zero"),
            std::string::npos);
  EXPECT_NE(error_of("schema: 1\nname: 007\nimages: [a.pfm]\nmetrics: [fake_mae]\nformats: [{format: fake_quant}]\n")
                .find("name: '007' has a leading zero"),
            std::string::npos);
  // Ordinary decimals with a zero in front of the point are fine.
  EXPECT_NO_THROW(parse_fake("schema: 1\nname: x\nimages: [a.pfm]\nmetrics: [fake_mae]\n"
                             "formats: [{format: fake_quant, options: {step: 0.5}}]\n"));
  EXPECT_NO_THROW(parse_fake("schema: 1\nname: \"007\"\nimages: [a.pfm]\nmetrics: [fake_mae]\n"
                             "formats: [{format: fake_quant}]\n"));
}

TEST(ExperimentConfig, Yaml11SurpriseDetectorsClassifyWords) {
  for (const char* word : {"y", "Y", "yes", "YES", "No", "on", "OFF"}) EXPECT_TRUE(is_yaml11_boolean_word(word)) << word;
  for (const char* word : {"true", "false", "yess", "onn", "o"}) EXPECT_FALSE(is_yaml11_boolean_word(word)) << word;
  for (const char* text : {"042", "-07", "+01", "0x1F", "0o17", "0b101", "00"}) EXPECT_TRUE(is_radix_looking_number(text)) << text;
  for (const char* text : {"0", "42", "0.5", "-0.25", "0e3", "10", "x0"}) EXPECT_FALSE(is_radix_looking_number(text)) << text;
}

TEST(ExperimentConfig, UnknownFormatNameListsTheValidFormats) {
  const std::string message = error_of(
      "schema: 1\nname: x\nimages: [a.pfm]\nmetrics: [fake_mae]\nformats:\n  - format: fake_qant\n");
  EXPECT_NE(message.find("test.yaml:6:13: unknown format 'fake_qant' in formats[0]; valid formats: fake_quant, "
                         "fake_broken"),
            std::string::npos) << message;
}

TEST(ExperimentConfig, UnknownFormatOptionListsTheValidOptions) {
  const std::string message = error_of(
      "schema: 1\nname: x\nimages: [a.pfm]\nmetrics: [fake_mae]\nformats:\n  - format: fake_quant\n"
      "    options:\n      stepp: 1\n");
  EXPECT_NE(message.find("test.yaml:8:7: unknown option 'stepp' for format 'fake_quant' in formats[0].options; "
                         "valid options: step, mode, flag, preset, seed"),
            std::string::npos) << message;
}

TEST(ExperimentConfig, BadOptionValueIsRejectedByTheFormatResolver) {
  const std::string message = error_of(
      "schema: 1\nname: x\nimages: [a.pfm]\nmetrics: [fake_mae]\nformats:\n"
      "  - format: fake_quant\n    options: {step: [0.5, abc]}\n");
  EXPECT_NE(message.find("test.yaml:6:5: formats[0] (fake_quant[step=abc])"), std::string::npos) << message;
  EXPECT_NE(message.find("option 'step' expects a finite real number, got 'abc'"), std::string::npos) << message;
}

TEST(ExperimentConfig, UnknownMetricAndMetricOptionListTheValidNames) {
  const std::string metric = error_of(
      "schema: 1\nname: x\nimages: [a.pfm]\nmetrics: [fake_mae, fake_pek]\nformats: [{format: fake_quant}]\n");
  EXPECT_NE(metric.find("test.yaml:4:21: unknown metric 'fake_pek' in metrics[1]; valid metrics: fake_mae, fake_peak"),
            std::string::npos) << metric;
  const std::string option = error_of(
      "schema: 1\nname: x\nimages: [a.pfm]\nmetrics:\n  - {name: fake_mae, scael: 2}\nformats: [{format: fake_quant}]\n");
  EXPECT_NE(option.find("unknown option 'scael' for metric 'fake_mae' in metrics[0]; valid options: column, scale"),
            std::string::npos) << option;
  const std::string none = error_of(
      "schema: 1\nname: x\nimages: [a.pfm]\nmetrics:\n  - {name: fake_peak, scale: 2}\nformats: [{format: fake_quant}]\n");
  EXPECT_EQ(none.substr(none.size() - std::string("valid options: column").size()), "valid options: column") << none;
}

TEST(ExperimentConfig, BadMetricOptionValueIsCaughtByADryEvaluationBeforeWork) {
  const std::string message = error_of(
      "schema: 1\nname: x\nimages: [a.pfm]\nmetrics:\n  - {name: fake_mae, scale: big}\nformats: [{format: fake_quant}]\n");
  EXPECT_NE(message.find("test.yaml:5:5: metric 'fake_mae': fake_mae: option 'scale' must be a number"),
            std::string::npos) << message;
}

TEST(ExperimentConfig, MetricListedTwiceWithoutAColumnLabelIsRejected) {
  const std::string message = error_of("schema: 1\nname: x\nimages: [a.pfm]\nmetrics: [fake_mae, {name: fake_mae, scale: 2}]\n"
                                       "formats: [{format: fake_quant}]\n");
  EXPECT_NE(message.find("metric column 'fake_mae' is listed twice in metrics[1]"), std::string::npos) << message;
  EXPECT_NE(message.find("give the second one `column: <name>`"), std::string::npos) << message;
}

TEST(ExperimentConfig, ColumnLabelLetsOneMetricAppearTwiceWithDifferentOptions) {
  const ExperimentConfig config = parse_fake(
      "schema: 1\nname: x\nimages: [a.pfm]\nmetrics: [fake_mae, {name: fake_mae, column: mae_x2, scale: 2}]\n"
      "formats: [{format: fake_quant}]\n");
  ASSERT_EQ(config.metrics.size(), 2u);
  EXPECT_EQ(config.metrics[0].column(), "fake_mae");
  EXPECT_EQ(config.metrics[1].column(), "mae_x2");
  EXPECT_EQ(config.metrics[1].name, "fake_mae");
  EXPECT_EQ(config.metrics[1].options.at("scale"), "2");   // `column` is not passed to the metric as an option
  EXPECT_EQ(config.metrics[1].options.count("column"), 0u);
  EXPECT_EQ(config.metric_names(), (std::vector<std::string>{"fake_mae", "mae_x2"}));
}

TEST(ExperimentConfig, CropNeedsPositiveSizesAndBothOrNeitherOfXAndY) {
  const std::string base = "schema: 1\nname: x\nimages: [a.pfm]\nmetrics: [fake_mae]\nformats: [{format: fake_quant}]\n";
  const ExperimentConfig centred = parse_fake(base + "crop: {width: 64, height: 32}\n");
  EXPECT_TRUE(centred.crop.enabled);
  EXPECT_TRUE(centred.crop.centred);
  EXPECT_EQ(centred.crop.width, 64);
  EXPECT_EQ(centred.crop.height, 32);
  const ExperimentConfig at = parse_fake(base + "crop: {x: 8, y: 0, width: 4, height: 4}\n");
  EXPECT_FALSE(at.crop.centred);
  EXPECT_EQ(at.crop.x, 8);
  EXPECT_FALSE(parse_fake(base).crop.enabled);
  EXPECT_NE(error_of(base + "crop: {width: 64}\n").find("test.yaml:6:7: missing required key 'height'"),
            std::string::npos) << error_of(base + "crop: {width: 64}\n");
  EXPECT_NE(error_of(base + "crop: {width: 0, height: 4}\n").find("crop.width must be in [1, 1048576], got 0"),
            std::string::npos);
  EXPECT_NE(error_of(base + "crop: {x: 1, width: 4, height: 4}\n").find("crop needs both x and y, or neither"),
            std::string::npos);
  EXPECT_NE(error_of(base + "crop: {widht: 4, height: 4}\n").find("unknown key 'widht'"), std::string::npos)
      << error_of(base + "crop: {widht: 4, height: 4}\n");
}

TEST(ExperimentConfig, MalformedYamlGivesFileAndLine) {
  const std::string message = error_of("schema: 1\nname: [unclosed\n");
  EXPECT_EQ(message.rfind("test.yaml:", 0), 0u) << message;
  EXPECT_NE(message.find("YAML syntax error"), std::string::npos) << message;
  const std::string indent = error_of("schema: 1\n  name: x\n");
  EXPECT_NE(indent.find("test.yaml:2:"), std::string::npos) << indent;
}

TEST(ExperimentConfig, SchemaVersionOtherThanOneIsRejected) {
  EXPECT_NE(error_of("schema: 2\nname: x\nimages: [a.pfm]\nmetrics: [fake_mae]\nformats: [{format: fake_quant}]\n")
                .find("test.yaml:1:9: schema 2 is not supported (this blocklab reads 1)"),
            std::string::npos);
}

TEST(ExperimentConfig, NamesAreRestrictedToPortableCharacters) {
  EXPECT_NE(error_of("schema: 1\nname: a b\nimages: [a.pfm]\nmetrics: [fake_mae]\nformats: [{format: fake_quant}]\n")
                .find("name: 'a b' is not a valid name"),
            std::string::npos);
  EXPECT_NE(error_of("schema: 1\nname: ../up\nimages: [a.pfm]\nmetrics: [fake_mae]\nformats: [{format: fake_quant}]\n")
                .find("is not a valid name"),
            std::string::npos);
}

TEST(ExperimentConfig, EmptyListsAndEmptyConfigAreRejected) {
  EXPECT_NE(error_of("").find("test.yaml: the config is empty"), std::string::npos);
  EXPECT_NE(error_of("schema: 1\nname: x\nimages: []\nmetrics: [fake_mae]\nformats: [{format: fake_quant}]\n")
                .find("images must list at least one image"),
            std::string::npos);
  EXPECT_NE(error_of("schema: 1\nname: x\nimages: [a.pfm]\nmetrics: []\nformats: [{format: fake_quant}]\n")
                .find("metrics must list at least one metric"),
            std::string::npos);
  EXPECT_NE(error_of("schema: 1\nname: x\nimages: [a.pfm]\nmetrics: [fake_mae]\nformats: []\n")
                .find("formats must list at least one format entry"),
            std::string::npos);
}

TEST(ExperimentConfig, AbsoluteImagePathsAreRejected) {
  EXPECT_NE(error_of("schema: 1\nname: x\nimages: [/etc/a.pfm]\nmetrics: [fake_mae]\nformats: [{format: fake_quant}]\n")
                .find("images[0]: '/etc/a.pfm' must be relative to the data root"),
            std::string::npos);
}

TEST(ExperimentConfig, ErrorMapsMustNameAConfiguredMetric) {
  EXPECT_NE(error_of(std::string(kMinimal) + "error_maps: [fake_peak]\n")
                .find("error_maps[0]: 'fake_peak' is not one of this config's metrics (fake_mae)"),
            std::string::npos);
}

TEST(ExperimentConfig, UnknownInputPolicyIsRejectedWithItsLine) {
  const std::string message = error_of(std::string(kMinimal) + "input_policy: ignore\n");
  EXPECT_NE(message.find("test.yaml:7:15: input_policy:"), std::string::npos) << message;
  EXPECT_NE(message.find("ignore"), std::string::npos) << message;
}

TEST(ExperimentConfig, LoadExperimentReadsAFileAndNamesItInErrors) {
  const std::string path = ::testing::TempDir() + "experiment_config_test.yaml";
  {
    std::ofstream out(path);
    out << kMinimal << "bogus: 1\n";
  }
  try {
    load_experiment(path, testing::fake_catalog());
    FAIL() << "expected an error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find(path + ":7:1: unknown key 'bogus'"), std::string::npos) << e.what();
  }
  std::remove(path.c_str());
  EXPECT_THROW(load_experiment(path, testing::fake_catalog()), Error);   // missing file
}

}  // namespace
}  // namespace blocklab
