// Sweep and ablation expansion (experiments/sweep.h): counts, order, labels, seeds, and the errors for sweeps that
// would produce duplicate or empty cells.
#include <gtest/gtest.h>

#include "core/error.h"
#include "experiments/sweep.h"
#include "test_experiment_fakes.h"

namespace blocklab {
namespace {

using testing::parse_fake;

std::string config_with(const std::string& formats, const std::string& extra = "") {
  return "schema: 1\nname: s\nimages: [a.pfm]\nmetrics: [fake_mae]\nformats:\n" + formats + extra;
}

std::string error_of(const std::string& yaml) {
  try {
    parse_fake(yaml);
  } catch (const Error& e) {
    return e.what();
  }
  ADD_FAILURE() << "config loaded but should have been rejected:\n" << yaml;
  return "";
}

TEST(ExperimentSweep, EntryWithoutListsIsOneVariant) {
  const ExperimentConfig config = parse_fake(config_with("  - format: fake_quant\n    options: {step: 0.5}\n"));
  ASSERT_EQ(config.variants.size(), 1u);
  EXPECT_EQ(config.variants[0].label, "fake_quant");
  EXPECT_EQ(config.variants[0].resolved.at("step"), "0.5");
}

TEST(ExperimentSweep, TwoAxesExpandToTheirProductWithTheFirstOptionOutermost) {
  const ExperimentConfig config =
      parse_fake(config_with("  - format: fake_quant\n    options: {step: [0.5, 1], mode: [a, b]}\n"));
  ASSERT_EQ(config.variants.size(), 4u);
  const std::vector<std::pair<std::string, std::string>> expected = {{"0.5", "a"}, {"0.5", "b"}, {"1", "a"}, {"1", "b"}};
  for (std::size_t i = 0; i < expected.size(); ++i) {
    EXPECT_EQ(config.variants[i].resolved.at("step"), expected[i].first) << i;
    EXPECT_EQ(config.variants[i].resolved.at("mode"), expected[i].second) << i;
  }
  EXPECT_EQ(config.variants[0].label, "fake_quant[step=0.5,mode=a]");
  EXPECT_EQ(config.variants[3].label, "fake_quant[step=1,mode=b]");
}

TEST(ExperimentSweep, ThreeAxesCountIsTheProductAndEntriesKeepFileOrder) {
  const ExperimentConfig config = parse_fake(config_with(
      "  - format: fake_quant\n    label: first\n    options: {step: [0.5, 1], mode: [a, b], seed: [1, 2, 3]}\n"
      "  - format: fake_broken\n"));
  ASSERT_EQ(config.variants.size(), 2u * 2u * 3u + 1u);
  EXPECT_EQ(variant_count(config.formats[0]), 12u);
  for (std::size_t i = 0; i < 12; ++i) EXPECT_EQ(config.variants[i].entry_index, 0u);
  EXPECT_EQ(config.variants[12].entry_index, 1u);
  EXPECT_EQ(config.variants[12].label, "fake_broken");
  // The last axis (seed) varies fastest.
  EXPECT_EQ(config.variants[0].label, "first[step=0.5,mode=a,seed=1]");   // labels keep the written option order
  EXPECT_EQ(config.variants[1].resolved.at("seed"), "2");
  EXPECT_EQ(config.variants[2].resolved.at("seed"), "3");
  EXPECT_EQ(config.variants[3].resolved.at("mode"), "b");
  EXPECT_EQ(config.variants[3].resolved.at("seed"), "1");
}

TEST(ExperimentSweep, ScalarOptionsDoNotAppearInTheLabelButOneElementListsDo) {
  const ExperimentConfig config =
      parse_fake(config_with("  - format: fake_quant\n    options: {step: 0.5, mode: [b]}\n"));
  ASSERT_EQ(config.variants.size(), 1u);
  EXPECT_EQ(config.variants[0].label, "fake_quant[mode=b]");
}

TEST(ExperimentSweep, ExperimentSeedReachesEveryEntryThatDoesNotSetItsOwn) {
  const ExperimentConfig config = parse_fake(config_with(
      "  - format: fake_quant\n  - format: fake_quant\n    label: own_seed\n    options: {seed: 9, step: 1}\n",
      "seed: 5\n"));
  EXPECT_EQ(config.variants[0].resolved.at("seed"), "5");
  EXPECT_EQ(config.variants[1].resolved.at("seed"), "9");
  const ExperimentConfig without = parse_fake(config_with("  - format: fake_quant\n"));
  EXPECT_EQ(without.variants[0].resolved.at("seed"), "1");   // the format's default
}

TEST(ExperimentSweep, EmptyOrRepeatingSweepListsAreRejected) {
  EXPECT_NE(error_of(config_with("  - format: fake_quant\n    options: {step: []}\n"))
                .find("formats[0].options.step: an empty list sweeps over nothing"),
            std::string::npos);
  EXPECT_NE(error_of(config_with("  - format: fake_quant\n    options: {step: [1, 2, 1]}\n"))
                .find("formats[0].options.step[2]: value '1' appears twice in the sweep"),
            std::string::npos);
}

TEST(ExperimentSweep, VariantsThatResolveToTheSameOptionsAreRejected) {
  // 0.25 is the default step, and "0.250" resolves to the same canonical "0.25".
  const std::string message = error_of(config_with(
      "  - format: fake_quant\n  - format: fake_quant\n    label: again\n    options: {step: 0.250}\n"));
  EXPECT_NE(message.find("formats[1] (again) repeats formats[0] (fake_quant): both are fake_quant"), std::string::npos)
      << message;
}

TEST(ExperimentSweep, TwoEntriesWithTheSameLabelAreRefused) {
  const std::string message = error_of(config_with(
      "  - format: fake_quant\n    label: q\n    options: {step: 0.5}\n"
      "  - format: fake_quant\n    label: q\n    options: {step: 1}\n"));
  EXPECT_NE(message.find("formats[1] has the label 'q', already used by formats[0]: results would be ambiguous"),
            std::string::npos) << message;
  // Unlabelled entries of one format share the format name as label.
  EXPECT_NE(error_of(config_with("  - format: fake_quant\n    options: {step: 0.5}\n"
                                 "  - format: fake_quant\n    options: {step: 1}\n"))
                .find("has the label 'fake_quant'"),
            std::string::npos);
  // Swept variants differ by their "[k=v]" suffix, so one entry never collides with itself.
  EXPECT_EQ(parse_fake(config_with("  - format: fake_quant\n    label: q\n    options: {step: [0.5, 1]}\n"))
                .variants.size(),
            2u);
}

TEST(ExperimentSweep, SweepAboveTheCellLimitIsRefusedFromTheListLengthsNamingEachList) {
  // 1000 x 1000 x 3 modes x (baseline + 1 ablation) = 6,000,000 treatments: refused from the list lengths, before
  // any value is resolved (step 1000.5 and mode c would be rejected later).
  std::string steps, seeds;
  for (int i = 1; i <= 1000; ++i) {
    steps += (i > 1 ? ", " : "") + std::to_string(i) + ".5";
    seeds += (i > 1 ? ", " : "") + std::to_string(i);
  }
  const std::string yaml = config_with("  - format: fake_quant\n    options: {step: [" + steps + "], seed: [" + seeds +
                                           "], mode: [a, b, c]}\n",
                                       "ablations:\n  flagged: {flag: true}\n");
  const std::string message = error_of(yaml);
  EXPECT_NE(message.find("test.yaml: the experiment expands to 6000000 cells, above the limit of 100000 (raise it "
                         "with --max-cells N): formats[0] fake_quant: step (1000) x seed (1000) x mode (3) x "
                         "(baseline + 1 ablation) = 6000000; total 6000000 treatments x at least 1 image"),
            std::string::npos) << message;
}

TEST(ExperimentSweep, CellLimitCountsImagePatternsAndCanBeRaised) {
  const std::string yaml =
      "schema: 1\nname: s\nimages: [a.pfm, b.pfm]\nmetrics: [fake_mae]\nformats:\n"
      "  - format: fake_quant\n    options: {step: [0.5, 1, 2]}\n";
  try {
    parse_experiment(yaml, "test.yaml", testing::fake_catalog(), 5);
    ADD_FAILURE() << "3 variants x 2 images is above a limit of 5";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("6 cells, above the limit of 5"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("x at least 2 images"), std::string::npos) << e.what();
  }
  EXPECT_EQ(parse_experiment(yaml, "test.yaml", testing::fake_catalog(), 6).variants.size(), 3u);
}

TEST(ExperimentSweep, SweepSizeOverflowSaturatesInsteadOfWrapping) {
  // 10 axes of 100 values: 10^20 variants, more than 2^64.
  ExperimentConfig config;
  config.source_path = "test.yaml";
  FormatEntry entry;
  entry.format = "fake_quant";
  for (int a = 0; a < 10; ++a) {
    OptionAxis axis;
    axis.key = "axis" + std::to_string(a);
    axis.swept = true;
    axis.values.assign(100, "v");
    entry.options.push_back(axis);
  }
  config.formats.push_back(entry);
  const SweepSize size = sweep_size(config, testing::fake_catalog());
  EXPECT_EQ(size.treatments, UINT64_MAX);
  try {
    check_cell_limit(config, size, 1, "1 image", kDefaultMaxCells);
    ADD_FAILURE() << "not refused";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("more than 18446744073709551614 cells"), std::string::npos) << e.what();
  }
}

TEST(ExperimentSweep, EachAblationAddsOneTreatmentPerVariantAfterItsBaseline) {
  const ExperimentConfig config = parse_fake(config_with(
      "  - format: fake_quant\n    options: {step: [0.5, 1]}\n",
      "ablations:\n  flagged: {flag: true}\n  coarse: {step: 2}\n"));
  ASSERT_EQ(config.treatments.size(), 6u);
  const std::vector<std::pair<std::size_t, std::string>> expected = {
      {0, "baseline"}, {0, "flagged"}, {0, "coarse"}, {1, "baseline"}, {1, "flagged"}, {1, "coarse"}};
  for (std::size_t i = 0; i < expected.size(); ++i) {
    EXPECT_EQ(config.treatments[i].variant_index, expected[i].first) << i;
    EXPECT_EQ(config.treatments[i].ablation, expected[i].second) << i;
  }
  EXPECT_EQ(config.treatments[1].resolved.at("flag"), "true");
  EXPECT_EQ(config.treatments[1].resolved.at("step"), "0.5");   // the rest of the variant is kept
  EXPECT_EQ(config.treatments[2].resolved.at("step"), "2");     // an ablation overrides a swept value
  EXPECT_TRUE(config.treatments[0].applied_patch.empty());
  EXPECT_EQ(config.treatments[2].applied_patch, (FormatOptions{{"step", "2"}}));
}

TEST(ExperimentSweep, AblationOnlyPatchesFormatsThatDeclareItsOptions) {
  const ExperimentConfig config = parse_fake(config_with(
      "  - format: fake_quant\n  - format: fake_broken\n", "ablations:\n  flagged: {flag: true, seed: 3}\n"));
  ASSERT_EQ(config.treatments.size(), 4u);
  EXPECT_EQ(config.treatments[1].applied_patch, (FormatOptions{{"flag", "true"}, {"seed", "3"}}));
  // fake_broken has only the common `seed`: it gets that part of the patch.
  EXPECT_EQ(config.treatments[3].ablation, "flagged");
  EXPECT_EQ(config.treatments[3].applied_patch, (FormatOptions{{"seed", "3"}}));

  const ExperimentConfig only_flag = parse_fake(config_with(
      "  - format: fake_quant\n  - format: fake_broken\n", "ablations:\n  flagged: {flag: true}\n"));
  // Nothing of the patch applies to fake_broken: no repeated baseline cell for it.
  ASSERT_EQ(only_flag.treatments.size(), 3u);
  EXPECT_EQ(only_flag.treatments[2].variant_index, 1u);
  EXPECT_EQ(only_flag.treatments[2].ablation, "baseline");
}

TEST(ExperimentSweep, AblationErrorsNameTheAblation) {
  EXPECT_NE(error_of(config_with("  - format: fake_broken\n", "ablations:\n  typo: {flagg: true}\n"))
                .find("ablations.typo: option 'flagg' is not declared by any format of this config (fake_broken)"),
            std::string::npos);
  EXPECT_NE(error_of(config_with("  - format: fake_quant\n", "ablations:\n  baseline: {flag: true}\n"))
                .find("'baseline' is reserved"),
            std::string::npos);
  EXPECT_NE(error_of(config_with("  - format: fake_quant\n", "ablations:\n  sweep: {step: [1, 2]}\n"))
                .find("ablations.sweep.step: an ablation is one patch"),
            std::string::npos);
  EXPECT_NE(error_of(config_with("  - format: fake_quant\n", "ablations:\n  bad: {step: huge}\n"))
                .find("ablations.bad on fake_quant: fake_quant: option 'step' expects a finite real number"),
            std::string::npos);
  EXPECT_NE(error_of(config_with("  - format: fake_quant\n", "ablations:\n  empty: {}\n"))
                .find("ablations.empty is an empty patch"),
            std::string::npos);
  EXPECT_NE(error_of(config_with("  - format: fake_quant\n", "ablations:\n  a: {flag: true}\n  a: {step: 1}\n"))
                .find("duplicate key 'a' in ablations"),
            std::string::npos);
}

TEST(ExperimentSweep, ExpandFormatEntryAloneFollowsTheSameRules) {
  const testing::FakeQuantFormat format;
  FormatEntry entry;
  entry.format = "fake_quant";
  entry.label = "q";
  entry.where = "x.yaml:1:1";
  entry.options = {{"mode", {"a", "b"}, true}, {"step", {"1", "2", "4"}, true}};
  const std::vector<FormatVariant> variants = expand_format_entry(entry, 3, format, true, 11);
  ASSERT_EQ(variants.size(), 6u);
  EXPECT_EQ(variants[0].label, "q[mode=a,step=1]");
  EXPECT_EQ(variants[5].label, "q[mode=b,step=4]");
  for (const FormatVariant& v : variants) {
    EXPECT_EQ(v.entry_index, 3u);
    EXPECT_EQ(v.resolved.at("seed"), "11");
  }
}

}  // namespace
}  // namespace blocklab
