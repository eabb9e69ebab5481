// Cell keys (experiments/cell_key.h): stable for the same inputs, different whenever something that can change a
// result changes, and blind to threads, labels, names and paths.
#include <gtest/gtest.h>

#include <functional>

#include "experiments/cell_key.h"
#include "experiments/sha256.h"
#include "test_experiment_fakes.h"

namespace blocklab {
namespace {

using testing::parse_fake;

const std::string kBase =
    "schema: 1\nname: keys\nimages: [a.pfm]\nmetrics: [fake_mae, {name: fake_peak}]\n"
    "formats:\n  - format: fake_quant\n    label: one\n    options: {step: 0.5}\n";

const ImageIdentity kImage{"hdr/a.pfm", std::string(64, 'a')};

std::string first_key(const std::string& yaml, const ImageIdentity& image = kImage, const Catalog* catalog = nullptr) {
  const ExperimentConfig config = parse_experiment(yaml, "k.yaml", catalog ? *catalog : testing::fake_catalog());
  return cell_key(cell_key_document(config, image, config.treatments.at(0)));
}

void replace_once(std::string& text, const std::string& from, const std::string& to) {
  const std::size_t at = text.find(from);
  ASSERT_NE(at, std::string::npos) << from;
  text.replace(at, from.size(), to);
}

std::string edited(std::string text, const std::string& from, const std::string& to) {
  replace_once(text, from, to);
  return text;
}

TEST(ExperimentCellKey, Sha256MatchesTheFips180KnownAnswers) {
  EXPECT_EQ(sha256_hex("abc"), "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad");
  EXPECT_EQ(sha256_hex(""), "e3b0c44298fc1c149afbf4c8996fb92427ae41e4649b934ca495991b7852b855");
}

TEST(ExperimentCellKey, SameConfigGivesTheSameSixtyFourHexKey) {
  const std::string key = first_key(kBase);
  EXPECT_EQ(key.size(), 64u);
  EXPECT_EQ(key.find_first_not_of("0123456789abcdef"), std::string::npos);
  EXPECT_EQ(first_key(kBase), key);
}

TEST(ExperimentCellKey, DisplayOnlyFieldsDoNotChangeTheKey) {
  const std::string key = first_key(kBase);
  EXPECT_EQ(first_key(edited(kBase, "label: one", "label: two")), key);
  EXPECT_EQ(first_key(edited(kBase, "name: keys", "name: other\ndescription: words")), key);
  EXPECT_EQ(first_key(kBase + "data_root: elsewhere\n"), key);
  // Equivalent spellings resolve to the same canonical option text.
  EXPECT_EQ(first_key(edited(kBase, "step: 0.5", "step: 0.50")), key);
  // Reordering metrics does not change what is computed.
  EXPECT_EQ(first_key(edited(kBase, "[fake_mae, {name: fake_peak}]", "[fake_peak, fake_mae]")), key);
}

TEST(ExperimentCellKey, ThreadCountIsNotPartOfTheKeyDocument) {
  const ExperimentConfig config = parse_fake(kBase);
  const nlohmann::json doc = cell_key_document(config, kImage, config.treatments[0]);
  const std::string text = doc.dump();
  EXPECT_EQ(text.find("thread"), std::string::npos) << text;
  EXPECT_EQ(text.find("one"), std::string::npos) << "labels must not be hashed: " << text;
  EXPECT_EQ(text.find("keys"), std::string::npos) << "the experiment name must not be hashed: " << text;
}

TEST(ExperimentCellKey, EverythingThatCanChangeAResultChangesTheKey) {
  const std::string key = first_key(kBase);
  const std::vector<std::pair<std::string, std::string>> changes = {
      {"option value", edited(kBase, "step: 0.5", "step: 1")},
      {"choice option", edited(kBase, "step: 0.5", "step: 0.5, mode: b")},
      {"seed", kBase + "seed: 2\n"},
      {"input policy", kBase + "input_policy: zero\n"},
      {"metric option", edited(kBase, "[fake_mae,", "[{name: fake_mae, scale: 2},")},
      {"metric set", edited(kBase, "[fake_mae, {name: fake_peak}]", "[fake_mae]")},
      {"save_decoded", kBase + "save_decoded: true\n"},
      {"error maps", kBase + "error_maps: [fake_mae]\n"},
  };
  for (const auto& [what, yaml] : changes) EXPECT_NE(first_key(yaml), key) << what;
  EXPECT_NE(first_key(kBase, ImageIdentity{"hdr/b.pfm", kImage.sha256}), key) << "image path";
  EXPECT_NE(first_key(kBase, ImageIdentity{kImage.relative_path, std::string(64, 'b')}), key) << "image bytes";
}

TEST(ExperimentCellKey, AblationCellsHaveTheirOwnKeys) {
  const ExperimentConfig config = parse_fake(kBase + "ablations:\n  flagged: {flag: true}\n  same: {step: 0.5}\n");
  ASSERT_EQ(config.treatments.size(), 3u);
  const std::string baseline = cell_key(cell_key_document(config, kImage, config.treatments[0]));
  const std::string flagged = cell_key(cell_key_document(config, kImage, config.treatments[1]));
  // "same" patches step to the value it already has: same options, still a distinct (named) cell.
  const std::string same = cell_key(cell_key_document(config, kImage, config.treatments[2]));
  EXPECT_NE(baseline, flagged);
  EXPECT_NE(baseline, same);
  EXPECT_NE(flagged, same);
}

// fake_quant with a bumped revision(): same name and options, different bytes.
class RevisedQuantFormat final : public Format {
 public:
  std::string name() const override { return base_.name(); }
  std::string description() const override { return base_.description(); }
  std::vector<OptionSpec> option_specs() const override { return base_.option_specs(); }
  std::vector<ModeSpec> mode_table() const override { return base_.mode_table(); }
  int block_bytes(const FormatOptions& o) const override { return base_.block_bytes(o); }
  int revision() const override { return 2; }
  EncodedTexture encode(const Image& i, const FormatOptions& o, const CodecContext& c) const override {
    return base_.encode(i, o, c);
  }
  Image decode(const EncodedTexture& t, const CodecContext& c) const override { return base_.decode(t, c); }

 private:
  testing::FakeQuantFormat base_;
};

TEST(ExperimentCellKey, FormatRevisionChangesTheKey) {
  const RevisedQuantFormat revised;
  const Catalog catalog{{&revised}, testing::fake_catalog().metrics};
  EXPECT_NE(first_key(kBase, kImage, &catalog), first_key(kBase));
}

TEST(ExperimentCellKey, EffectiveSeedIsTheResolvedSeedOption) {
  const ExperimentConfig config = parse_fake(kBase + "seed: 12\n");
  EXPECT_EQ(effective_seed(config, config.treatments[0]), 12u);
  const ExperimentConfig own = parse_fake(edited(kBase, "step: 0.5", "step: 0.5, seed: 4") + "seed: 12\n");
  EXPECT_EQ(effective_seed(own, own.treatments[0]), 4u);
}

}  // namespace
}  // namespace blocklab
